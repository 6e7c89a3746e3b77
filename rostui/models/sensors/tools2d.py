"""What the top-down view sends, as rviz's tools send it: "2D Nav Goal", "2D Pose Estimate", and teleop.

- A goal is a geometry_msgs/PoseStamped in the fixed frame, stamped now, on
  ``/move_base_simple/goal`` (rviz's SetGoal tool).
- A pose estimate is a geometry_msgs/PoseWithCovarianceStamped on
  ``/initialpose`` with rviz's covariance: 0.5 m standard deviation in x and y,
  pi/12 in yaw (rviz's SetInitialPose tool).
- Teleop sends a geometry_msgs/Twist on ``/cmd_vel`` for each key, at
  teleop_twist_keyboard's speeds (0.5 m/s, 1.0 rad/s); leaving it sends a stop.

Nothing here talks to a master: :class:`ToolSender` is given the node.
"""

from __future__ import annotations

import asyncio
import math
from dataclasses import dataclass
from enum import Enum
from typing import Any

from rostui.core.msg import get_message_class
from rostui.core.node.clock import CLOCK_TOPIC as CLOCK
from rostui.core.node.clock import USE_SIM_TIME_PARAM as USE_SIM_TIME
from rostui.core.rostime import Time
from rostui.models.sensors.pose2d import Pose2D

__all__ = ["Tool", "ToolTopics", "ToolSender", "goal_message", "initial_pose_message", "twist_message",
           "heading_quaternion", "POSE_STD_XY", "POSE_STD_YAW", "TELEOP_LINEAR", "TELEOP_ANGULAR"]

#: rviz's SetInitialPose standard deviations (metres, radians).
POSE_STD_XY = 0.5
POSE_STD_YAW = math.pi / 12.0

#: Teleop speeds (teleop_twist_keyboard's defaults).
TELEOP_LINEAR = 0.5
TELEOP_ANGULAR = 1.0


class Tool(Enum):
    """A mode of the view's cursor."""

    GOAL = "goal"
    POSE = "pose estimate"
    TELEOP = "teleop"


@dataclass(frozen=True)
class ToolTopics:
    """Where each tool sends (rviz's defaults; `rostui view --goal-topic` and the others change them)."""

    goal: str = "/move_base_simple/goal"
    pose: str = "/initialpose"
    cmd_vel: str = "/cmd_vel"

    def of(self, tool: Tool) -> str:
        """The topic ``tool`` sends on."""
        return {Tool.GOAL: self.goal, Tool.POSE: self.pose, Tool.TELEOP: self.cmd_vel}[tool]


TOOL_TYPES = {Tool.GOAL: "geometry_msgs/PoseStamped", Tool.POSE: "geometry_msgs/PoseWithCovarianceStamped",
              Tool.TELEOP: "geometry_msgs/Twist"}


def heading_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation by ``yaw`` about z."""
    return 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def _place(pose: Any, where: Pose2D) -> None:
    pose.position.x, pose.position.y, pose.position.z = where.x, where.y, 0.0
    q = pose.orientation
    q.x, q.y, q.z, q.w = heading_quaternion(where.yaw)


def goal_message(frame: str, where: Pose2D, stamp: Time) -> Any:
    """The PoseStamped rviz's "2D Nav Goal" sends for ``where`` in ``frame``."""
    msg: Any = get_message_class(TOOL_TYPES[Tool.GOAL])()
    msg.header.frame_id, msg.header.stamp = frame, stamp
    _place(msg.pose, where)
    return msg


def initial_pose_message(frame: str, where: Pose2D, stamp: Time) -> Any:
    """The PoseWithCovarianceStamped rviz's "2D Pose Estimate" sends for ``where`` in ``frame``."""
    msg: Any = get_message_class(TOOL_TYPES[Tool.POSE])()
    msg.header.frame_id, msg.header.stamp = frame, stamp
    _place(msg.pose.pose, where)
    covariance = [0.0] * 36
    covariance[6 * 0 + 0] = POSE_STD_XY ** 2
    covariance[6 * 1 + 1] = POSE_STD_XY ** 2
    covariance[6 * 5 + 5] = POSE_STD_YAW ** 2
    msg.pose.covariance = covariance
    return msg


def twist_message(forward: float, turn: float) -> Any:
    """A Twist of ``forward`` x :data:`TELEOP_LINEAR` m/s and ``turn`` x :data:`TELEOP_ANGULAR` rad/s."""
    msg: Any = get_message_class(TOOL_TYPES[Tool.TELEOP])()
    msg.linear.x = forward * TELEOP_LINEAR
    msg.angular.z = turn * TELEOP_ANGULAR
    return msg


class ToolSender:
    """The publishers of the tools on ``node`` (an AsyncNode), each advertised when first used, never before;
    stamps in ROS time, as rviz stamps: ``/clock`` when the master's ``/use_sim_time`` is true."""

    def __init__(self, node: Any, topics: ToolTopics) -> None:
        self.node = node
        self.topics = topics
        self._publishers: dict[Tool, Any] = {}
        self._lock = asyncio.Lock()
        self._sim_time: Time | None = None
        self._clock: Any = None

    async def advertise(self, tool: Tool) -> Any:
        """``tool``'s publisher, advertised now if it was not (the view advertises as a mode opens, so the
        robot's subscriber is connected by the time a key sends; nothing is latched, as in rviz: a goal is not
        sent again to a node that starts later).  One at a time: a key pressed while a mode opens waits."""
        async with self._lock:
            publisher = self._publishers.get(tool)
            if publisher is None:
                await self._follow_sim_time()
                cls = get_message_class(TOOL_TYPES[tool])
                publisher = await self.node.advertise(self.topics.of(tool), cls)
                self._publishers[tool] = publisher
            return publisher

    async def _follow_sim_time(self) -> None:
        """Under ``/use_sim_time``, keep the newest ``/clock`` for :meth:`now` (asked of the master once)."""
        if self._clock is not None:
            return
        self._clock = False
        try:
            sim = await self.node.master_call("getParam", USE_SIM_TIME)
        except Exception:  # unset (the master refuses getParam of an unset name): the wall clock
            sim = False
        if sim is True:
            self._sim_time = Time(0, 0)

            def tick(msg: Any) -> None:
                self._sim_time = Time(msg.clock.secs, msg.clock.nsecs)

            self._clock = await self.node.subscribe(CLOCK, get_message_class("rosgraph_msgs/Clock"), tick)

    def now(self) -> Time:
        """ROS time: the newest ``/clock`` under simulated time (zero before one came), else the wall clock."""
        return Time(self._sim_time.secs, self._sim_time.nsecs) if self._sim_time is not None else Time.now()

    async def send(self, tool: Tool, msg: Any) -> str:
        """Publish ``msg`` on ``tool``'s topic; the topic's name."""
        (await self.advertise(tool)).publish(msg)
        return self.topics.of(tool)

    def connections(self, tool: Tool) -> int:
        """Subscribers connected to ``tool``'s publisher (0 before it was advertised)."""
        publisher = self._publishers.get(tool)
        return publisher.get_num_connections() if publisher is not None else 0

    async def close(self) -> None:
        """Unadvertise every publisher (and leave ``/clock``)."""
        publishers, self._publishers = list(self._publishers.values()), {}
        if self._clock:
            publishers.append(self._clock)
        self._clock = None
        for publisher in publishers:
            try:
                await publisher.unregister()
            except Exception:  # the node or the master went first: nothing left to undo
                pass
