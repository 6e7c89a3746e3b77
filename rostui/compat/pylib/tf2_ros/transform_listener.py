"""tf2_ros.transform_listener: ``TransformListener`` feeds a buffer from /tf and /tf_static."""

from __future__ import annotations

import threading
from typing import Any

import rospy

from rostui.core.msg import get_message_class

__all__ = ["TransformListener"]


class TransformListener:
    """Subscribes /tf and /tf_static (tf2_msgs/TFMessage) and gives every transform to ``buffer``.

    Each transform's authority is the sending node (the connection's ``callerid``). When ROS time goes
    backwards (a bag played again) the buffer is cleared first, with a warning, as tf2_ros does.
    """

    def __init__(self, buffer: Any, queue_size: Any = None, buff_size: int = 65536, tcp_nodelay: bool = False) -> None:
        self.buffer = buffer
        self.last_update = rospy.Time.now()
        self.last_update_lock = threading.Lock()
        tf_message = get_message_class("tf2_msgs/TFMessage")
        options = {"queue_size": queue_size, "buff_size": buff_size, "tcp_nodelay": tcp_nodelay}
        self.tf_sub = rospy.Subscriber("/tf", tf_message, self.callback, **options)
        self.tf_static_sub = rospy.Subscriber("/tf_static", tf_message, self.static_callback, **options)

    def __del__(self) -> None:
        try:
            self.unregister()
        except Exception:  # noqa: BLE001 (a half-made listener at interpreter exit has nothing left to stop)
            pass

    def unregister(self) -> None:
        """Stop listening."""
        self.tf_sub.unregister()
        self.tf_static_sub.unregister()

    def check_for_reset(self) -> None:
        """Clear the buffer when ROS time moved backwards since the last message."""
        with self.last_update_lock:
            now = rospy.Time.now()
            if now < self.last_update:
                rospy.logwarn("Detected jump back in time of %fs. Clearing TF buffer." % (self.last_update - now).to_sec())
                self.buffer.clear()
            self.last_update = now

    def callback(self, data: Any) -> None:
        """Take a /tf message."""
        self.check_for_reset()
        who = _authority(data)
        for transform in data.transforms:
            self.buffer.set_transform(transform, who)

    def static_callback(self, data: Any) -> None:
        """Take a /tf_static message."""
        self.check_for_reset()
        who = _authority(data)
        for transform in data.transforms:
            self.buffer.set_transform_static(transform, who)


def _authority(msg: Any) -> str:
    header = getattr(msg, "_connection_header", None) or {}
    return str(header.get("callerid", "default_authority"))
