"""tf2_ros.buffer: ``Buffer``, tf2's BufferCore with waiting lookups, ``transform`` and the ``~tf2_frames`` service.

A lookup with a timeout waits (polling at a hundredth of the timeout, as tf2_ros does) until the
transform can be answered, the timeout passes, or ROS time jumps back (a bag starting over); then it
answers or raises tf2's exception. With ``debug`` (the default) the node offers ``~tf2_frames``
(tf2_msgs/FrameGraph, the frames as YAML) unless it already does.
"""

from __future__ import annotations

from typing import Any

import rospy
import tf2_py

from rostui.core.msg import get_service_class

from .buffer_interface import BufferInterface

__all__ = ["Buffer", "DEFAULT_CAN_TRANSFORM_POLLING_SCALE"]

DEFAULT_CAN_TRANSFORM_POLLING_SCALE = 0.01
"""The fraction of a lookup's timeout it sleeps between two tries."""

_BAG_LOOP_JUMP = 3.0


class Buffer(tf2_py.BufferCore, BufferInterface):
    """The tf2 buffer scripts make: ``Buffer(cache_time=None, debug=True)``."""

    def __init__(self, cache_time: Any = None, debug: bool = True) -> None:
        tf2_py.BufferCore.__init__(self, cache_time)
        BufferInterface.__init__(self)
        self.CAN_TRANSFORM_POLLING_SCALE = DEFAULT_CAN_TRANSFORM_POLLING_SCALE
        if debug:
            self._offer_frames_service()

    def _offer_frames_service(self) -> None:
        frame_graph = get_service_class("tf2_msgs/FrameGraph")
        code, _, _ = rospy.get_master().lookupService("~tf2_frames")
        if code != 1:
            self.frame_server = rospy.Service("~tf2_frames", frame_graph,
                                              lambda _: frame_graph._response_class(self.all_frames_as_yaml()))

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        """The ``TransformStamped`` from ``source_frame`` to ``target_frame`` at ``time``, waiting up to ``timeout``."""
        self.can_transform(target_frame, source_frame, time, timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    def lookup_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                              fixed_frame: str, timeout: Any = None) -> Any:
        """The advanced lookup (two times and a fixed frame), waiting up to ``timeout``."""
        self.can_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        return self.lookup_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)

    def can_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None,
                      return_debug_tuple: bool = False) -> Any:
        """Whether the lookup answers, waiting up to ``timeout``; ``(answer, why)`` with ``return_debug_tuple``."""
        self._wait(timeout, lambda: self.can_transform_core(target_frame, source_frame, time)[0])
        result = self.can_transform_core(target_frame, source_frame, time)
        return result if return_debug_tuple else result[0]

    def can_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                           fixed_frame: str, timeout: Any = None, return_debug_tuple: bool = False) -> Any:
        """:meth:`can_transform` for the advanced lookup."""
        def answers() -> Any:
            return self.can_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)[0]

        self._wait(timeout, answers)
        result = self.can_transform_full_core(target_frame, target_time, source_frame, source_time, fixed_frame)
        return result if return_debug_tuple else result[0]

    def _wait(self, timeout: Any, answers: Any) -> None:
        """Sleep in steps until ``answers()``, the timeout passes (ROS time), or time jumps back by seconds."""
        if timeout is None or timeout == rospy.Duration(0.0):
            return
        start = rospy.Time.now()
        step = timeout * self.CAN_TRANSFORM_POLLING_SCALE
        while True:
            now = rospy.Time.now()
            if not now < start + timeout or answers() or now + rospy.Duration(_BAG_LOOP_JUMP) < start:
                return
            rospy.sleep(step)
