"""actionlib for unmodified ROS 1 scripts: action clients and servers, simple and full, on rostui's rospy.

``SimpleActionClient``, ``SimpleActionServer``, ``ActionClient``, ``ActionServer`` and their goal handles
speak actionlib's protocol (goal, cancel, status, feedback and result topics under the action's
namespace), so they work with real actionlib clients and servers, Python or C++. ``actionlib.msg`` holds
the package's test actions (``TestAction``...), served by rostui's message modules.
"""

from __future__ import annotations

from rostui.core.msg import get_message_class

from .action_client import ActionClient, ClientGoalHandle, CommStateMachine, GoalManager
from .action_server import ActionServer, nop_cb
from .server_goal_handle import ServerGoalHandle, StatusTracker
from .simple_action_client import SimpleActionClient
from .simple_action_server import SimpleActionServer
from .spec import ActionException, GoalIDGenerator
from .states import (
    INVALID_TRANSITION, NO_TRANSITION, CommState, GoalStatus, SimpleGoalState, TerminalState, get_name_of_constant,
)

GoalID = get_message_class("actionlib_msgs/GoalID")
GoalStatusArray = get_message_class("actionlib_msgs/GoalStatusArray")
Header = get_message_class("std_msgs/Header")

__all__ = [
    "ActionClient", "ActionException", "ActionServer", "ClientGoalHandle", "CommState", "CommStateMachine",
    "GoalID", "GoalIDGenerator", "GoalManager", "GoalStatus", "GoalStatusArray", "Header", "INVALID_TRANSITION",
    "NO_TRANSITION", "ServerGoalHandle", "SimpleActionClient", "SimpleActionServer", "SimpleGoalState",
    "StatusTracker", "TerminalState", "get_name_of_constant", "nop_cb",
]
