"""tf.broadcaster: tf's ``TransformBroadcaster``, a tuple-taking face of tf2_ros's."""

from __future__ import annotations

from typing import Any, Sequence

import tf2_ros

from rostui.core.msg import get_message_class

__all__ = ["TransformBroadcaster"]


class TransformBroadcaster:
    """Publishes on /tf; ``queue_size`` is taken and, as in tf, not used (tf2_ros's broadcaster keeps 100)."""

    def __init__(self, queue_size: int = 100) -> None:
        self.tf2_broadcaster = tf2_ros.TransformBroadcaster()

    def sendTransform(self, translation: Sequence[float], rotation: Sequence[float], time: Any, child: str,  # noqa: N802
                      parent: str) -> None:
        """Send the pose of frame ``child`` in frame ``parent`` at ``time``: translation (x, y, z), rotation (x, y, z, w)."""
        t: Any = get_message_class("geometry_msgs/TransformStamped")()
        t.header.frame_id = parent
        t.header.stamp = time
        t.child_frame_id = child
        tr, rot = t.transform.translation, t.transform.rotation
        tr.x, tr.y, tr.z = translation[0], translation[1], translation[2]
        rot.x, rot.y, rot.z, rot.w = rotation[0], rotation[1], rotation[2], rotation[3]
        self.sendTransformMessage(t)

    def sendTransformMessage(self, transform: Any) -> None:  # noqa: N802 (tf's name)
        """Send one ``geometry_msgs/TransformStamped``."""
        self.tf2_broadcaster.sendTransform([transform])
