"""`rostui python` gives a robot script its modules beyond rospy from rostui alone, with no ROS needed.

tests/python_compat/own/no_ros_imports.py imports visualization_msgs, actionlib, tf2_ros, tf, cv_bridge,
message_filters and move_base_msgs and uses each. .ci/run runs it on the new machine before Debian's ROS is
installed (a machine with no ROS, as fresh-ci's root is then) and compares what it prints with
no_ros_imports.expected; here, on a machine that has Debian's ROS too, the same script prints the same and
every module it used comes from rostui (its files, and its import hook for the message packages).
"""

from __future__ import annotations

import subprocess

from conftest import REPO, rostui_cmd

OWN = REPO / "tests" / "python_compat" / "own"
COMPAT = REPO / "rostui" / "compat"


def test_robot_imports_come_from_rostui() -> None:
    out = subprocess.run(rostui_cmd("python", "--rostui", str(OWN / "no_ros_imports.py"), "--origins"),
                         env={"PATH": "/usr/bin:/bin", "HOME": "/tmp"}, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    expected = (OWN / "no_ros_imports.expected").read_text().splitlines()
    assert lines[:len(expected)] == expected
    origins = {line.split()[1]: line.split()[2] for line in lines[len(expected):]}
    assert len(origins) == 12
    assert {name: where for name, where in origins.items()
            if not (where.startswith(str(COMPAT / "pylib")) or where == "rostui.compat.finder")} == {}


def test_ci_runs_it_before_ros_is_installed() -> None:
    """The check in .ci/run comes before the apt-get line that installs Debian's ROS."""
    run = (REPO / ".ci" / "run").read_text()
    check = run.index("no_ros_imports.py")
    assert check < run.index("apt-get install") and run.index(".venv/bin/pip install -q -e") < check
