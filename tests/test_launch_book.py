"""The book's launch files (chapter 6, 7.4) under `rostui launch`: the graphs and behaviour the book describes.

Launched nodes have no terminal, so turtlesim_node runs headless; the book's
teleop nodes use ``launch-prefix="xterm -e"``, which needs xterm and a display.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Iterator

import pytest

from conftest import master_port, wait_for_port, wait_until
from launch_helpers import launch_env
from live_helpers import Watcher
from test_launch_supervisor import Launch, gone

CENTRE = 5.544445


@pytest.fixture
def book(ros_env: dict[str, str], tmp_path: Path) -> Iterator["Book"]:
    session = Book(launch_env(ros_env), tmp_path)
    try:
        yield session
    finally:
        session.close()


class Book:
    """One `rostui launch agitr FILE` and a watcher node on its master."""

    def __init__(self, env: dict[str, str], tmp: Path) -> None:
        self.env = env
        self.tmp = tmp
        self.launch: Launch | None = None
        self.watcher: Watcher | None = None

    def start(self, name: str, *args: str) -> Watcher:
        self.launch = Launch(["agitr", name, *args], self.env, self.tmp)
        wait_for_port(master_port(self.env), timeout=60)
        self.watcher = Watcher()
        return self.watcher

    def close(self) -> None:
        if self.watcher is not None:
            self.watcher.close()
        if self.launch is not None:
            children = self.launch.descendants()
            self.launch.interrupt()
            assert gone([c.pid for c in children])  # nothing the launch started outlives it


def test_doublesim_runs_two_independent_simulators(book: Book) -> None:
    watcher = book.start("doublesim.launch")
    for node in ("/sim1/turtlesim_node", "/sim2/turtlesim_node", "/sim2/velocity_publisher"):
        wait_until(lambda: watcher.lookup_node(node), f"{node} to register", timeout=60)
    sim1 = watcher.record("/sim1/turtle1/pose", "turtlesim/Pose")
    sim2 = watcher.record("/sim2/turtle1/pose", "turtlesim/Pose")
    sim2.wait_for(lambda p: abs(p.x - CENTRE) > 0.05 or abs(p.y - CENTRE) > 0.05, "the /sim2 turtle to move")
    first = sim1.wait_for_count(5)
    assert all((p.x, p.y) == (first[0].x, first[0].y) for p in sim1.messages)  # nobody drives /sim1
    assert book.launch is not None
    if shutil.which("xterm") is None:
        assert "cannot launch node [/sim1/teleop_key]: launch-prefix program 'xterm' is not installed" \
            in book.launch.err


def test_reverse_drives_the_turtle_backwards(book: Book) -> None:
    watcher = book.start("reverse.launch")
    wait_until(lambda: watcher.lookup_node("/reverse_velocity"), "reverse_velocity to register", timeout=60)
    poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
    start = poses.wait_for_count(1)[0]
    assert start.theta == 0.0  # facing +x: a forward command would raise x
    command = watcher.publisher("/turtle1/command_velocity", "turtlesim/Velocity")
    wait_until(lambda: command.get_num_connections() > 0, "reverse_velocity to subscribe")

    def moved_back() -> bool:
        command.publish(linear=2.0, angular=0.0)
        return bool(poses.messages) and poses.messages[-1].x < CENTRE - 0.5

    wait_until(moved_back, "the turtle to drive backwards", timeout=60)


def test_fast_yellow_sets_max_vel_and_a_yellow_background(book: Book) -> None:
    watcher = book.start("fast_yellow.launch")
    wait_until(lambda: watcher.lookup_node("/publish_velocity"), "publish_velocity to register", timeout=60)
    assert watcher.get_param("/publish_velocity/max_vel") == 3
    colours = watcher.record("/turtle1/color_sensor", "turtlesim/Color")
    colours.wait_for(lambda c: (c.r, c.g, c.b) == (255, 255, 0), "the background to turn yellow")
    assert [watcher.get_param(f"/background_{c}") for c in "rgb"] == [255, 255, 0]
