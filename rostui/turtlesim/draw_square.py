"""draw_square: reset turtlesim, then drive turtle1 round and round a 2 m square.

Behaves like ROS turtlesim's ``draw_square`` tutorial node: it calls the
``reset`` service (waiting for it to appear first, so it also works when
started before the simulator), then every 16 ms looks at the latest
``turtle1/pose`` and commands the turtle through four phases per side: drive
forward at 1 m/s until 2 m from where the side began, stop, turn at 0.4 rad/s
until a quarter turn is done, stop.  Goals are checked against the pose
(0.1 m, 0.01 rad), so the square stays square whatever the message timing.

Commands go out as ``geometry_msgs/Twist`` on ``turtle1/cmd_vel`` and, for the
book (chapter 9 records ``/turtle1/command_velocity`` from draw_square), as
``turtlesim/Velocity`` on ``turtle1/command_velocity`` with the same values.
"""

from __future__ import annotations

import enum
import math
import sys
from dataclasses import dataclass
from typing import Any, Callable

__all__ = ["Goal", "Phase", "SquareDriver", "main"]

SIDE = 2.0
"""Length of a side of the square, in metres."""

FORWARD_SPEED = 1.0
TURN_SPEED = 0.4
POSITION_TOLERANCE = 0.1
ANGLE_TOLERANCE = 0.01
STOPPED_SPEED = 0.0001
TIMER_PERIOD = 0.016


class Phase(enum.Enum):
    """What the turtle is doing on the current side."""

    FORWARD = "forward"
    STOP_FORWARD = "stop_forward"
    TURN = "turn"
    STOP_TURN = "stop_turn"


@dataclass
class Goal:
    """Where the current phase should leave the turtle."""

    x: float
    y: float
    theta: float


def _angle_between(a: float, b: float) -> float:
    """The absolute difference of two headings, in [0, pi]."""
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


def _wrap(angle: float) -> float:
    """An angle in [-pi, pi)."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


class SquareDriver:
    """The square-drawing state machine, free of ROS: pose in, command out.

    ``log`` receives the progress lines (``New goal [...]``, ``Reached goal``).
    """

    def __init__(self, log: Callable[[str], None] = lambda _line: None) -> None:
        self.phase = Phase.FORWARD
        self.goal: Goal | None = None
        self.log = log

    def step(self, pose: Any) -> tuple[float, float] | None:
        """The ``(linear, angular)`` command for this tick, or None when none is due.

        ``pose`` has turtlesim/Pose's fields (x, y, theta, linear_velocity,
        angular_velocity).
        """
        if self.goal is None:
            self._goal_ahead(pose)
        if self.phase is Phase.FORWARD:
            return self._move_until_goal(pose, Phase.STOP_FORWARD, (FORWARD_SPEED, 0.0))
        if self.phase is Phase.TURN:
            return self._move_until_goal(pose, Phase.STOP_TURN, (0.0, TURN_SPEED))
        if not self._stopped(pose):
            return 0.0, 0.0
        self.log("Reached goal")
        if self.phase is Phase.STOP_FORWARD:
            self.phase = Phase.TURN
            self._set_goal(Goal(pose.x, pose.y, _wrap(pose.theta + math.pi / 2)))
        else:
            self.phase = Phase.FORWARD
            self._goal_ahead(pose)
        return None

    def _move_until_goal(self, pose: Any, next_phase: Phase, command: tuple[float, float]) -> tuple[float, float]:
        if self._reached(pose):
            self.phase = next_phase
            return 0.0, 0.0
        return command

    def _goal_ahead(self, pose: Any) -> None:
        self._set_goal(Goal(pose.x + SIDE * math.cos(pose.theta), pose.y + SIDE * math.sin(pose.theta), pose.theta))

    def _set_goal(self, goal: Goal) -> None:
        self.goal = goal
        self.log(f"New goal [{goal.x:f} {goal.y:f}, {goal.theta:f}]")

    def _reached(self, pose: Any) -> bool:
        goal = self.goal
        assert goal is not None
        return (abs(pose.x - goal.x) < POSITION_TOLERANCE and abs(pose.y - goal.y) < POSITION_TOLERANCE
                and _angle_between(pose.theta, goal.theta) < ANGLE_TOLERANCE)

    @staticmethod
    def _stopped(pose: Any) -> bool:
        return abs(pose.linear_velocity) < STOPPED_SPEED and abs(pose.angular_velocity) < STOPPED_SPEED


def main(argv: list[str] | None = None) -> int:
    """The ``draw_square`` node; ``argv`` is the full command line (default ``sys.argv``)."""
    from rostui import client as ros

    Pose = ros.msg("turtlesim/Pose")
    Twist = ros.msg("geometry_msgs/Twist")
    Velocity = ros.msg("turtlesim/Velocity")
    Empty = ros.srv("std_srvs/Empty")

    try:
        ros.init_node("draw_square", argv=sys.argv if argv is None else argv)
    except ros.ROSInterruptException:
        return 0
    latest: dict[str, Any] = {}
    twist_pub = ros.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    velocity_pub = ros.Publisher("turtle1/command_velocity", Velocity, queue_size=1)
    driver = SquareDriver(ros.loginfo)

    def tick(_event: Any) -> None:
        if "pose" not in latest:
            return
        command = driver.step(latest["pose"])
        if command is None:
            return
        twist: Any = Twist()  # a generated class: its fields are not known statically
        twist.linear.x, twist.angular.z = command
        twist_pub.publish(twist)
        velocity_pub.publish(Velocity(linear=command[0], angular=command[1]))

    try:
        ros.wait_for_service("reset")
        ros.ServiceProxy("reset", Empty)()
    except ros.ServiceException as exc:
        ros.logwarn("Could not reset the simulation: %s", exc)
    except ros.ROSException:
        if ros.is_shutdown():
            return 0
        raise

    # Subscribed only now, so that every pose the driver sees is from after the reset.
    def on_pose(pose: Any) -> None:
        latest["pose"] = pose

    ros.Subscriber("turtle1/pose", Pose, on_pose, queue_size=1)
    ros.Timer(TIMER_PERIOD, tick)
    ros.spin()
    return 0
