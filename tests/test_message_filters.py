"""rostui's message_filters lets through what Debian's does: the same sets, in the same order, the same warnings.

tests/message_filters_compare/scenarios.py pushes random streams of stamped messages (equal stamps, stamps a
few milliseconds apart, ROS time jumping back) through a Cache, a TimeSynchronizer and an
ApproximateTimeSynchronizer sharing their inputs, asks the cache for intervals and neighbours, and feeds a
message without a header. It runs unchanged under Debian's python3-message-filters and under `rostui python`;
both must print the same lines, on stdout and on stderr.
"""

from __future__ import annotations

import subprocess

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "message_filters_compare" / "scenarios.py"


@pytest.mark.parametrize("seed", [3, 4])
def test_random_streams_give_the_same_sets_as_debians(seed: int) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import message_filters"], capture_output=True).returncode == 0,
              "message_filters (Debian python3-message-filters)")
    args = [str(SCRIPT), str(seed), "40"]
    theirs = subprocess.run([SYSTEM_PYTHON, *args], capture_output=True, text=True, timeout=120)
    ours = subprocess.run(rostui_cmd("python", "--rostui", *args), capture_output=True, text=True, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert '"approx"' in theirs.stdout and '"exact"' in theirs.stdout and '"cache"' in theirs.stdout
    assert ours.stdout.splitlines() == theirs.stdout.splitlines()
    assert ours.stderr.splitlines() == theirs.stderr.splitlines()
