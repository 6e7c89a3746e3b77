"""Odometry, paths, poses and pose arrays as planar poses and polylines (numpy; no screen).

A path or pose array longer than :data:`~rostui.models.sensors.pose2d.MAX_POSES` is drawn with a stride
(its first and last poses kept): only the poses drawn are read.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import MAX_POSES, Points, Pose2D, every, pose_of

__all__ = ["odometry_pose", "path_points", "path_poses", "pose_array_poses", "stamped_pose"]


def odometry_pose(odom: Any) -> Pose2D:
    """Where a nav_msgs/Odometry puts its child frame, in ``odom.header.frame_id``."""
    return pose_of(odom.pose.pose)


def stamped_pose(msg: Any) -> Pose2D:
    """The pose of a geometry_msgs/PoseStamped, in ``msg.header.frame_id``."""
    return pose_of(msg.pose)


def _strided(items: Any, most: int) -> list[Any]:
    """At most ``most`` (and at least two) of ``items``, evenly strided, the first and the last kept."""
    count = len(items)
    if count <= most:
        return list(items)
    picks = list(range(0, count, every(count, most - 1)))
    if picks[-1] != count - 1:
        picks.append(count - 1)
    return [items[i] for i in picks]


def path_poses(path: Any, most: int = MAX_POSES) -> list[Pose2D]:
    """The poses of a nav_msgs/Path in order, at most ``most`` (each PoseStamped's own frame is taken as the
    path's)."""
    return [pose_of(p.pose) for p in _strided(path.poses, most)]


def path_points(path: Any, most: int = MAX_POSES) -> Points:
    """A nav_msgs/Path as an N x 2 polyline in ``path.header.frame_id`` (at most ``most`` vertices)."""
    if not len(path.poses):
        return np.zeros((0, 2))
    return np.array([(float(p.pose.position.x), float(p.pose.position.y)) for p in _strided(path.poses, most)],
                    dtype=np.float64)


def pose_array_poses(msg: Any, most: int = MAX_POSES) -> list[Pose2D]:
    """The poses of a geometry_msgs/PoseArray (at most ``most``), in ``msg.header.frame_id``."""
    return [pose_of(p) for p in _strided(msg.poses, most)]
