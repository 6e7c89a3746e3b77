"""`rostui view /map --goal-topic /goal` end to end in tmux (80x24): g, the arrows, a and Enter send a goal that
Debian's rospy receives where the keys put it; t opens teleop, ↑ drives, Esc stops; q returns to the shell with 0.
The map comes from tests/peers/topdown_talker.py (rospy) in frame "map"."""

from __future__ import annotations

import math
import shlex
import sys
from pathlib import Path
from typing import Iterator

import pytest

from conftest import SYSTEM_PYTHON
from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from test_topdown_tools import GOAL, TWIST, map_and_listener, received, yaw
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "TOOLS_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("tools", 80, 24) as pane:
        yield pane


def test_goal_and_teleop_with_keys_in_tmux(pane: Pane, ros_env: dict[str, str], rostui_core: object, spawn: Spawn,
                                           rospy_available: None) -> None:
    listener = map_and_listener(spawn, f"/goal={GOAL}", f"/cmd_vel={TWIST}")
    values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    pane.type(f"env -u COLUMNS -u LINES {assignments} {shlex.quote(sys.executable)} -m rostui view /map "
              f"--frame map --goal-topic /goal; echo {EXIT_MARK}$?")
    pane.wait_until(lambda: pane.shows("■ /map", "frame map"), "the map's view")
    pane.keys("g")
    pane.wait_until(lambda: pane.shows("→ /goal (1 sub)  Enter send  Esc cancel"), "the goal cursor, rospy connected")
    before = next(line for line in pane.screen().splitlines() if "→ /goal (1 sub)" in line)
    pane.keys("Right", "Right", "Right", "Right", "Up", "Up", "a", "a", "a", "a", "a", "a")
    pane.wait_until(lambda: "90° → /goal" in pane.screen(), "the cursor turned to 90 degrees")
    line = next(line for line in pane.screen().splitlines() if "→ /goal (1 sub)" in line)
    x, y = (float(v) for v in line.split("GOAL ")[1].split()[0].split(","))
    x0, y0 = (float(v) for v in before.split("GOAL ")[1].split()[0].split(","))
    assert x > x0 and y > y0, (before, line)
    pane.keys("Enter")
    pane.wait_until(lambda: len(received(listener, "/goal", GOAL)) == 1, "the goal at rospy")
    goal = received(listener, "/goal", GOAL)[0]
    assert (round(goal.pose.position.x, 2), round(goal.pose.position.y, 2)) == (x, y)
    assert math.isclose(yaw(goal.pose.orientation), math.pi / 2, abs_tol=1e-6) and goal.header.frame_id == "map"
    pane.wait_until(lambda: pane.shows("sent goal"), "the sent line")
    pane.keys("t")
    pane.wait_until(lambda: pane.shows("TELEOP → /cmd_vel (1 sub)"), "teleop's line, rospy connected")
    pane.keys("Up")
    pane.wait_until(lambda: len(received(listener, "/cmd_vel", TWIST)) >= 1, "a twist at rospy")
    pane.keys("Escape")
    pane.wait_until(lambda: [(t.linear.x, t.angular.z) for t in received(listener, "/cmd_vel", TWIST)][-1:]
                    == [(0.0, 0.0)], "the stop on Escape")
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")


def test_a_view_saved_on_quit_opens_again_as_it_was(pane: Pane, ros_env: dict[str, str], rostui_core: object,
                                                    spawn: Spawn, rospy_available: None, tmp_path: Path) -> None:
    """`--save FILE`: zoomed in and panned, then q: the file says where; `rostui view FILE` opens that picture."""
    talker = spawn([SYSTEM_PYTHON, str(PEERS / "topdown_talker.py"), "rospy"], label="rospy topdown talker")
    talker.wait_for("ready")
    saved = tmp_path / "nav.yaml"
    values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    command = (f"env -u COLUMNS -u LINES {' '.join(f'{k}={shlex.quote(v)}' for k, v in values.items())} "
               f"{shlex.quote(sys.executable)} -m rostui view")
    pane.type(f"{command} /map /scan --frame map --save {shlex.quote(str(saved))}; echo {EXIT_MARK}$?")
    pane.wait_until(lambda: pane.shows("■ /map", "■ /scan", "frame map   centre 0.00, 0.00"), "the view")
    pane.keys("+", "Left")
    pane.wait_until(lambda: "frame map   centre -" in pane.screen(), "the view zoomed and panned")
    status = next(line for line in pane.screen().splitlines() if "frame map   centre" in line)
    picture = status.split("   ")[0] + "   " + "   ".join(status.split("   ")[1:3])  # scale bar, frame, centre
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "exit status 0 after q")
    assert f"rostui view: saved the view to {saved}" in pane.screen().replace("\n", "")
    text = saved.read_text()
    assert "topics: [/map, /scan]" in text and "frame: map" in text and "span:" in text
    pane.clear()
    pane.type(f"{command} {shlex.quote(str(saved))}; echo {EXIT_MARK}$?")
    pane.wait_until(lambda: pane.shows("■ /map", "■ /scan", picture), f"the saved picture again: {picture!r}")
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "exit status 0 after q")
