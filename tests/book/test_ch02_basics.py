"""Chapter 2, Getting started: the book's turtlesim session, step by step, with rostui in tmux terminals.

2.3 core, simulator and teleop in three terminals; 2.4 packages; 2.6 nodes;
2.7 the graph, topics, echo, hz/bw, info, message types and pub; 2.8 the
larger example with nodes A, B, C, D; 2.9 wtf.
"""

from __future__ import annotations

import math
import os
import re
import signal

import pytest

from book_helpers import (
    Desk, cli, desk, dot_edges, dot_nodes, dot_topics, drive, lines, ok, poll, start_core, start_teleop,
    start_turtlesim_view, status_pose,
)

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

TURTLE_TOPICS = {"/turtle1/command_velocity", "/turtle1/pose", "/turtle1/color_sensor"}
TURTLESIM_SERVICES = {"/clear", "/kill", "/reset", "/spawn", "/turtle1/set_pen", "/turtle1/teleport_absolute",
                      "/turtle1/teleport_relative", "/turtlesim/get_loggers", "/turtlesim/set_logger_level"}


def test_turtlesim_in_three_terminals(desk: Desk) -> None:
    env = desk.env
    # 2.3: roscore, turtlesim_node and turtle_teleop_key in three terminals; the arrow keys drive the turtle.
    start_core(desk)
    sim = start_turtlesim_view(desk)
    teleop = start_teleop(desk)
    drive(teleop, sim, "Up", "the turtle to drive forward")
    drive(teleop, sim, "Left", "the turtle to turn")

    # 2.4: packages.
    assert "turtlesim" in [line.split()[0] for line in lines(ok("pkg list", env))]
    turtlesim_dir = ok("pkg find turtlesim", env).strip()
    listing = set(lines(ok("pkg ls turtlesim", env)))
    assert {"msg", "srv", "package.xml"} <= listing
    assert turtlesim_dir.endswith("turtlesim")

    # 2.6: nodes.
    assert lines(ok("node list", env)) == ["/rosout", "/teleop_turtle", "/turtlesim"]
    info = ok("node info /turtlesim", env)
    assert re.search(r"^Node \[/turtlesim\]$", info, re.MULTILINE)
    assert re.search(r"^Pid: \d+$", info, re.MULTILINE)
    publications = info.split("Publications:")[1].split("Subscriptions:")[0]
    assert "* /turtle1/pose [turtlesim/Pose]" in publications
    assert "* /turtle1/command_velocity [turtlesim/Velocity]" in info.split("Subscriptions:")[1]

    # 2.7.1: the graph (Figure 2.2: nodes only, debug hidden; 2.3: debug shown; 2.4: the book's setup).
    nodes_only = ok("graph --dot", env)
    assert dot_nodes(nodes_only) == {"/teleop_turtle", "/turtlesim"}
    assert ("/teleop_turtle", "/turtlesim", "/turtle1/command_velocity") in dot_edges(nodes_only)
    debug = ok("graph --dot --show-debug", env)
    assert "/rosout" in dot_nodes(debug)
    assert {("/teleop_turtle", "/rosout", "/rosout"), ("/turtlesim", "/rosout", "/rosout")} <= dot_edges(debug)
    book = ok("graph --dot --book", env)
    assert TURTLE_TOPICS <= dot_topics(book)
    assert {("/teleop_turtle", "/turtle1/command_velocity", ""), ("/turtle1/command_velocity", "/turtlesim", ""),
            ("/turtlesim", "/turtle1/pose", ""), ("/turtlesim", "/turtle1/color_sensor", "")} <= dot_edges(book)

    graph = desk.terminal("graph")
    graph.run("rostui graph --book")
    graph.wait_for(r"│ /teleop_turtle │")
    assert "Nodes/Topics (all) · hide debug" in graph.screen() and "/rosout" not in graph.screen()
    graph.wait_for(r"\barrows scroll\s*$")  # Figure 2.4 is wider than the reader's 80 columns
    graph.keys(*["Right"] * 30)
    graph.wait_for(r"/turtle1/color_sensor")
    graph.keys("q")
    assert graph.exit_status() == 0

    # 2.7.2: topics, echo (Listing 2.2), info (Listing 2.3), message types.
    assert TURTLE_TOPICS | {"/rosout", "/rosout_agg"} <= set(lines(ok("topic list", env)))
    echo = desk.terminal("echo")
    echo.run("rostui topic echo /turtle1/command_velocity")
    poll(lambda: "/rostopic_" in ok("node list", env), "rostopic's echo node to register")
    teleop.keys("Up")
    echo.wait_for(r"^linear: 2\.0\nangular: 0\.0\n---$")
    teleop.keys("Left")
    echo.wait_for(r"^linear: 0\.0\nangular: 2\.0\n---$")
    info = ok("topic info /turtle1/command_velocity", env)
    assert re.fullmatch(
        r"Type: turtlesim/Velocity\n\nPublishers: \n \* /teleop_turtle \(http://[\w.]+:\d+/\)\n\n"
        r"Subscribers: \n( \* /(turtlesim|rostopic_\d+_\d+) \(http://[\w.]+:\d+/\)\n){2}\n*", info), info
    assert echo.interrupt() in (0, 1, 130)
    assert ok("msg show turtlesim/Velocity", env).strip() == "float32 linear\nfloat32 angular"

    # Measuring rates: turtlesim publishes its pose at 62.5 Hz.
    hz = desk.terminal("hz")
    hz.run("rostui topic hz /turtle1/pose")
    rates = [float(m) for m in re.findall(r"^average rate: (\d+\.\d+)$",
                                          hz.wait_for(r"(average rate: .*\n(.*\n){1}){3}")[0], re.MULTILINE)]
    assert rates and 40.0 < rates[-1] < 80.0, rates
    hz.wait_for(r"^\s*min: \d+\.\d+s max: \d+\.\d+s std dev: \d+\.\d+s window: \d+$")
    hz.interrupt()
    bw = desk.terminal("bw")
    bw.run("rostui topic bw /turtle1/pose")
    bw.wait_for(r"^average: \d+(\.\d+)? ?[KM]?B/s$")
    bw.interrupt()

    # Publishing messages from the command line: -r 1 with field values, then one YAML dict (latched).
    pub = desk.terminal("pub")
    start = status_pose(sim)
    assert start is not None
    pub.run("rostui topic pub -r 1 /turtle1/command_velocity turtlesim/Velocity 1 0")
    poll(lambda: math.dist((status_pose(sim) or start)[:2], start[:2]) > 0.5, "the turtle to drive straight ahead")
    pub.interrupt()
    pub.run("rostui topic pub /turtle1/command_velocity turtlesim/Velocity \"linear: 0.1\nangular: 0.0\"")
    pub.wait_for(r"publishing and latching message\. Press ctrl-C to terminate")
    pub.interrupt()

    # 2.9: checking for problems.
    wtf = cli("wtf", env)
    assert wtf.returncode == 0, wtf.stdout + wtf.stderr
    assert wtf.stdout.strip() == "No errors or warnings"

    # 2.6: killing a node.
    assert "killed" in ok("node kill /teleop_turtle", env)
    assert teleop.exit_status() == 0
    assert lines(ok("node list", env)) == ["/rosout", "/turtlesim"]

    # A node that dies without unregistering stays listed until `rosnode cleanup`.
    doomed = desk.terminal("doomed")
    doomed.run("rostui run turtlesim turtle_teleop_key __name:=doomed")
    doomed.wait_for(r"Use arrow keys to move the turtle")
    pid = re.search(r"^Pid: (\d+)$", ok("node info /doomed", env), re.MULTILINE)[1]  # type: ignore[index]
    os.kill(int(pid), signal.SIGKILL)
    assert doomed.exit_status() == 128 + signal.SIGKILL
    assert "/doomed" in lines(ok("node list", env))
    cleanup = desk.terminal("cleanup")
    cleanup.run("rostui node cleanup")
    cleanup.wait_for(r"^Unable to contact the following nodes:\n \* /doomed$")
    cleanup.wait_for(r"^Please type y or n to continue:$")
    cleanup.type("y")
    assert cleanup.exit_status() == 0
    cleanup.wait_for(r"^Unregistering /doomed\ndone$")
    assert lines(ok("node list", env)) == ["/rosout", "/turtlesim"]
    sim.keys("q")
    assert sim.exit_status() == 0


