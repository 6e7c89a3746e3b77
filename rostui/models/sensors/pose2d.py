"""Planar poses: a position and a heading in a frame, and the 2D transforms between frames (numpy).

The top-down view draws everything on the ground plane of one fixed frame.
A :class:`Pose2D` is both a pose (where a robot is, which way it faces) and
the rigid transform that carries points from a child frame into its parent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["Points", "Pose2D", "yaw_of", "pose_of"]

#: An N x 2 float64 array of (x, y) in metres.
Points = npt.NDArray[np.float64]


def yaw_of(q: Any) -> float:
    """The heading (rotation about z, radians) of a quaternion with fields x, y, z, w.

    A zero quaternion (all fields 0, as an unset message has) counts as no rotation.
    """
    x, y, z, w = float(q.x), float(q.y), float(q.z), float(q.w)
    if x == y == z == w == 0.0:
        return 0.0
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


@dataclass(frozen=True)
class Pose2D:
    """A position ``(x, y)`` in metres and heading ``yaw`` in radians (counter-clockwise from +x)."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    def apply(self, points: Points) -> Points:
        """``points`` (N x 2, in this pose's child frame) expressed in its parent frame."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        rot = np.array([[c, -s], [s, c]])
        out: Points = points @ rot.T + np.array([self.x, self.y])
        return out

    def compose(self, other: "Pose2D") -> "Pose2D":
        """``other`` (given in this pose's child frame) expressed in this pose's parent frame."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(self.x + c * other.x - s * other.y, self.y + s * other.x + c * other.y,
                      math.atan2(math.sin(self.yaw + other.yaw), math.cos(self.yaw + other.yaw)))

    def inverse(self) -> "Pose2D":
        """The transform back: parent frame into child frame."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(-(c * self.x + s * self.y), s * self.x - c * self.y, -self.yaw)


def pose_of(pose: Any) -> Pose2D:
    """A geometry_msgs/Pose (position, orientation) projected onto the ground plane."""
    return Pose2D(float(pose.position.x), float(pose.position.y), yaw_of(pose.orientation))
