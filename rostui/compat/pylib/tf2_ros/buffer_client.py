"""``tf2_ros.BufferClient``: lookups asked of a tf2 buffer server (``tf2_ros buffer_server``) through its action.

A node that does not keep a buffer of its own sends each lookup as a ``tf2_msgs/LookupTransform`` goal to the
server's action namespace and gets the transform, or the server's error as tf2's exception of that kind.
"""

from __future__ import annotations

from typing import Any

import rospy
import tf2_py
from actionlib import GoalStatus, SimpleActionClient

from rostui.core.msg import get_message_class

from .buffer_interface import BufferInterface

__all__ = ["BufferClient"]

LookupTransformAction: Any = get_message_class("tf2_msgs/LookupTransformAction")
LookupTransformGoal: Any = get_message_class("tf2_msgs/LookupTransformGoal")
NO_ANSWER = ("The LookupTransform goal sent to the BufferServer did not come back in the specified time. Something "
             "is likely wrong with the server")
NOT_SUCCEEDED = ("The LookupTransform goal sent to the BufferServer did not come back with SUCCEEDED status. "
                 "Something is likely wrong with the server.")


def _error_classes() -> dict[int, type[Exception]]:
    """tf2's exception for each error code of tf2_msgs/TF2Error."""
    error: Any = get_message_class("tf2_msgs/TF2Error")
    return {error.LOOKUP_ERROR: tf2_py.LookupException, error.CONNECTIVITY_ERROR: tf2_py.ConnectivityException,
            error.EXTRAPOLATION_ERROR: tf2_py.ExtrapolationException,
            error.INVALID_ARGUMENT_ERROR: tf2_py.InvalidArgumentException,
            error.TIMEOUT_ERROR: tf2_py.TimeoutException}


class BufferClient(BufferInterface):
    """A tf2 buffer answered by the buffer server at action namespace *ns*; a lookup waits its *timeout* plus
    *timeout_padding* for the answer."""

    def __init__(self, ns: str, check_frequency: float | None = None,
                 timeout_padding: Any = rospy.Duration.from_sec(2.0)) -> None:
        super().__init__()
        self.client = SimpleActionClient(ns, LookupTransformAction)
        self.timeout_padding = timeout_padding
        if check_frequency is not None:
            rospy.logwarn("Argument check_frequency is deprecated and should not be used.")

    def wait_for_server(self, timeout: Any = rospy.Duration()) -> bool:
        """Wait for the server's action to be there (for ever with a zero timeout)."""
        return self.client.wait_for_server(timeout)

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any,
                         timeout: Any = rospy.Duration(0.0)) -> Any:
        """The transform from *source_frame* to *target_frame* at *time*, as the server's buffer gives it."""
        return self._ask(LookupTransformGoal(target_frame=target_frame, source_frame=source_frame, source_time=time,
                                             timeout=timeout, advanced=False))

    def lookup_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                              fixed_frame: str, timeout: Any = rospy.Duration(0.0)) -> Any:
        """The transform between two frames at two times, through *fixed_frame*."""
        return self._ask(LookupTransformGoal(target_frame=target_frame, source_frame=source_frame,
                                             source_time=source_time, timeout=timeout, target_time=target_time,
                                             fixed_frame=fixed_frame, advanced=True))

    def can_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = rospy.Duration(0.0)) -> bool:
        """Whether the server can give that transform."""
        try:
            self.lookup_transform(target_frame, source_frame, time, timeout)
        except tf2_py.TransformException:
            return False
        return True

    def can_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                           fixed_frame: str, timeout: Any = rospy.Duration(0.0)) -> bool:
        """Whether the server can give that transform (the advanced form)."""
        try:
            self.lookup_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        except tf2_py.TransformException:
            return False
        return True

    def _ask(self, goal: Any) -> Any:
        self.client.send_goal(goal)
        if not self.client.wait_for_result(goal.timeout + self.timeout_padding):
            raise tf2_py.TimeoutException(NO_ANSWER)
        if self.client.get_state() != GoalStatus.SUCCEEDED:
            raise tf2_py.TimeoutException(NOT_SUCCEEDED)
        result = self.client.get_result()
        if not result:
            raise tf2_py.TransformException(
                "The BufferServer returned None for result!  Something is likely wrong with the server.")
        error = result.error
        if error.error != error.NO_ERROR:
            raise _error_classes().get(error.error, tf2_py.TransformException)(error.error_string)
        return result.transform