def test_a_larger_example_two_simulators_two_teleops(desk: Desk) -> None:
    env = desk.env
    # 2.8: four nodes renamed with __name; every teleop drives both turtles (Figure 2.5).
    start_core(desk)
    a = start_turtlesim_view(desk, "A", "__name:=A")
    c = start_teleop(desk, "C", "__name:=C")
    b = start_turtlesim_view(desk, "B", "__name:=B")
    d = start_teleop(desk, "D", "__name:=D")
    assert lines(ok("node list", env)) == ["/A", "/B", "/C", "/D", "/rosout"]
    edges = dot_edges(ok("graph --dot", env))
    assert {(teleop, sim, "/turtle1/command_velocity") for teleop in ("/C", "/D") for sim in ("/A", "/B")} <= edges
    book = ok("graph --dot --book", env)
    assert {("/C", "/turtle1/command_velocity", ""), ("/D", "/turtle1/command_velocity", ""),
            ("/turtle1/command_velocity", "/A", ""), ("/turtle1/command_velocity", "/B", "")} <= dot_edges(book)
    for teleop in (c, d):
        before_a, before_b = status_pose(a), status_pose(b)
        drive(teleop, a, "Up", f"turtle A to move on {teleop.name}'s keys")
        poll(lambda: status_pose(b) != before_b, f"turtle B to move on {teleop.name}'s keys too")
        assert before_a != status_pose(a)

    # Two nodes with the same name: the original one is shut down by the master.
    again = desk.terminal("A2")
    again.run("rostui run turtlesim turtlesim_node --headless __name:=A")
    assert a.exit_status() == 0
    a.wait_for(r"^\[ WARN\] \[\d+\.\d+\]: Shutdown request received\. "
               r"Reason given for shutdown: \[.*new node registered with same name\]$")
    poll(lambda: cli("node ping -c 1 /A", env).returncode == 0, "the new /A to answer")
    assert lines(ok("node list", env)) == ["/A", "/B", "/C", "/D", "/rosout"]
