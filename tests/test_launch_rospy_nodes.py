"""`rostui launch`: a node whose executable is a rospy script gets what `rostui run` gives it.

A package on a temporary ROS_PACKAGE_PATH holds ros_tutorials' talker.py and listener.py (unmodified, from
tests/python_compat/real) and a launch file starting both. `python` on PATH is rostui's own Python (as in a
virtualenv holding rostui), which has no real rospy: the nodes get rostui's rospy. Debian's `rostopic echo`
hears the talker, the listener hears it too, and `--args` prints what Debian's roslaunch prints. A node
whose `#!` line names Debian's python3 gets Debian's rospy, and the launcher's stderr says so in one line.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rostui.compat import PYLIB

from conftest import REPO, SYSTEM_PYTHON, need_peer, wait_until
from launch_helpers import Launch, have_roslaunch, run_roslaunch, run_rostui

TUTORIALS = REPO / "tests" / "python_compat" / "real" / "ros_tutorials"
WHICH = "import rospy, sys\nprint(rospy.__file__, sys.argv[1:2], flush=True)\n"
CHAT = """<launch>
  <node pkg="demo_pkg" type="talker.py" name="talker"/>
  <node pkg="demo_pkg" type="listener.py" name="listener" output="screen"/>
  <node pkg="demo_pkg" type="which_env.py" name="which_env" args="env" output="screen"/>
</launch>
"""
REAL = """<launch>
  <node pkg="demo_pkg" type="which_debian.py" name="which_debian" args="debian" output="screen"/>
</launch>
"""
FORCED = """<launch>
  <node pkg="demo_pkg" type="which_debian.py" name="which_debian" args="forced" output="screen">
    <env name="ROSTUI_PYTHON" value="rostui"/>
  </node>
</launch>
"""


@pytest.fixture
def launch_env(tmp_path: Path, ros_env: dict[str, str]) -> dict[str, str]:
    """demo_pkg (talker.py, listener.py, two scripts saying which rospy they got, two launch files) on
    ROS_PACKAGE_PATH, and `python` on PATH naming rostui's Python."""
    root = tmp_path / "pkgs" / "demo_pkg"
    (root / "scripts").mkdir(parents=True)
    (root / "launch").mkdir()
    (root / "package.xml").write_text(
        '<package format="2"><name>demo_pkg</name><version>0.0.1</version><description>demo</description>'
        '<maintainer email="a@example.com">a</maintainer><license>BSD</license></package>\n')
    for name in ("talker.py", "listener.py"):
        shutil.copy(TUTORIALS / name, root / "scripts" / name)
    (root / "scripts" / "which_env.py").write_text("#!/usr/bin/env python\n" + WHICH)
    (root / "scripts" / "which_debian.py").write_text(f"#!{SYSTEM_PYTHON}\n" + WHICH)
    for script in (root / "scripts").iterdir():
        script.chmod(0o755)
    (root / "launch" / "chat.launch").write_text(CHAT)
    (root / "launch" / "real.launch").write_text(REAL)
    (root / "launch" / "forced.launch").write_text(FORCED)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    # A script, not a symlink: a venv made from Debian's python3 (as CI's is) found through a symlink
    # elsewhere would miss its pyvenv.cfg and import Debian's rospy.
    (bin_dir / "python").write_text(f'#!/bin/sh\nexec {sys.executable} "$@"\n')
    (bin_dir / "python").chmod(0o755)
    env = {k: v for k, v in ros_env.items() if k != "PYTHONPATH" and not k.startswith("ROSTUI_PYTHON")}
    env["ROS_PACKAGE_PATH"] = str(tmp_path / "pkgs")
    env["PATH"] = os.pathsep.join([str(bin_dir), env.get("PATH", os.defpath)])
    return env


def test_launched_talker_heard_by_rostopic_echo_and_listener(launch_env: dict[str, str], rostui_core: object,
                                                            tmp_path: Path) -> None:
    """talker.py and listener.py as launch nodes, on rostui's rospy: the real `rostopic echo` and the
    listener hear the talker; nothing on stderr says which ROS they got (no real ROS in their Python)."""
    launch = Launch(["demo_pkg", "chat.launch"], launch_env, tmp_path)
    try:
        echo = subprocess.run(["rostopic", "echo", "-n", "1", "/chatter"], env=launch_env, capture_output=True,
                              text=True, timeout=90)
        wait_until(lambda: "I heard hello world" in launch.out and "['env']" in launch.out,
                   "the listener to hear the talker", timeout=60)
    finally:
        code = launch.interrupt()
    assert echo.stdout.startswith('data: "hello world '), echo.stdout + echo.stderr
    assert f"{PYLIB / 'rospy' / '__init__.py'} ['env']" in launch.out.splitlines(), launch.out
    heard = [line for line in launch.out.splitlines() if "I heard hello world" in line]
    assert heard and heard[0].startswith("[INFO] [") and "]: /listenerI heard hello world " in heard[0], heard
    assert "rostui python:" not in launch.err, launch.err
    assert code == 0, launch.err


def test_real_rospy_of_the_nodes_python_wins(launch_env: dict[str, str], rostui_core: object, tmp_path: Path,
                                             rospy_available: None) -> None:
    """A node whose `#!` line names Debian's python3 gets Debian's rospy; one stderr line says so."""
    launch = Launch(["demo_pkg", "real.launch"], launch_env, tmp_path)
    try:
        wait_until(lambda: "['debian']" in launch.out, "the node to print which rospy it got", timeout=60)
    finally:
        launch.interrupt()
    assert "/usr/lib/python3/dist-packages/rospy/__init__.py ['debian']" in launch.out.splitlines(), launch.out
    notices = [line for line in launch.err.splitlines() if line.startswith("rostui python:")]
    assert notices == ["rostui python: the script gets the real ROS at /usr/lib/python3/dist-packages/rospy "
                       "(`rostui python --rostui` gives it rostui's)"], launch.err


def test_rostui_python_env_beats_a_real_rospy(launch_env: dict[str, str], rostui_core: object, tmp_path: Path,
                                              rospy_available: None) -> None:
    """`<env name="ROSTUI_PYTHON" value="rostui"/>` gives the same node rostui's rospy; one stderr line names
    the real ROS it does not get."""
    launch = Launch(["demo_pkg", "forced.launch"], launch_env, tmp_path)
    try:
        wait_until(lambda: "['forced']" in launch.out, "the node to print which rospy it got", timeout=60)
    finally:
        launch.interrupt()
    assert f"{PYLIB / 'rospy' / '__init__.py'} ['forced']" in launch.out.splitlines(), launch.out
    notices = [line for line in launch.err.splitlines() if line.startswith("rostui python:")]
    assert notices == [f"rostui python: the script gets rostui's rospy, genpy, roslib, rosbag and message modules "
                       f"({PYLIB}), not the real ROS at /usr/lib/python3/dist-packages/rospy"], launch.err


@pytest.mark.parametrize("node", ["/talker", "/listener"])
def test_args_show_what_roslaunch_shows(launch_env: dict[str, str], node: str) -> None:
    """`--args NODE` prints the command line Debian's roslaunch prints: the script itself, not rostui's
    Python and modules."""
    need_peer(have_roslaunch(), "roslaunch (Debian ros-core)")
    ours = run_rostui(["--args", node, "demo_pkg", "chat.launch"], launch_env)
    theirs = run_roslaunch(["--args", node, "demo_pkg", "chat.launch"], launch_env)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == theirs.stdout
    assert ours.stdout.split()[0].endswith(f"/demo_pkg/scripts/{node[1:]}.py"), ours.stdout

