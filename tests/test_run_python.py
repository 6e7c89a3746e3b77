"""`rostui run PKG SCRIPT`: a package's rospy script gets what `rostui python` gives it.

The package lives on a temporary ROS_PACKAGE_PATH with its own message; its scripts print which rospy
they got, a message of the package, and their arguments. A script whose `#!` line names Debian's
python3 gets Debian's real rospy (one stderr line says so) unless `--rostui` is given; ros_tutorials'
talker run this way is heard by the real `rostopic echo`.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from rostui.compat import PYLIB

from conftest import REPO, SYSTEM_PYTHON, rostui_cmd, stop_process

SCRIPT = '''import sys
import rospy
from demo_pkg.msg import Thing
print(rospy.__file__)
print(Thing(text="a", n=2))
print(sys.argv[1:])
'''
OURS = str(PYLIB / "rospy" / "__init__.py")
THING = ['text: "a"', "n: 2"]
ARGS = ["a:=b", "__name:=x", "-v"]


def _script(path: Path, first_line: str | None, executable: bool = True) -> None:
    path.write_text((f"{first_line}\n" if first_line else "") + SCRIPT)
    path.chmod(0o755 if executable else 0o644)


@pytest.fixture
def package(tmp_path: Path) -> dict[str, str]:
    """demo_pkg with msg/Thing.msg and its scripts on ROS_PACKAGE_PATH; the environment to run them in."""
    root = tmp_path / "pkgs" / "demo_pkg"
    (root / "msg").mkdir(parents=True)
    (root / "scripts").mkdir()
    (root / "package.xml").write_text(
        '<package format="2"><name>demo_pkg</name><version>0.0.1</version><description>demo</description>'
        '<maintainer email="a@example.com">a</maintainer><license>BSD</license></package>\n')
    (root / "msg" / "Thing.msg").write_text("string text\nint32 n\n")
    _script(root / "scripts" / "ours.py", f"#!{sys.executable}")
    _script(root / "scripts" / "debian.py", f"#!{SYSTEM_PYTHON}")
    _script(root / "scripts" / "named_python", "#!/usr/bin/env python")
    _script(root / "scripts" / "not_executable.py", None, executable=False)
    shutil.copy(REPO / "tests" / "python_compat" / "real" / "ros_tutorials" / "talker.py", root / "scripts")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH" and not k.startswith("ROSTUI_PYTHON")}
    env["ROS_PACKAGE_PATH"] = str(tmp_path / "pkgs")
    return env


def _run(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(rostui_cmd("run", *args), env=env, capture_output=True, text=True, timeout=120,
                          stdin=subprocess.DEVNULL)


@pytest.mark.parametrize("script", ["ours.py", "named_python", "not_executable.py"])
@pytest.mark.parametrize("flags", [[], ["--rostui"]])
def test_script_gets_rostuis_modules(package: dict[str, str], script: str, flags: list[str]) -> None:
    """A script with no real ROS in its Python gets rostui's rospy and the package's messages, silently."""
    out = _run(package, *flags, "demo_pkg", script, *ARGS)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [OURS, *THING, repr(ARGS)]
    assert out.stderr == ""


def test_real_rospy_of_the_scripts_python_wins(package: dict[str, str], rospy_available: None) -> None:
    """`#!/usr/bin/python3` with Debian's rospy: the script gets it, and one stderr line says so."""
    env = dict(package, PYTHONPATH=str(Path(package["ROS_PACKAGE_PATH"]) / "none"))
    code = "import rospy, sys; print(rospy.__file__); print(sys.argv[1:])"
    script = Path(package["ROS_PACKAGE_PATH"]) / "demo_pkg" / "scripts" / "real_only.py"
    script.write_text(f"#!{SYSTEM_PYTHON}\n{code}\n")
    script.chmod(0o755)
    out = _run(env, "demo_pkg", "real_only.py", *ARGS)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["/usr/lib/python3/dist-packages/rospy/__init__.py", repr(ARGS)]
    assert out.stderr.splitlines() == [
        "rostui python: the script gets the real ROS at /usr/lib/python3/dist-packages/rospy "
        "(`rostui python --rostui` gives it rostui's)"]


def test_rostui_flag_beats_a_real_rospy(package: dict[str, str], rospy_available: None) -> None:
    """`rostui run --rostui` gives the same script rostui's modules; one stderr line names both."""
    out = _run(package, "--rostui", "demo_pkg", "debian.py", *ARGS)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [OURS, *THING, repr(ARGS)]
    assert out.stderr.splitlines() == [
        f"rostui python: the script gets rostui's rospy, genpy, roslib, rosbag and message modules ({PYLIB}), "
        "not the real ROS at /usr/lib/python3/dist-packages/rospy"]


def test_both_flags_are_refused(package: dict[str, str]) -> None:
    out = _run(package, "--rostui", "--real-ros", "demo_pkg", "ours.py")
    assert out.returncode == 2
    assert out.stderr.strip() == "rostui run: --real-ros and --rostui exclude each other"


def test_run_talker_heard_by_rostopic_echo(package: dict[str, str], ros_env: dict[str, str],
                                           rostui_core: subprocess.Popen) -> None:
    """ros_tutorials' talker.py (`#!/usr/bin/env python`), run by `rostui run`, publishes to the real rostopic."""
    env = dict(package, **{k: ros_env[k] for k in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")})
    talker = subprocess.Popen(rostui_cmd("run", "--rostui", "demo_pkg", "talker.py"), env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        echo = subprocess.run(["rostopic", "echo", "-n", "1", "/chatter"], env=env, capture_output=True,
                              text=True, timeout=60)
    finally:
        stop_process(talker)
    assert echo.stdout.startswith('data: "hello world '), echo.stdout + echo.stderr
