"""`rostui tf echo` against real broadcasters: the composed map -> laser transform to 1e-6, and tf_echo's text."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from cli_helpers import rostui
from conftest import rostui_cmd
from interop_helpers import Peer, Spawn, spawn  # noqa: F401  (fixture)
from tf_chain import BROADCASTERS, pose_in

NUM = r"(-?\d+\.\d+)"
BLOCK = re.compile(
    rf"At time {NUM}\n- Translation: \[{NUM}, {NUM}, {NUM}\]\n- Rotation: in Quaternion \[{NUM}, {NUM}, {NUM}, {NUM}\]\n"
    rf" {{12}}in RPY \(radian\) \[{NUM}, {NUM}, {NUM}\]\n {{12}}in RPY \(degree\) \[{NUM}, {NUM}, {NUM}\]\n")


def quaternion_matrix(x: float, y: float, z: float, w: float) -> np.ndarray:
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def first_block(peer: Peer) -> tuple[float, ...]:
    peer.wait_for(r"in RPY \(degree\)")
    match = BLOCK.search(peer.output + "\n")
    assert match, peer.describe()
    return tuple(float(v) for v in match.groups())


def check_against_matrices(values: tuple[float, ...], target: str, source: str, tol: float) -> None:
    stamp, tx, ty, tz, qx, qy, qz, qw, roll, pitch, yaw, droll, dpitch, dyaw = values
    want = pose_in(target, source)
    assert stamp > 0
    assert np.allclose([tx, ty, tz], want[:3, 3], atol=tol), (values, want)
    assert np.allclose(quaternion_matrix(qx, qy, qz, qw), want[:3, :3], atol=tol * 4), (values, want)
    assert math.hypot(qx, qy, qz, qw) == pytest.approx(1.0, abs=tol * 4)
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    from_rpy = (np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]) @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
                @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]]))
    assert np.allclose(from_rpy, want[:3, :3], atol=tol * 4)
    assert np.allclose([droll, dpitch, dyaw], np.degrees([roll, pitch, yaw]), atol=tol * 100)


@pytest.mark.parametrize("broadcaster,master", [("rospy", "real_roscore"), ("rostui", "rostui_core")])
def test_echo_matches_the_composed_transform(broadcaster: str, master: str, request: pytest.FixtureRequest,
                                             ros_env: dict[str, str], rospy_available: None, spawn: Spawn) -> None:
    request.getfixturevalue(master)
    BROADCASTERS[broadcaster](spawn)
    for target, source in [("map", "laser"), ("laser", "odom")]:
        echo = spawn(rostui_cmd("tf", "echo", target, source, "5", "--precision", "9"), label="rostui tf echo")
        check_against_matrices(first_block(echo), target, source, 1e-6)
        echo.stop()


def test_echo_prints_what_real_tf_echo_prints(real_roscore: object, ros_env: dict[str, str],
                                              rospy_available: None, spawn: Spawn) -> None:
    BROADCASTERS["rospy"](spawn)
    ours = spawn(rostui_cmd("tf", "echo", "map", "laser"), label="rostui tf echo")
    theirs = spawn(["/usr/lib/tf/tf_echo", "map", "laser"], label="tf_echo")
    mine, real = first_block(ours), first_block(theirs)
    assert len(mine) == len(real)
    assert mine[1:] == real[1:], f"{ours.describe()}\n{theirs.describe()}"  # 3 decimals, as tf_echo
    check_against_matrices(real, "map", "laser", 2e-3)


def test_echo_of_an_unknown_frame_says_so_and_lists_frames(rostui_core: object, ros_env: dict[str, str],
                                                           spawn: Spawn) -> None:
    BROADCASTERS["rostui"](spawn)
    echo = spawn(rostui_cmd("tf", "echo", "map", "nowhere"), label="rostui tf echo")
    echo.wait_for(r'Exception thrown:"nowhere" passed to lookupTransform argument source_frame does not exist')
    echo.wait_for(r"^Frame laser exists with parent base_link\.$")
    echo.wait_for(r"^Frame odom exists with parent map\.$")


def test_echo_without_a_master_or_with_a_bad_rate(ros_env: dict[str, str]) -> None:
    result = rostui(["tf", "echo", "map", "laser"], ros_env)
    assert result.returncode == 1
    assert result.stderr.strip() == f"ERROR: Unable to communicate with master at {ros_env['ROS_MASTER_URI']}/"
    result = rostui(["tf", "echo", "map", "laser", "0"], ros_env)
    assert result.returncode == 1 and result.stderr.strip() == "Echo rate must be > 0.0"


def test_tf_tree_needs_a_terminal(ros_env: dict[str, str]) -> None:
    result = rostui(["tf", "tree"], ros_env)
    assert result.returncode == 1
    assert result.stderr.strip() == ("ERROR: rostui tf tree draws in a terminal: stdin and stdout must be a TTY "
                                     "(use `rostui tf echo SOURCE TARGET` without one)")


def test_tf_echo_loads_no_textual() -> None:
    import subprocess
    import sys

    code = ("import sys, rostui.cli.main, rostui.models.tf.echo; "
            "print(sorted(m for m in ('textual', 'rich') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
