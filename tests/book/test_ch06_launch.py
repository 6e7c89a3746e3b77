"""Chapter 6, Launch files: example.launch, doublesim.launch (Figure 6.1), a remapping on the command line,
reverse.launch (Figure 6.3) and triplesim.launch with use_sim3:=1, each launched with ``rostui launch`` in a
terminal that has no master yet.

The book starts turtle_teleop_key with ``launch-prefix="xterm -e"``.  Without xterm (a terminal over SSH),
``rostui launch`` says so and keeps the other nodes running; the reader then runs the teleop in a second
terminal, under the name the launch file gives it.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from book_helpers import Desk, Terminal, cli, desk, dot_edges, dot_nodes, lines, ok, poll

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

POSITION = re.compile(r"position=\((\d+\.\d\d),(\d+\.\d\d)\) direction=(-?\d+\.\d\d)$", re.MULTILINE)
NO_XTERM = "launch-prefix program 'xterm' is not installed"


def launch(desk: Desk, name: str, line: str, expect_nodes: set[str]) -> Terminal:
    """Type ``rostui launch LINE`` in a new terminal; wait until every node of ``expect_nodes`` registered."""
    terminal = desk.terminal(name)
    terminal.run(f"rostui launch {line}")
    poll(lambda: expect_nodes <= _node_list(desk), f"the nodes of {line}")
    return terminal


def _node_list(desk: Desk) -> set[str]:
    """The master's node list, empty when no master answers."""
    result = cli("node list", desk.env)
    return set(lines(result.stdout)) if result.returncode == 0 else set()


def _pid(env: dict[str, str], node: str) -> int | None:
    """The pid ``rostui node info NODE`` reports, None while the node does not answer."""
    match = re.search(r"^Pid: (\d+)$", cli(f"node info {node}", env).stdout, re.MULTILINE)
    return int(match[1]) if match else None


def teleop_in_second_terminal(desk: Desk, launched: Terminal, name: str, args: str) -> Terminal:
    """Where the launch could not open xterm, the reader starts the launch file's teleop node by hand."""
    if shutil.which("xterm") is None:
        launched.wait_for(re.escape(f"cannot launch node [{name}]: {NO_XTERM}"))
    teleop = desk.terminal(f"teleop{len(desk.terminals)}")
    teleop.run(f"rostui run turtlesim turtle_teleop_key {args}")
    teleop.wait_for(r"Use arrow keys to move the turtle")
    return teleop


def stop(terminal: Terminal, desk: Desk) -> None:
    """Ctrl-C the launch: every node it started is gone, and the master it started too."""
    assert terminal.interrupt(timeout=90) in (0, 130)
    assert cli("node list", desk.env).returncode != 0


