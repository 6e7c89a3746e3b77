"""Files with <machine>s and files roslaunch only warns about: rostui's views equal Debian roslaunch's.

tests/roslaunch_xml holds roslaunch's own test launch files (ros_comm, unmodified)
that declare machines, far-away ones too; tests/launch_real holds launch files
of public robot repositories (unmodified) that use attributes roslaunch only
warns about.  Both launchers see one ROS_PACKAGE_PATH: fake packages made here
(``package``, ``roslaunch``, ``rospy``, ``rviz``, ``rostopic`` and the PR2's driver packages,
with empty executables, and
roslaunch's test params.yaml where its files ``$(find roslaunch)`` it), rostui's
built-ins and a copy of tests/launch_real.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, need_peer
from launch_helpers import BUILTIN_SHARE, have_roslaunch, run_roslaunch, run_rostui

XML = REPO / "tests" / "roslaunch_xml"
REAL = REPO / "tests" / "launch_real"
REMOTE_ARGS = ["address:=robot7.example.invalid", "env_loader:=/opt/ros/noetic/env.sh", "user:=robot"]
#: (file, args): roslaunch's test files with machines, then the real-world files.
VALID = [
    (str(XML / "test-machine-valid.xml"), []),
    (str(XML / "test-node-valid.xml"), []),
    (str(XML / "test-test-valid.xml"), []),
    (str(XML / "test-valid.xml"), []),
    (str(XML / "example-ssh.launch"), []),
    (str(XML / "manual-test-remote-timeouts.launch"), REMOTE_ARGS),
]
#: PR2's machine definitions and the nodes it starts on its second computer: a real two-machine robot.
PR2 = [str(REAL / "pr2_machine" / "pr2.machine"), str(REAL / "pr2_bringup" / "pr2-c2.launch")]
REAL_FILES = [
    (PR2, []),
    (["ct_icp_odometry", "ct_icp_on_rosbag.launch"], ["rosbag:=/data/run1.bag", "topic:=/velodyne_points"]),
    (["fkie_node_manager", "demo_bob.launch"], []),
]
#: Executables Debian's roslaunch finds in catkin's libexec (/usr/lib/PKG) for the real files' nodes.
DEBIAN_LIBEXEC = ("/usr/lib/rostopic/rostopic", "/usr/lib/rosbag/play")
INVALID = sorted(p.name for p in XML.glob("test-machine-invalid*.xml")) + ["test-machine-substitution.xml"]


def _package(root: Path, name: str, executables: list[str]) -> Path:
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<package format="2"><name>{name}</name><version>0.0.0</version>'
        '<description>fake package for tests</description><maintainer email="t@example.com">t</maintainer>'
        '<license>BSD</license></package>\n')
    for exe in executables:
        (folder / exe).write_text("#!/bin/sh\n")
        (folder / exe).chmod(0o755)
    return folder


@pytest.fixture
def env(ros_env: dict[str, str], tmp_path: Path) -> dict[str, str]:
    """Fake packages, rostui's built-ins and a copy of the real files on ROS_PACKAGE_PATH."""
    need_peer(have_roslaunch(), "roslaunch (Debian ros-core)")
    fake = tmp_path / "fake"
    types = sorted(set(re.findall(r'type="(test_\w+)"', "".join(p.read_text() for p in XML.glob("*.xml")))))
    _package(fake, "package", types)
    roslaunch = _package(fake, "roslaunch", ["signal_logger.py"])
    (roslaunch / "test").mkdir()
    shutil.copy(XML / "params.yaml", roslaunch / "test" / "params.yaml")
    _package(fake, "rospy", ["talker.py", "listener.py"])
    _package(fake, "rviz", ["rviz"])
    _package(fake, "rostopic", ["rostopic"])
    _package(fake, "ocean_battery_driver", ["ocean_server"])
    _package(fake, "urg_node", ["urg_node"])
    _package(fake, "pr2_computer_monitor", ["ntp_monitor.py", "cpu_monitor.py", "hd_monitor.py"])
    real = tmp_path / "real"
    shutil.copytree(REAL, real)
    node = real / "ct_icp_odometry" / "ct_icp_odometry_node"
    node.write_text("#!/bin/sh\n")
    node.chmod(0o755)
    env = dict(ros_env)
    env["ROS_PACKAGE_PATH"] = f"{fake}:{BUILTIN_SHARE}:{real}"
    env["ROS_ENV_LOADER"] = "/home/pr2/ros/env.sh"  # pr2.machine reads it with $(env)
    return env


def _cases() -> list[tuple[list[str], list[str]]]:
    return [([path], args) for path, args in VALID] + REAL_FILES


def _id(words: list[str]) -> str:
    return "+".join(Path(w).name for w in words if "/" in w) or words[-1]


IDS = [_id(words) for words, _ in _cases()]


@pytest.mark.parametrize("words,args", _cases(), ids=IDS)
@pytest.mark.parametrize("mode", ["--nodes", "--dump-params", "--ros-args"])
def test_views_equal_roslaunch(env: dict[str, str], words: list[str], args: list[str], mode: str) -> None:
    """Machines (far-away ones too) and unknown names never stop the views; the output is roslaunch's."""
    ours, theirs = run_rostui([mode, *words, *args], env), run_roslaunch([mode, *words, *args], env)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == theirs.stdout


