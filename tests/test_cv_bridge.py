"""rostui's cv_bridge converts images as Debian's does: every encoding pair, both ways, errors word for word.

tests/cv_bridge_compare/scenarios.py makes random images for every named encoding (rgb, bgr, rgba, bgra,
mono, bayer, yuv422, 8 and 16 bits) and generic ones (``32FC1``, ``8SC1``...), turns each into an Image
message and back into every other encoding, and tries big-endian data, malformed inputs and a PNG round
trip. It runs unchanged under Debian's python3-cv-bridge (with Debian's OpenCV) and under `rostui python`
(numpy, and OpenCV from pip where a conversion computes colour): every array is byte-equal (by digest)
and every error the same.
"""

from __future__ import annotations

import subprocess

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "cv_bridge_compare" / "scenarios.py"


@pytest.mark.parametrize("seed", [5, 6])
def test_every_conversion_equals_debians(seed: int) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import cv_bridge"], capture_output=True).returncode == 0,
              "cv_bridge (Debian python3-cv-bridge)")
    theirs = subprocess.run([SYSTEM_PYTHON, str(SCRIPT), str(seed)], capture_output=True, text=True, timeout=120)
    ours = subprocess.run(rostui_cmd("python", "--rostui", str(SCRIPT), str(seed)), capture_output=True, text=True,
                          timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    answers = theirs.stdout.splitlines()
    assert len(answers) > 900 and sum('"err"' in a for a in answers) > 100
    assert ours.stdout.splitlines() == answers
