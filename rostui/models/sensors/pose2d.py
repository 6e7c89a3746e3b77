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

__all__ = ["MAX_POINTS", "MAX_POSES", "Planar", "Points", "Pose2D", "every", "yaw_of", "pose_of"]

#: An N x 2 float64 array of (x, y) in metres.
Points = npt.NDArray[np.float64]

#: Most points one message is drawn with (more than a terminal's dots); a larger scan or cloud is strided.
MAX_POINTS = 1 << 17

#: Most poses (arrows) or path vertices one message is drawn with; a longer array is strided.
MAX_POSES = 1 << 12


def every(count: int, most: int) -> int:
    """The stride that keeps at most ``most`` of ``count`` items (1: keep all)."""
    return max(1, -(-count // max(1, most)))


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


@dataclass(frozen=True)
class Planar:
    """A 3D rigid transform as it acts on the ground plane: ``p -> matrix @ p + offset`` (2 x 2 and 2).

    For points at z = 0 of the source frame this is exact, whatever the
    transform's roll and pitch: an upside-down laser (roll 180 degrees) comes
    out mirrored, as it should.
    """

    matrix: npt.NDArray[np.float64]
    offset: npt.NDArray[np.float64]

    @staticmethod
    def of(where: "Planar | Pose2D") -> "Planar":
        """``where`` as a Planar (a Pose2D is a rotation and a shift)."""
        if isinstance(where, Planar):
            return where
        c, s = math.cos(where.yaw), math.sin(where.yaw)
        return Planar(np.array([[c, -s], [s, c]]), np.array([where.x, where.y]))

    @staticmethod
    def from_rotation(rotation: npt.NDArray[np.float64], translation: npt.NDArray[np.float64]) -> "Planar":
        """From a 3 x 3 rotation matrix and a translation: their x and y rows and columns."""
        return Planar(np.asarray(rotation, dtype=np.float64)[:2, :2].copy(),
                      np.asarray(translation, dtype=np.float64)[:2].copy())

    def apply(self, points: Points) -> Points:
        """``points`` (N x 2, z = 0 in the source frame) on the target frame's plane."""
        out: Points = points @ self.matrix.T + self.offset
        return out

    def compose(self, other: "Planar | Pose2D") -> "Planar":
        """``other`` first, then this."""
        o = Planar.of(other)
        return Planar(self.matrix @ o.matrix, self.matrix @ o.offset + self.offset)

    def pose(self, pose: Pose2D) -> Pose2D:
        """Where ``pose`` (in the source frame) lands and which way it faces on the target plane."""
        x, y = self.apply(np.array([[pose.x, pose.y]]))[0]
        dx, dy = self.matrix @ np.array([math.cos(pose.yaw), math.sin(pose.yaw)])
        return Pose2D(float(x), float(y), math.atan2(dy, dx))

    def inverse(self) -> "Planar | None":
        """The way back, or None when the plane is seen edge-on (a frame pitched or rolled 90 degrees)."""
        if abs(float(np.linalg.det(self.matrix))) < 1e-9:
            return None
        inv = np.asarray(np.linalg.inv(self.matrix), dtype=np.float64)
        return Planar(inv, np.asarray(-inv @ self.offset, dtype=np.float64))
