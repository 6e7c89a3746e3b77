"""Odometry, paths, poses and pose arrays as planar poses and polylines (numpy; no screen)."""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import Points, Pose2D, pose_of

__all__ = ["odometry_pose", "path_points", "path_poses", "pose_array_poses", "stamped_pose"]


def odometry_pose(odom: Any) -> Pose2D:
    """Where a nav_msgs/Odometry puts its child frame, in ``odom.header.frame_id``."""
    return pose_of(odom.pose.pose)


def stamped_pose(msg: Any) -> Pose2D:
    """The pose of a geometry_msgs/PoseStamped, in ``msg.header.frame_id``."""
    return pose_of(msg.pose)


def path_poses(path: Any) -> list[Pose2D]:
    """Every pose of a nav_msgs/Path, in order (each PoseStamped's own frame is taken as the path's)."""
    return [pose_of(p.pose) for p in path.poses]


def path_points(path: Any) -> Points:
    """A nav_msgs/Path as an N x 2 polyline in ``path.header.frame_id``."""
    if not path.poses:
        return np.zeros((0, 2))
    return np.array([(float(p.pose.position.x), float(p.pose.position.y)) for p in path.poses], dtype=np.float64)


def pose_array_poses(msg: Any) -> list[Pose2D]:
    """Every pose of a geometry_msgs/PoseArray, in ``msg.header.frame_id``."""
    return [pose_of(p) for p in msg.poses]
