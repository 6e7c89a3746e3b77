"""rosgraph and rospkg under `rostui python`, against Debian's python3-rosgraph, python3-rospkg and rospack.

One probe script (tests/python_compat/own/rosgraph_rospkg_probe.py) calls the master through
``rosgraph.Master`` (parameters, errors, state, a master that is not there, bad URIs), rosgraph's name
functions over a battery of names and namespaces, and rospkg's ``RosPack`` on a package tree of three packages
(package.xml with exports and dependencies, a rosbuild manifest.xml): it prints the same under both, on rostui
core and on a real roscore. The
dependencies rospkg reports are compared with the rospack command's (Debian's rospkg lists a package.xml's
dependencies only when a rosdep database is installed; rostui's lists them as rospack does).
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_command, need_peer, rostui_cmd

PROBE = REPO / "tests" / "python_compat" / "own" / "rosgraph_rospkg_probe.py"

PROBE_PKG = """<?xml version="1.0"?>
<package format="2">
  <name>probe_pkg</name>
  <version>1.2.3</version>
  <description>A probe package</description>
  <maintainer email="m@example.com">M</maintainer>
  <license>BSD</license>
  <license>MIT</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend>std_msgs</depend>
  <build_depend>probe_base</build_depend>
  <exec_depend>probe_base</exec_depend>
  <exec_depend>rospy</exec_depend>
  <test_depend>rostest</test_depend>
  <export>
    <probe_pkg plugin="${prefix}/plugins.xml"/>
    <probe_pkg plugin="${prefix}/more.xml"/>
  </export>
</package>
"""
PROBE_BASE = """<?xml version="1.0"?>
<package format="2"><name>probe_base</name><version>0.1.0</version><description>Base</description>
  <maintainer email="m@example.com">M</maintainer><license>BSD</license><depend>std_msgs</depend></package>
"""
PROBE_OLD = """<package>
  <description brief="old">An old rosbuild package</description>
  <author>A</author>
  <license>BSD</license>
  <depend package="probe_base"/>
  <export><cpp cflags="-I${prefix}/include"/></export>
</package>
"""


def package_tree(root: Path) -> Path:
    """probe_pkg, probe_base and the rosbuild probe_old under *root*."""
    for name, text, file in (("probe_pkg", PROBE_PKG, "package.xml"), ("probe_base", PROBE_BASE, "package.xml"),
                             ("probe_old", PROBE_OLD, "manifest.xml")):
        (root / name / "src").mkdir(parents=True)
        (root / name / file).write_text(text)
    return root


def test_probe_prints_what_it_prints_under_debian(any_master: str, ros_env: dict[str, str],
                                                  tmp_path: Path) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import rosgraph, rospkg"], capture_output=True).returncode == 0,
              "rosgraph, rospkg (Debian python3-rosgraph, python3-rospkg)")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    env["ROS_PACKAGE_PATH"] = str(package_tree(tmp_path / "packages"))
    env.pop("ROS_NAMESPACE", None)
    debian = subprocess.run([SYSTEM_PYTHON, str(PROBE)], env=env, capture_output=True, text=True, timeout=60)
    ours = subprocess.run(rostui_cmd("python", "--rostui", str(PROBE)), env=env, capture_output=True, text=True,
                          timeout=60)
    assert debian.returncode == 0, debian.stderr
    assert ours.returncode == 0, ours.stderr
    lines = ours.stdout.splitlines()
    assert lines[0] == "caller /probe True False"
    assert any(line.startswith("getParam MasterError True") for line in lines)
    assert "offline raises ConnectionRefusedError" in lines
    assert len([line for line in lines if line.startswith("name '")]) == 18
    assert ours.stdout == debian.stdout


def rospack(env: dict[str, str], *args: str) -> list[str]:
    """The lines the rospack command prints."""
    done = subprocess.run(["rospack", *args], env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return sorted(done.stdout.split())


def test_dependencies_are_rospacks(ros_env: dict[str, str], tmp_path: Path) -> None:
    need_command("rospack")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    env["ROS_PACKAGE_PATH"] = str(package_tree(tmp_path / "packages"))
    env["ROS_HOME"] = str(tmp_path / "home")
    script = ("import rospkg; p = rospkg.RosPack()\n"
              "for name in ('probe_pkg', 'probe_old'):\n"
              "    print(name, sorted(p.get_depends(name, implicit=False)))\n"
              "print('probe_base', sorted(n for n in p.get_depends_on('probe_base', implicit=False)))\n")
    ours = subprocess.run(rostui_cmd("python", "--rostui", "-c", script), env=env, capture_output=True, text=True,
                          timeout=60)
    assert ours.returncode == 0, ours.stderr
    said = dict(line.split(" ", 1) for line in ours.stdout.splitlines())
    assert said["probe_pkg"] == str(rospack(env, "depends1", "probe_pkg")) == "['probe_base', 'rospy', 'std_msgs']"
    assert said["probe_old"] == str(rospack(env, "depends1", "probe_old"))
    assert said["probe_base"] == str(rospack(env, "depends-on1", "probe_base"))
