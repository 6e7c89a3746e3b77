"""What an action's generated ``XAction`` class gives the client and the server: its six message types."""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Any

import rospy

from rostui.core.msg import get_message_class

__all__ = ["ActionException", "ActionTypes", "GoalIDGenerator", "action_types", "queue_size_param"]

GoalID: Any = get_message_class("actionlib_msgs/GoalID")


class ActionException(Exception):
    """A class given as an action spec that is not one."""


@dataclass(frozen=True)
class ActionTypes:
    """The message classes of one action: the three wire messages and the three parts users handle."""

    action_goal: Any
    action_result: Any
    action_feedback: Any
    goal: Any
    result: Any
    feedback: Any


def action_types(spec: Any) -> ActionTypes:
    """The types of action ``spec`` (an ``XAction`` class); ActionException if it is not one."""
    try:
        action = spec()
        return ActionTypes(type(action.action_goal), type(action.action_result), type(action.action_feedback),
                           type(action.action_goal.goal), type(action.action_result.result),
                           type(action.action_feedback.feedback))
    except AttributeError:
        raise ActionException("Type is not an action spec: %s" % str(spec)) from None


def queue_size_param(name: str, default: int | None) -> int | None:
    """A queue size from the parameter ``name`` (searched as rospy reads it); negative means the default."""
    value = rospy.get_param(name, default if default is not None else -1)
    return default if value is None or int(value) < 0 else int(value)


class GoalIDGenerator:
    """Goal ids for goals that came without one: ``<node>-<count>-<secs>.<nsecs>``, the count shared by the process."""

    _count = 0
    _lock = threading.Lock()

    def __init__(self, name: str | None = None) -> None:
        self.name = rospy.get_name() if name is None else name

    def set_name(self, name: str) -> None:
        """Use ``name`` in the ids from now on."""
        self.name = name

    def generate_ID(self) -> Any:  # noqa: N802 (actionlib's name)
        """A new ``actionlib_msgs/GoalID``, stamped now."""
        with GoalIDGenerator._lock:
            GoalIDGenerator._count += 1
            count = GoalIDGenerator._count
        now = rospy.Time.now()
        return GoalID(id=f"{self.name}-{count}-{now.secs}.{now.nsecs}", stamp=now)
