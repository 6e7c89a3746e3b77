"""tf2_geometry_msgs for unmodified ROS 1 scripts: transform stamped geometry messages, and register them for
``Buffer.transform``.

Importing it registers PointStamped, Vector3Stamped, PoseStamped and WrenchStamped with tf2_ros, as
the real module does. Each ``do_transform_*`` returns a new message whose header is the transform's
(its target frame and stamp). The arithmetic is KDL's (rotation matrices from the quaternions, the
orientation read back as KDL reads it), so results equal the real module's, signs of quaternions included.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import tf2_ros

from rostui.core.msg import get_message_class
from rostui.tools.tf.transform import kdl_quaternion, kdl_rotation

__all__ = ["do_transform_point", "do_transform_pose", "do_transform_vector3", "do_transform_wrench",
           "from_msg_msg", "to_msg_msg", "transform_to_kdl"]

PointStamped: Any = get_message_class("geometry_msgs/PointStamped")
PoseStamped: Any = get_message_class("geometry_msgs/PoseStamped")
Vector3Stamped: Any = get_message_class("geometry_msgs/Vector3Stamped")
WrenchStamped: Any = get_message_class("geometry_msgs/WrenchStamped")


def to_msg_msg(msg: Any) -> Any:
    """A message is its own message form."""
    return msg


def from_msg_msg(msg: Any) -> Any:
    """A message made from its message form: itself."""
    return msg


def transform_to_kdl(t: Any) -> tuple[np.ndarray, np.ndarray]:
    """The rotation matrix and translation of a ``TransformStamped`` (KDL's Frame, as plain arrays)."""
    tr, q = t.transform.translation, t.transform.rotation
    return kdl_rotation((q.x, q.y, q.z, q.w)), np.array([tr.x, tr.y, tr.z], dtype=np.float64)


def _moved(rotation: np.ndarray, translation: np.ndarray, x: float, y: float, z: float) -> list[float]:
    return [float(v) for v in rotation @ np.array([x, y, z], dtype=np.float64) + translation]


def do_transform_point(point: Any, transform: Any) -> Any:
    """A ``PointStamped`` moved by ``transform``."""
    rotation, translation = transform_to_kdl(transform)
    res = PointStamped()
    p = point.point
    res.point.x, res.point.y, res.point.z = _moved(rotation, translation, p.x, p.y, p.z)
    res.header = transform.header
    return res


def do_transform_vector3(vector3: Any, transform: Any) -> Any:
    """A ``Vector3Stamped`` turned by ``transform``'s rotation (a direction: no translation)."""
    rotation, _ = transform_to_kdl(transform)
    res = Vector3Stamped()
    v = vector3.vector
    res.vector.x, res.vector.y, res.vector.z = _moved(rotation, np.zeros(3), v.x, v.y, v.z)
    res.header = transform.header
    return res


def do_transform_pose(pose: Any, transform: Any) -> Any:
    """A ``PoseStamped`` moved by ``transform``: position moved, orientation composed."""
    rotation, translation = transform_to_kdl(transform)
    p, q = pose.pose.position, pose.pose.orientation
    res = PoseStamped()
    res.pose.position.x, res.pose.position.y, res.pose.position.z = _moved(rotation, translation, p.x, p.y, p.z)
    o = res.pose.orientation
    o.x, o.y, o.z, o.w = kdl_quaternion(rotation @ kdl_rotation((q.x, q.y, q.z, q.w)))
    res.header = transform.header
    return res


def do_transform_wrench(wrench: Any, transform: Any) -> Any:
    """A ``WrenchStamped`` with force and torque each turned as a vector."""
    res = WrenchStamped()
    force, torque = Vector3Stamped(), Vector3Stamped()
    force.vector, torque.vector = copy.deepcopy(wrench.wrench.force), copy.deepcopy(wrench.wrench.torque)
    res.wrench.force = do_transform_vector3(force, transform).vector
    res.wrench.torque = do_transform_vector3(torque, transform).vector
    res.header = transform.header
    return res


for _cls in (Vector3Stamped, PoseStamped, PointStamped):
    tf2_ros.ConvertRegistration().add_to_msg(_cls, to_msg_msg)
    tf2_ros.ConvertRegistration().add_from_msg(_cls, from_msg_msg)
tf2_ros.TransformRegistration().add(PointStamped, do_transform_point)
tf2_ros.TransformRegistration().add(Vector3Stamped, do_transform_vector3)
tf2_ros.TransformRegistration().add(PoseStamped, do_transform_pose)
tf2_ros.TransformRegistration().add(WrenchStamped, do_transform_wrench)
