"""Real ROS 1 tools drive rostui's turtlesim the way the book and the ROS wiki do.

Debian ships no turtlesim Python classes, so the fixture generates them from
rostui's own turtlesim .msg/.srv files with Debian's genpy generators (which
also proves the definitions are real ROS).  The node runs against `rostui
core` and against a real roscore.
"""

from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import SYSTEM_PYTHON, need_peer, shared_build
from interop_helpers import run_tool, spawn, wait_until  # noqa: F401
from rostui.core.msg import get_message_class, get_service_class
from rostui.turtlesim.world import WORLD_SIZE

SHARE = Path(__file__).resolve().parent.parent / "rostui" / "share"
GENMSG = Path("/usr/lib/genpy/genmsg_py.py")
GENSRV = Path("/usr/lib/genpy/gensrv_py.py")
MSGS = ("Pose", "Color", "Velocity")
SRVS = ("Spawn", "Kill", "SetPen", "TeleportAbsolute", "TeleportRelative")
CENTRE = WORLD_SIZE / 2.0


@pytest.fixture(scope="session")
def turtlesim_python(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """PYTHONPATH and ROS_PACKAGE_PATH that give the real tools a genpy-generated turtlesim package."""
    need_peer(GENMSG.exists() and GENSRV.exists(), "genpy generators (Debian python3-genpy)")
    need_peer(shutil.which("rostopic") is not None and shutil.which("rosservice") is not None,
              "rostopic, rosservice (Debian ros-core)")

    def build(root: Path) -> None:
        python_dir, packages = root / "python", root / "packages"
        out_msg, out_srv = python_dir / "turtlesim" / "msg", python_dir / "turtlesim" / "srv"
        includes = [f"-Iturtlesim:{SHARE / 'turtlesim' / 'msg'}", "-Istd_msgs:/usr/share/std_msgs/msg"]

        def generate(argv: list[str]) -> None:
            proc = subprocess.run([SYSTEM_PYTHON, *argv], capture_output=True, text=True)
            if proc.returncode != 0:
                pytest.fail(f"genpy refused {argv[-1]}:\n{proc.stdout}{proc.stderr}")

        for name in MSGS:
            generate([str(GENMSG), "-p", "turtlesim", *includes, "-o", str(out_msg),
                      str(SHARE / "turtlesim" / "msg" / f"{name}.msg")])
        for name in SRVS:
            generate([str(GENSRV), "-p", "turtlesim", *includes, "-o", str(out_srv),
                      str(SHARE / "turtlesim" / "srv" / f"{name}.srv")])
        generate([str(GENMSG), "--initpy", "-p", "turtlesim", "-o", str(out_msg)])
        generate([str(GENSRV), "--initpy", "-p", "turtlesim", "-o", str(out_srv)])
        (python_dir / "turtlesim" / "__init__.py").write_text("")
        packages.mkdir()
        (packages / "turtlesim").symlink_to(SHARE / "turtlesim", target_is_directory=True)

    root = shared_build(tmp_path_factory, "turtlesim_genpy", build)
    python_dir, packages = root / "python", root / "packages"
    return {"PYTHONPATH": str(python_dir), "ROS_PACKAGE_PATH": str(packages)}


@pytest.fixture
def tool_env(ros_env: dict[str, str], turtlesim_python: dict[str, str]) -> dict[str, str]:
    """The environment for real ROS tools: the test master plus the generated turtlesim package."""
    return {**ros_env, **turtlesim_python}


@pytest.fixture
def rostui_turtlesim(any_master, spawn, ros_env):  # noqa: F811
    """A headless rostui turtlesim on the test's master, with turtle1 publishing."""
    sim = spawn([sys.executable, "-m", "rostui", "run", "turtlesim", "turtlesim_node", "--headless"],
                label="rostui turtlesim")
    sim.wait_for(r"Spawning turtle \[turtle1\]")
    return sim


def echo_pose(env: dict[str, str], topic: str = "/turtle1/pose") -> dict[str, float]:
    """One pose as real `rostopic echo -n 1` prints it, parsed."""
    out = run_tool(["rostopic", "echo", "-n", "1", topic], env).stdout
    lines = out.splitlines()
    assert lines[-1] == "---", out
    fields = dict(line.split(": ", 1) for line in lines[:-1])
    assert list(fields) == ["x", "y", "theta", "linear_velocity", "angular_velocity"], out
    return {key: float(value) for key, value in fields.items()}


def test_genpy_generated_types_have_our_md5s(turtlesim_python: dict[str, str]) -> None:
    script = ("import json, turtlesim.msg as m, turtlesim.srv as s\n"
              f"print(json.dumps({{**{{n: getattr(m, n)._md5sum for n in {MSGS!r}}}, "
              f"**{{n: getattr(s, n)._md5sum for n in {SRVS!r}}}}}))\n")
    proc = subprocess.run([SYSTEM_PYTHON, "-c", script], capture_output=True, text=True,
                          env={"PATH": "/usr/bin:/bin", "PYTHONPATH": turtlesim_python["PYTHONPATH"]})
    assert proc.returncode == 0, proc.stderr
    theirs = json.loads(proc.stdout)
    ours = {n: get_message_class(f"turtlesim/{n}")._md5sum for n in MSGS}
    ours |= {n: get_service_class(f"turtlesim/{n}")._md5sum for n in SRVS}
    assert theirs == ours
    assert theirs["Pose"] == "863b248d5016ca62ea2e895ae5265cf9"  # the md5 every turtlesim tutorial shows


def test_rostopic_echo_prints_the_pose(rostui_turtlesim, tool_env) -> None:
    out = run_tool(["rostopic", "echo", "-n", "1", "/turtle1/pose"], tool_env).stdout
    assert out.splitlines() == [
        "x: 5.544444561004639", "y: 5.544444561004639", "theta: 0.0",
        "linear_velocity: 0.0", "angular_velocity: 0.0", "---",
    ]
    assert run_tool(["rostopic", "type", "/turtle1/pose"], tool_env).stdout.strip() == "turtlesim/Pose"


def test_rostopic_pub_command_velocity_moves_the_turtle(rostui_turtlesim, tool_env, spawn) -> None:  # noqa: F811
    spawn(["rostopic", "pub", "-r", "1", "/turtle1/command_velocity", "turtlesim/Velocity", "1", "0"],
          label="rostopic pub command_velocity", env=tool_env)
    wait_until(lambda: echo_pose(tool_env)["x"] > CENTRE + 1.5, "the turtle to drive right")
    pose = echo_pose(tool_env)
    assert pose["y"] == pytest.approx(CENTRE, abs=1e-5) and pose["theta"] == 0.0


def test_rostopic_pub_twist_drives_an_arc(rostui_turtlesim, tool_env) -> None:
    # The ROS wiki's form (publish once, latched) ...
    run_tool(["rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--",
              "[2.0, 0.0, 0.0]", "[0.0, 0.0, 1.8]"], tool_env)
    wait_until(lambda: echo_pose(tool_env)["theta"] > 1.5, "the turtle to turn")
    first = echo_pose(tool_env)
    assert first["x"] > CENTRE and first["y"] > CENTRE
    # ... and the YAML dictionary form.
    run_tool(["rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist",
              "{linear: {x: 2.0}, angular: {z: 1.8}}"], tool_env)
    wait_until(lambda: abs(echo_pose(tool_env)["theta"] - first["theta"]) > 1.0, "the turtle to turn again")
    second = echo_pose(tool_env)
    assert math.hypot(second["x"] - first["x"], second["y"] - first["y"]) > 0.5


def test_rosservice_call_spawn_like_the_book(rostui_turtlesim, tool_env) -> None:
    out = run_tool(["rosservice", "call", "/spawn", "3", "3", "0", "Mikey"], tool_env).stdout
    assert out.strip() == 'name: "Mikey"'
    assert "/Mikey/pose" in run_tool(["rostopic", "list"], tool_env).stdout.split()
    pose = echo_pose(tool_env, "/Mikey/pose")
    assert (pose["x"], pose["y"], pose["theta"]) == pytest.approx((3.0, 3.0, 0.0))
    again = run_tool(["rosservice", "call", "/spawn", "3", "3", "0", "Mikey"], tool_env, check=False)
    assert again.returncode != 0
    assert re.search(r"ERROR: service \[/spawn\] responded with an error: .*A turtle named \[Mikey\] already exists",
                     again.stdout + again.stderr), again.stdout + again.stderr
    rostui_turtlesim.wait_for(r"\[ERROR\] \[[\d.]+\]: A turtle named \[Mikey\] already exists")
    run_tool(["rosservice", "call", "/kill", "Mikey"], tool_env)
    assert "/Mikey/pose" not in run_tool(["rostopic", "list"], tool_env).stdout.split()


def test_rosparam_shows_background_and_clear_applies_it(rostui_turtlesim, tool_env) -> None:
    listed = run_tool(["rosparam", "list"], tool_env).stdout.split()
    assert {"/background_r", "/background_g", "/background_b"} <= set(listed)
    run_tool(["rosparam", "set", "/background_r", "255"], tool_env)
    run_tool(["rosparam", "set", "/background_b", "0"], tool_env)
    run_tool(["rosservice", "call", "/clear"], tool_env)

    def colour() -> list[str]:
        return run_tool(["rostopic", "echo", "-n", "1", "/turtle1/color_sensor"], tool_env).stdout.splitlines()

    wait_until(lambda: colour() == ["r: 255", "g: 86", "b: 0", "---"], "the new background under turtle1")
