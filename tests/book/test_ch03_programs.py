"""Chapter 3, Writing ROS programs: a package of your own, hello, pubvel (at 2 Hz) and subpose.

rostui has nothing to build: a package is a directory with a package.xml on
ROS_PACKAGE_PATH, and its Python scripts run with ``rostui run``.  The book's
own programs ship as the built-in package ``agitr``.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from book_helpers import (
    Desk, cli, desk, dot_edges, lines, ok, poll, start_core, start_turtlesim_view, status_pose,
)

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

HELLO = re.compile(r"^\[ INFO\] \[\d+\.\d+\]: Hello, ROS!$", re.MULTILINE)
SENDING = r"^\[ INFO\] \[\d+\.\d+\]: Sending random velocity command: linear=\S+ angular=\S+$"
POSITION = re.compile(r"^\[ INFO\] \[\d+\.\d+\]: position=\((\d+\.\d\d),(\d+\.\d\d)\) direction=(-?\d+\.\d\d)$",
                      re.MULTILINE)


def test_own_package_hello_pubvel_and_subpose(desk: Desk, tmp_path: Path) -> None:
    env = desk.env
    start_core(desk)
    shell = desk.terminal("shell")

    # 3.1-3.2: a package of your own; the book's hello, copied from agitr, runs from it.
    agitr = ok("pkg find agitr", env).strip()
    assert {"hello", "pubvel", "subpose", "package.xml"} <= set(lines(ok("pkg ls agitr", env)))
    shell.run(f"mkdir -p ws/src/mine && cp {agitr}/package.xml {agitr}/hello ws/src/mine/ && "
              "sed -i 's|<name>agitr</name>|<name>mine</name>|' ws/src/mine/package.xml && "
              "export ROS_PACKAGE_PATH=$PWD/ws/src && rostui run mine hello")
    assert shell.exit_status() == 0
    assert HELLO.search(shell.screen(200))
    assert (tmp_path / "ws/src/mine/hello").is_file()
    shell.run("rostui run mien hello")
    assert shell.exit_status() == 2
    shell.wait_for(r"^\[rospack\] Error: package 'mien' not found$")
    hello = cli("run agitr hello", env)
    assert hello.returncode == 0 and HELLO.search(hello.stdout), hello.stderr

    # 3.3: pubvel drives the turtlesim turtle at random, 2 commands a second.
    sim = start_turtlesim_view(desk)
    pubvel = desk.terminal("pubvel")
    pubvel.run("rostui run agitr pubvel")
    pubvel.wait_for(SENDING)
    poll(lambda: status_pose(sim) not in (None, (5.54, 5.54, 0.0)), "the turtle to wander")
    hz = desk.terminal("hz")
    hz.run("rostui topic hz /turtle1/command_velocity")
    hz.wait_for(r"(average rate: .*\n.*\n(.*\n)?){3}")
    rates = [float(r) for r in re.findall(r"^average rate: (\d+\.\d+)$", hz.screen(200), re.MULTILINE)]
    assert 1.8 < rates[-1] < 2.2, rates
    gaps = re.findall(r"^\s*min: (\d+\.\d+)s max: (\d+\.\d+)s std dev: \d+\.\d+s window: \d+$", hz.screen(200),
                      re.MULTILINE)
    assert gaps and all(0.3 < float(low) <= float(high) < 0.75 for low, high in gaps[-1:]), gaps
    hz.interrupt()

    # 3.4: subpose logs the pose turtlesim publishes.
    subpose = desk.terminal("subpose")
    subpose.run("rostui run agitr subpose")
    # A pose line per message, 62.5 a second: five in a row can be alike when pubvel's random command is
    # slow and turns little, or the turtle sits against a wall, so wait for it to move under pubvel.
    def logged_moving() -> bool:
        positions = POSITION.findall(subpose.screen(100))
        return len(positions) >= 5 and len(set(positions)) > 1
    poll(logged_moving, "five pose lines or more from subpose, the turtle moving")
    edges = dot_edges(ok("graph --dot", env))
    assert {("/publish_velocity", "/turtlesim", "/turtle1/command_velocity"),
            ("/turtlesim", "/subscribe_to_pose", "/turtle1/pose")} <= edges

    # Stopping pubvel: rosnode kill, or Ctrl-C in its terminal.
    ok("node kill /publish_velocity", env)
    assert pubvel.exit_status() == 0
    assert subpose.interrupt() == 0
    assert lines(ok("node list", env)) == ["/rosout", "/turtlesim"]
