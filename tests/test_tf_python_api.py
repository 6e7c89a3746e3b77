"""tf's own test of its Python API passes under `rostui python` and prints what it prints under Debian's tf.

tests/python_compat/real/geometry/tf/test/testPython.py (ros/geometry, unmodified) exercises tf.Transformer
(set, look up, wait with and without a listener thread, chain, common time, frame listings, twists),
subclassing it, and TransformerROS on points, quaternions and point clouds, run by rostest's deprecated
``unitrun`` with rosunit's report. Both runs must print the same lines: the deprecation warning, the
results file, tf2's warnings about repeated data, one ``[Testcase: ...] ... ok`` per test and the summary.
"""

from __future__ import annotations

import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "python_compat" / "real" / "geometry" / "tf" / "test" / "testPython.py"


def _debian_tf() -> bool:
    return subprocess.run([SYSTEM_PYTHON, "-c", "import tf, rostest"], capture_output=True).returncode == 0


def run(cmd: list[str], home: Path) -> list[str]:
    env = {"PATH": "/usr/bin:/bin", "ROS_HOME": str(home), "PYTHONUNBUFFERED": "1"}
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    text = (out.stderr + out.stdout).replace(str(home), "ROS_HOME")
    return [line for line in text.splitlines() if not line.startswith("         at line ")]


def test_tfs_python_test_passes_and_reports_as_under_debian(tmp_path: Path) -> None:
    need_peer(_debian_tf(), "Debian's tf, rostest (python3-tf, python3-rostest)")
    theirs = run([SYSTEM_PYTHON, str(SCRIPT)], tmp_path / "debian")
    ours = run(rostui_cmd("python", "--rostui", str(SCRIPT)), tmp_path / "rostui")
    assert sorted(ours) == sorted(theirs)  # stderr and stdout interleave differently; the lines are the same
    assert "[Testcase: test_twist] ... ok" in ours and " * TESTS: 10" in ours
    report = ET.parse(tmp_path / "rostui" / "test_results" / "tf" / "rosunit-directed.xml").getroot()
    assert (report.get("tests"), report.get("errors"), report.get("failures")) == ("10", "0", "0")
