"""draw_square and mimic against `rostui core` and a headless rostui turtlesim."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Iterator

import pytest

from rostui.turtlesim.draw_square import Phase, SquareDriver

from live_helpers import Program, Recording, Watcher, start_headless_sim, stop_all, wait_until

CENTRE = 5.544445


class FakePose:
    """The fields of turtlesim/Pose the driver reads."""

    def __init__(self, x: float, y: float, theta: float, linear: float = 0.0, angular: float = 0.0) -> None:
        self.x, self.y, self.theta = x, y, theta
        self.linear_velocity, self.angular_velocity = linear, angular


@pytest.fixture
def sim(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[tuple[Watcher, list[Any]]]:
    """A headless turtlesim (turtle1 publishing its pose) and a watcher; the list collects things to stop."""
    watcher = Watcher()
    items: list[Any] = [watcher]
    try:
        items.append(start_headless_sim(ros_env, tmp_path))
        pose = watcher.record("/turtle1/pose", "turtlesim/Pose")
        pose.wait_for_count(1, "turtlesim to publish /turtle1/pose")
        yield watcher, items
    finally:
        stop_all(items)


def near(pose: Any, x: float, y: float, tolerance: float = 0.25) -> bool:
    """True when the pose is within ``tolerance`` metres of (x, y) on both axes."""
    return abs(pose.x - x) < tolerance and abs(pose.y - y) < tolerance


def test_driver_sets_goals_two_metres_ahead_and_quarter_turns() -> None:
    lines: list[str] = []
    driver = SquareDriver(lines.append)
    assert driver.step(FakePose(1.0, 1.0, 0.0)) == (1.0, 0.0)
    assert driver.goal is not None and (driver.goal.x, driver.goal.y) == (3.0, 1.0)
    assert driver.step(FakePose(3.0, 1.0, 0.0, linear=1.0)) == (0.0, 0.0)
    assert driver.phase is Phase.STOP_FORWARD
    assert driver.step(FakePose(3.0, 1.0, 0.0, linear=1.0)) == (0.0, 0.0)  # still moving: stop again
    assert driver.step(FakePose(3.0, 1.0, 0.0)) is None
    assert driver.phase is Phase.TURN and driver.goal.theta == pytest.approx(math.pi / 2)
    assert driver.step(FakePose(3.0, 1.0, 0.5)) == (0.0, 0.4)
    assert driver.step(FakePose(3.0, 1.0, math.pi / 2 + 0.005, angular=0.4)) == (0.0, 0.0)
    assert lines[:3] == ["New goal [3.000000 1.000000, 0.000000]", "Reached goal",
                         "New goal [3.000000 1.000000, 1.570796]"]


def test_driver_turns_across_the_pi_boundary() -> None:
    driver = SquareDriver()
    driver.phase = Phase.STOP_FORWARD
    driver.step(FakePose(1.0, 1.0, math.pi / 2 + 0.001))
    driver.step(FakePose(1.0, 1.0, math.pi / 2 + 0.001))
    assert driver.phase is Phase.TURN
    assert driver.step(FakePose(1.0, 1.0, -math.pi + 0.002, angular=0.4)) == (0.0, 0.0)  # pi and -pi meet


def test_draw_square_resets_then_drives_a_two_metre_square(sim: tuple[Watcher, list[Any]],
                                                           ros_env: dict[str, str], tmp_path: Path) -> None:
    watcher, items = sim
    watcher.call("/turtle1/teleport_absolute", "turtlesim/TeleportAbsolute", x=1.0, y=1.0, theta=1.0)
    poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
    poses.wait_for(lambda p: near(p, 1.0, 1.0, 0.01), "the teleported pose")
    velocities = watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    program = Program(ros_env, tmp_path, "turtlesim", "draw_square")
    items.append(program)
    corners = [(CENTRE, CENTRE), (CENTRE + 2, CENTRE), (CENTRE + 2, CENTRE + 2), (CENTRE, CENTRE + 2),
               (CENTRE, CENTRE)]
    visited: list[int] = []  # index in poses of the first pose near each corner, in order

    def visited_every_corner() -> bool:
        messages = poses.messages
        while len(visited) < len(corners):
            start = visited[-1] if visited else 0
            hit = next((i for i, p in enumerate(messages[start:], start) if near(p, *corners[len(visited)])), None)
            if hit is None:
                return False
            visited.append(hit)
        return True
    wait_until(visited_every_corner, "the turtle to visit the corners of the square in order", 120)
    reset_pose = poses.messages[visited[0]]
    assert reset_pose.theta == pytest.approx(0.0, abs=0.05)
    program.wait_for_output(r"New goal \[7\.5\d+ 5\.5\d+, 0\.0+\]")
    assert any(v.linear == 1.0 and v.angular == 0.0 for v in velocities.messages)
    assert any(v.linear == 0.0 and v.angular == pytest.approx(0.4) for v in velocities.messages)


def test_mimic_makes_turtle2_copy_turtle1(sim: tuple[Watcher, list[Any]], ros_env: dict[str, str],
                                         tmp_path: Path) -> None:
    watcher, items = sim
    assert watcher.call("/spawn", "turtlesim/Spawn", x=2.0, y=2.0, theta=0.0, name="turtle2").name == "turtle2"
    turtle2: Recording = watcher.record("/turtle2/pose", "turtlesim/Pose")
    start = turtle2.wait_for_count(1, "turtle2's pose")[-1]
    commands = watcher.record("/turtle2/cmd_vel", "geometry_msgs/Twist")
    items.append(Program(ros_env, tmp_path, "turtlesim", "mimic", "input:=turtle1", "output:=turtle2"))
    commands.wait_connected()
    drive = watcher.publisher("/turtle1/cmd_vel", "geometry_msgs/Twist")
    Twist = drive.msg_class

    def driven() -> bool:
        twist = Twist()
        twist.linear.x, twist.angular.z = 1.0, 0.5
        drive.publish(twist)
        return any(m.linear_velocity == 1.0 and m.angular_velocity == 0.5 for m in turtle2.messages)
    wait_until(driven, "turtle2 to take turtle1's velocities")
    wait_until(lambda: driven() and math.dist((turtle2.messages[-1].x, turtle2.messages[-1].y),
                                              (start.x, start.y)) > 0.3, "turtle2 to move")
    assert any(m.linear.x == 1.0 and m.angular.z == 0.5 for m in commands.messages)
