"""`rostui python` on a machine with no ROS: the modules a robot script imports beyond rospy are there.

The way fresh-ci's root is before .ci/run installs ROS: the script runs in a mount namespace where
/usr/share (Debian's ROS packages) and /usr/lib/python3/dist-packages (Debian's ROS Python) are empty, so
everything it imports (visualization_msgs, actionlib, tf2_ros, tf, cv_bridge, message_filters,
move_base_msgs) must come from rostui and its pip dependencies.
"""

from __future__ import annotations

import os
import shutil
import subprocess

from conftest import REPO, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "python_compat" / "own" / "no_ros_imports.py"


def test_robot_imports_work_with_no_ros_installed() -> None:
    need_peer(os.geteuid() == 0 and shutil.which("unshare") is not None, "root and unshare (util-linux)")
    hide = "mount -t tmpfs none /usr/share && mount -t tmpfs none /usr/lib/python3/dist-packages && exec \"$@\""
    out = subprocess.run(["unshare", "--mount", "sh", "-c", hide, "sh", *rostui_cmd("python", "--rostui",
                                                                                    str(SCRIPT))],
                         env={"PATH": "/usr/bin:/bin", "HOME": "/tmp"}, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [
        "marker visualization_msgs/Marker 4048c9de2a16f4ae8e0538085ebf1b97 demo 3",
        "action move_base_msgs/MoveBaseAction True SUCCEEDED",
        "tf2 2.0",
        "tf [0.0, 0.0, 0.479426, 0.877583]",
        "cv_bridge rgb8 6 [2, 1, 0]",
        "filters Cache True",
    ]