@pytest.mark.parametrize("words,args", _cases(), ids=IDS)
def test_files_equal_roslaunch(env: dict[str, str], words: list[str], args: list[str]) -> None:
    ours, theirs = run_rostui(["--files", *words, *args], env), run_roslaunch(["--files", *words, *args], env)
    assert ours.returncode == theirs.returncode == 0, ours.stderr + theirs.stderr
    assert sorted(ours.stdout.split()) == sorted(theirs.stdout.split())


WITH_NODES = [(words, args) for words, args in _cases() if not words[-1].endswith(("machine-valid.xml", "/test-valid.xml"))]
#: Files with many nodes are compared in parts (every PARTS-th node), so no one test runs two processes per node
#: of 30 nodes in a row: each part is a test of its own that the workers share out.
PARTS = {"test-node-valid.xml": 4, "test-test-valid.xml": 3}
NODE_ARGS_CASES = [(words, args, part, PARTS.get(Path(words[-1]).name, 1))
                   for words, args in WITH_NODES for part in range(PARTS.get(Path(words[-1]).name, 1))]


@pytest.mark.parametrize("words,args,part,parts", NODE_ARGS_CASES,
                         ids=[f"{_id(w)}-{part + 1}of{parts}" if parts > 1 else _id(w)
                              for w, _, part, parts in NODE_ARGS_CASES])
def test_node_args_equal_roslaunch(env: dict[str, str], words: list[str], args: list[str], part: int,
                                   parts: int) -> None:
    """``--args NODE`` for every node (those of this ``part`` of ``parts``), remote ones included.

    roslaunch finds Debian's own ``rostopic`` and ``rosbag play`` in /usr/lib/PKG
    (catkin's libexec), which rostui's resolver does not search; for those
    nodes the executable's path is left out of the comparison (rostui's must
    end in the same name), the rest must be equal.
    """
    listing = run_roslaunch(["--nodes", *words, *args], env)
    assert listing.returncode == 0, listing.stderr
    names = listing.stdout.split()
    assert len(names) >= parts
    for node in names[part::parts]:
        ours = run_rostui(["--args", node, *words, *args], env)
        theirs = run_roslaunch(["--args", node, *words, *args], env)
        assert theirs.returncode == 0, theirs.stderr
        assert ours.returncode == 0, ours.stderr
        libexec = [w for w in theirs.stdout.split() if w in DEBIAN_LIBEXEC]
        if libexec:
            theirs_words, ours_words = theirs.stdout.split(), ours.stdout.split()
            at = theirs_words.index(libexec[0])
            assert ours_words[at].endswith("/" + Path(libexec[0]).name), ours.stdout
            assert ours_words[:at] + ours_words[at + 1:] == theirs_words[:at] + theirs_words[at + 1:]
        else:
            assert ours.stdout == theirs.stdout, node


@pytest.mark.parametrize("name", INVALID)
def test_invalid_machines_fail_in_both(env: dict[str, str], name: str) -> None:
    """roslaunch's invalid <machine> files: both refuse them; rostui in one line naming file and line."""
    path = str(XML / name)
    ours, theirs = run_rostui(["--nodes", path], env), run_roslaunch(["--nodes", path], env)
    assert theirs.returncode != 0
    assert ours.returncode == 1 and ours.stdout == ""
    lines = ours.stderr.strip().splitlines()
    assert len(lines) == 1 and re.match(rf"rostui launch: {re.escape(path)}:\d+: ", lines[0]), ours.stderr


WARNED = [
    (["ct_icp_odometry", "ct_icp_on_rosbag.launch"], ["rosbag:=/data/run1.bag", "topic:=/velodyne_points"],
     ["ct_icp_odometry/launch/ct_icp_on_rosbag.launch:3: unknown <arg> attribute 'required'",
      "ct_icp_odometry/launch/ct_icp_on_rosbag.launch:4: unknown <arg> attribute 'required'",
      "ct_icp_odometry/launch/ct_icp_on_rosbag.launch:14: unknown <include> attribute 'args'"]),
    (["fkie_node_manager", "demo_bob.launch"], [],
     ["fkie_node_manager/launch/demo_capabilities.launch:3: unknown <rosparam> attribute 'tag'",
      "fkie_node_manager/launch/demo_capabilities.launch:39: unknown <rosparam> attribute 'tag'"]),
]


@pytest.mark.parametrize("words,args,problems", WARNED, ids=[w[1] for w, _, _ in WARNED])
def test_strict_and_check_refuse_what_roslaunch_warns_about(env: dict[str, str], words: list[str], args: list[str],
                                                            problems: list[str]) -> None:
    """One FILE:LINE line per unknown name with --strict and with `launch check`; roslaunch's checker agrees."""
    real = Path(env["ROS_PACKAGE_PATH"].split(":")[-1])
    expected = [f"rostui launch: {real}/{line}" for line in problems]
    strict = run_rostui(["--strict", "--nodes", *words, *args], env)
    assert strict.returncode == 1 and strict.stdout == ""
    assert strict.stderr.splitlines() == expected
    checked = run_rostui(["check", *words, *args], env)
    assert checked.returncode == 1 and checked.stdout == ""
    assert checked.stderr.splitlines()[:len(expected)] == expected


def test_check_names_the_machine_that_does_not_resolve(env: dict[str, str]) -> None:
    """PR2's second computer ``c2`` is not on this network: `launch check` says so, pointing at its <machine>."""
    result = run_rostui(["check", *PR2], env)
    assert result.returncode == 1
    assert result.stderr.strip() == f"rostui launch: {PR2[0]}:3: cannot resolve host address for machine [c2]"
    listing = run_rostui(["--nodes", *PR2], env)
    assert listing.returncode == 0 and "/ntp_c2" in listing.stdout.split()
