"""Chapter 9, Recording and replaying messages: the bag of squares.

draw_square drives the turtle while ``rostui bag record -O square.bag`` records the velocity commands and
poses; ``rostui bag info`` describes the bag as rosbag does; ``rostui bag play`` makes the turtle move again
from wherever it is, as ``rostui bag view`` does once asked to publish; 9.3's ``rosbag`` package executables run the same commands from rosrun and launch files.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from book_helpers import (
    Desk, desk, dot_edges, lines, ok, poll, settled_pose, start_core, start_turtlesim_view, status_pose,
)

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

ANON = r"\d+_\d+"


def test_bag_of_squares(desk: Desk, tmp_path: Path) -> None:
    env = desk.env
    start_core(desk)
    sim = start_turtlesim_view(desk)

    # 9.2: draw_square resets the turtle and drives it around a square.
    square = desk.terminal("square")
    square.run("rostui run turtlesim draw_square")
    poll(lambda: "/draw_square" in lines(ok("node list", env)), "draw_square to register")

    # Recording a bag of squares.
    record = desk.terminal("record")
    record.run("rostui bag record -O square.bag /turtle1/command_velocity /turtle1/pose")
    record.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: Recording to 'square\.bag'\.$")
    record.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: Subscribing to /turtle1/command_velocity$")
    record.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: Subscribing to /turtle1/pose$")
    recorder = next(n for n in lines(ok("node list", env)) if n.startswith("/record_"))
    assert re.fullmatch(rf"/record_{ANON}", recorder)
    graph = dot_edges(ok("graph --dot --book", env))  # Figure 9.1
    assert {("/draw_square", "/turtle1/command_velocity", ""), ("/turtle1/command_velocity", "/turtlesim", ""),
            ("/turtle1/command_velocity", recorder, ""), ("/turtle1/pose", recorder, "")} <= graph
    start = status_pose(sim)
    assert start is not None
    poll(lambda: math.dist((status_pose(sim) or start)[:2], start[:2]) > 1.5, "the turtle to draw part of a square")
    assert record.interrupt() == 0
    record.wait_for(r"Recorded \d+ messages to square\.bag")
    assert square.interrupt() == 0

    # Inspecting the bag (rosbag info's layout).
    info = ok(f"bag info {tmp_path / 'square.bag'}", env)
    assert re.search(r"^version:\s+2\.0$", info, re.MULTILINE)
    assert re.search(r"^duration:\s+\d+(\.\d)?s$", info, re.MULTILINE)
    assert re.search(r"^start:\s+\w{3} \d\d \d{4} \d\d:\d\d:\d\d\.\d\d \(\d+\.\d\d\)$", info, re.MULTILINE)
    assert re.search(r"^compression:\s+none \[\d+/\d+ chunks\]$", info, re.MULTILINE)
    assert re.search(r"^types:\s+turtlesim/Pose\s+\[863b248d5016ca62ea2e895ae5265cf9\]\n"
                     r"\s+turtlesim/Velocity \[9d5c2dcd348ac8f76ce2a4307bd63a13\]$", info, re.MULTILINE), info
    counts = dict(re.findall(r"(/turtle1/\w+)\s+(\d+) msgs\s+: turtlesim/\w+\s*$", info, re.MULTILINE))
    assert set(counts) == {"/turtle1/command_velocity", "/turtle1/pose"}, info
    total = int(re.search(r"^messages:\s+(\d+)$", info, re.MULTILINE)[1])  # type: ignore[index]
    assert total == sum(int(n) for n in counts.values())
    assert int(counts["/turtle1/pose"]) > 20 and int(counts["/turtle1/command_velocity"]) > 5

    # Replaying the bag of squares: the turtle moves again, from where it stands (Figure 9.2).
    before = status_pose(sim)
    play = desk.terminal("play")
    play.run("rostui bag play square.bag")
    poll(lambda: any(n.startswith("/play_") for n in lines(ok("node list", env))), "rosbag play's node")
    player = next(n for n in lines(ok("node list", env)) if n.startswith("/play_"))
    assert re.fullmatch(rf"/play_{ANON}", player)
    assert {(player, "/turtle1/command_velocity", ""), ("/turtle1/command_velocity", "/turtlesim", "")} <= dot_edges(
        ok("graph --dot --book", env))
    publishers = ok("topic info /turtle1/pose", env).split("Subscribers:")[0]
    assert "/turtlesim" in publishers and player in publishers  # two nodes claim to know the pose
    poll(lambda: status_pose(sim) not in (None, before), "the turtle to move under the bag's commands")
    assert play.exit_status(timeout=120) == 0  # play ends with the bag

    # rqt_bag's part: bag view plays the bag on screen and publishes nothing until asked (t: the selected topic).
    view = desk.terminal("view")
    view.run("rostui bag view square.bag")
    view.wait_for(r"not publishing")
    still = settled_pose(sim)
    view.keys("8", "Space")  # the last fifth of the bag
    view.wait_for(r"■ END")
    assert status_pose(sim) == still and not any(n.startswith("/bag_view_") for n in lines(ok("node list", env)))
    view.keys("t")  # the first row, selected from the start
    view.wait_for(r"publishing 1 topic as\s+/bag_view_")  # the header wraps at 80 columns
    view.wait_for(r"● /turtle1/comm")
    view.keys("Home", "Space")
    poll(lambda: status_pose(sim) != still, "the turtle to move under the commands bag view publishes")
    view.keys("q")
    assert view.exit_status() == 0

    # 9.3: the rosbag package's record and play executables, from rosrun and from a launch file.
    shell = desk.terminal("shell")
    shell.run("rostui run rosbag play -q square.bag")
    poll(lambda: any(n.startswith("/play_") for n in lines(ok("node list", env))), "rosrun rosbag play's node")
    assert shell.exit_status(timeout=120) == 0
    (tmp_path / "bags.launch").write_text(
        '<launch>\n'
        f'  <node pkg="rosbag" name="record" type="record" args="-O {tmp_path}/again.bag /turtle1/pose" />\n'
        '</launch>\n')
    launch = desk.terminal("launch")
    launch.run("rostui launch bags.launch")
    poll(lambda: "/record" in lines(ok("node list", env)), "the launch file's record node")
    poll(lambda: (tmp_path / "again.bag").exists() or (tmp_path / "again.bag.active").exists(), "again.bag")
    assert launch.interrupt(timeout=90) in (0, 130)
    assert re.search(r"^topics:\s+/turtle1/pose\s+\d+ msgs?\s+: turtlesim/Pose\s*$",
                     ok(f"bag info {tmp_path / 'again.bag'}", env), re.MULTILINE)
