"""tf2_ros.static_transform_broadcaster: ``StaticTransformBroadcaster`` latches transforms on /tf_static."""

from __future__ import annotations

from typing import Any

import rospy

from rostui.core.msg import get_message_class

from .transform_broadcaster import as_list

__all__ = ["StaticTransformBroadcaster"]


class StaticTransformBroadcaster:
    """A latched /tf_static publisher: every call replaces what late subscribers get (as tf2_ros)."""

    def __init__(self, queue_size: int = 100) -> None:
        self.pub_tf = rospy.Publisher("/tf_static", get_message_class("tf2_msgs/TFMessage"), queue_size=queue_size,
                                      latch=True)

    def sendTransform(self, transform: Any) -> None:  # noqa: N802 (tf2_ros's name)
        """Publish one ``TransformStamped`` or a list of them, in one latched message."""
        self.pub_tf.publish(get_message_class("tf2_msgs/TFMessage")(as_list(transform)))