def test_launch_files_of_chapter_6(desk: Desk) -> None:
    env = desk.env

    # 6.1: example.launch starts a master and three nodes; subpose's output is on the screen (output="screen").
    example = launch(desk, "example", "-v agitr example.launch", {"/turtlesim", "/pose_subscriber", "/rosout"})
    example.wait_for(r"node /turtlesim: turtlesim/turtlesim_node")
    example.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: position=\(5\.54,5\.54\) direction=0\.00$")
    teleop = teleop_in_second_terminal(desk, example, "/teleop_key", "__name:=teleop_key")
    assert _node_list(desk) == {"/turtlesim", "/teleop_key", "/pose_subscriber", "/rosout"}
    assert {("/teleop_key", "/turtle1/command_velocity", ""), ("/turtle1/command_velocity", "/turtlesim", ""),
            ("/turtlesim", "/turtle1/pose", ""), ("/turtle1/pose", "/pose_subscriber", "")} <= dot_edges(
        ok("graph --dot --book", env))

    def moved() -> bool:
        teleop.keys("Up")
        return any(float(x) > 5.6 for x, _, _ in POSITION.findall(example.screen(50)))
    poll(moved, "subpose to log the turtle driving forward")
    # turtlesim's standard output went to a log file; respawn="true" brings it back when it dies.
    run_id = ok("param get /run_id", env).strip()
    assert (Path(env["ROS_HOME"]) / "log" / run_id / "turtlesim-1-stdout.log").exists()
    first_pid = _pid(env, "/turtlesim")
    ok("node kill /turtlesim", env)
    poll(lambda: _pid(env, "/turtlesim") not in (None, first_pid), "turtlesim to respawn with a new pid")
    assert teleop.interrupt() == 0
    stop(example, desk)

    # 6.3: doublesim.launch, two simulators in namespaces sim1 and sim2 (Figure 6.1).
    double = launch(desk, "double", "agitr doublesim.launch",
                    {"/sim1/turtlesim_node", "/sim2/turtlesim_node", "/sim2/velocity_publisher"})
    teleop = teleop_in_second_terminal(desk, double, "/sim1/teleop_key", "__ns:=sim1 __name:=teleop_key")
    graph = ok("graph --dot --book", env)
    assert {"/sim1/teleop_key", "/sim1/turtlesim_node", "/sim2/turtlesim_node",
            "/sim2/velocity_publisher"} <= dot_nodes(graph)
    assert {("/sim1/teleop_key", "/sim1/turtle1/command_velocity", ""),
            ("/sim1/turtle1/command_velocity", "/sim1/turtlesim_node", ""),
            ("/sim1/turtlesim_node", "/sim1/turtle1/pose", ""),
            ("/sim1/turtlesim_node", "/sim1/turtle1/color_sensor", ""),
            ("/sim2/velocity_publisher", "/sim2/turtle1/command_velocity", ""),
            ("/sim2/turtle1/command_velocity", "/sim2/turtlesim_node", ""),
            ("/sim2/turtlesim_node", "/sim2/turtle1/pose", ""),
            ("/sim2/turtlesim_node", "/sim2/turtle1/color_sensor", "")} <= dot_edges(graph)
    assert teleop.interrupt() == 0
    stop(double, desk)

    # 6.4.1: a remapping on the command line: turtlesim publishes its pose on /tim.
    reverse = launch(desk, "reverse", "agitr reverse.launch", {"/turtlesim", "/reverse_velocity"})
    remapped = desk.terminal("remapped")
    remapped.run("rostui run turtlesim turtlesim_node --headless __name:=tim_sim turtle1/pose:=tim")
    poll(lambda: "/tim" in lines(ok("topic list", env)), "the pose on /tim")
    assert ("/tim_sim", "/tim", "") in dot_edges(ok("graph --dot --book", env))
    assert remapped.interrupt() == 0

    # 6.4.2: reverse.launch; the teleop's commands reach turtlesim reversed (Figure 6.3).
    teleop = teleop_in_second_terminal(desk, reverse, "/teleop_key", "__name:=teleop_key")
    graph = ok("graph --dot --book", env)
    assert {("/teleop_key", "/turtle1/command_velocity", ""),
            ("/turtle1/command_velocity", "/reverse_velocity", ""),
            ("/reverse_velocity", "/turtle1/command_velocity_reversed", ""),
            ("/turtle1/command_velocity_reversed", "/turtlesim", "")} <= dot_edges(graph)
    assert ("/turtle1/command_velocity", "/turtlesim", "") not in dot_edges(graph)

    def backwards() -> bool:
        teleop.keys("Up")
        pose = ok("topic echo -n 1 /turtle1/pose", env)
        return float(re.search(r"^x: (\S+)$", pose, re.MULTILINE)[1]) < 5.0
    poll(backwards, "Up to drive the turtle backwards")
    assert teleop.interrupt() == 0
    stop(reverse, desk)

    # A launch file by its path, without the package; --nodes lists what it would start.
    path = Path(ok("pkg find agitr", env).strip()) / "example.launch"
    assert lines(ok(f"launch {path} --nodes", env)) == ["/turtlesim", "/teleop_key", "/pose_subscriber"]

    # 6.5: triplesim.launch includes doublesim.launch; use_sim3:=1 adds a third simulator in sim3.
    assert "/sim3/turtlesim_node" not in ok("launch agitr triplesim.launch --nodes", env)
    triple = launch(desk, "triple", "agitr triplesim.launch use_sim3:=1",
                    {"/sim1/turtlesim_node", "/sim2/turtlesim_node", "/sim3/turtlesim_node"})
    graph = ok("graph --dot --book", env)
    assert {("/sim3/turtle1/command_velocity", "/sim3/turtlesim_node", ""),
            ("/sim3/turtlesim_node", "/sim3/turtle1/pose", ""),
            ("/sim2/velocity_publisher", "/sim2/turtle1/command_velocity", "")} <= dot_edges(graph)
    stop(triple, desk)
