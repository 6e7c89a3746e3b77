"""tf2_ros.transform_broadcaster: ``TransformBroadcaster`` publishes transforms on /tf."""

from __future__ import annotations

from typing import Any

import rospy

from rostui.core.msg import get_message_class

__all__ = ["TransformBroadcaster", "as_list"]


def as_list(transform: Any) -> list[Any]:
    """One transform or several (a list, or any iterable) as a list."""
    if isinstance(transform, list):
        return transform
    if hasattr(transform, "__iter__"):
        return list(transform)
    return [transform]


class TransformBroadcaster:
    """A /tf publisher (tf2_msgs/TFMessage, queue of 100)."""

    def __init__(self, queue_size: int = 100) -> None:
        self.pub_tf = rospy.Publisher("/tf", get_message_class("tf2_msgs/TFMessage"), queue_size=queue_size)

    def sendTransform(self, transform: Any) -> None:  # noqa: N802 (tf2_ros's name)
        """Publish one ``TransformStamped`` or a list of them, in one message."""
        self.pub_tf.publish(get_message_class("tf2_msgs/TFMessage")(as_list(transform)))
