"""``tf.transformations``' virtual trackball: rotations from cursor drags on a window (as tf has it)."""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from rostui.tools.tf.rotations import (
    _EPS, Vector, quaternion_from_matrix, quaternion_matrix, quaternion_multiply, quaternion_slerp, unit_vector,
    vector_norm,
)

__all__ = ["Arcball", "arcball_constrain_to_axis", "arcball_map_to_sphere", "arcball_nearest_axis"]


def arcball_map_to_sphere(point: Vector, center: Vector, radius: float) -> np.ndarray:
    """The unit-sphere point under window ``point`` for a trackball at ``center`` of ``radius``."""
    v = np.array(((point[0] - center[0]) / radius, (center[1] - point[1]) / radius, 0.0), dtype=np.float64)
    n = v[0] * v[0] + v[1] * v[1]
    if n > 1.0:
        v /= math.sqrt(n)  # outside the ball: on its rim
    else:
        v[2] = math.sqrt(1.0 - n)
    return v


def arcball_constrain_to_axis(point: Vector, axis: Vector) -> np.ndarray:
    """The sphere point nearest ``point`` on the great circle perpendicular to ``axis``."""
    v = np.array(point, dtype=np.float64, copy=True)
    a = np.array(axis, dtype=np.float64, copy=True)
    v -= a * np.dot(a, v)
    n = vector_norm(v)
    if n > _EPS:
        if v[2] < 0.0:
            v *= -1.0
        v /= n
        return v
    if a[2] == 1.0:
        return np.array([1.0, 0.0, 0.0])
    return unit_vector([-a[1], a[0], 0.0])


def arcball_nearest_axis(point: Vector, axes: Sequence[Any]) -> Any:
    """Of ``axes``, the one whose circle passes nearest ``point``."""
    at = np.asarray(point, dtype=np.float64)
    nearest, best = None, -1.0
    for axis in axes:
        closeness = np.dot(arcball_constrain_to_axis(at, axis), at)
        if closeness > best:
            nearest, best = axis, closeness
    return nearest


class Arcball:
    """A virtual trackball: :meth:`place` it, then :meth:`down` and :meth:`drag` with the cursor; :meth:`matrix`."""

    def __init__(self, initial: Any = None) -> None:
        self._axis: Any = None
        self._axes: list[np.ndarray] | None = None
        self._radius = 1.0
        self._center = [0.0, 0.0]
        self._vdown = np.array([0.0, 0.0, 1.0])
        self._constrain = False
        if initial is None:
            self._qdown = np.array([0.0, 0.0, 0.0, 1.0])
        else:
            start = np.array(initial, dtype=np.float64)
            if start.shape == (4, 4):
                self._qdown = quaternion_from_matrix(start)
            elif start.shape == (4,):
                self._qdown = start / vector_norm(start)
            else:
                raise ValueError("initial not a quaternion or matrix.")
        self._qnow = self._qpre = self._qdown

    def place(self, center: Vector, radius: float) -> None:
        """Put the ball at window ``center`` with ``radius`` (window units)."""
        self._radius = float(radius)
        self._center[0], self._center[1] = center[0], center[1]

    def setaxes(self, *axes: Vector) -> None:
        """The axes rotations may be constrained to."""
        self._axes = [unit_vector(axis) for axis in axes]

    def setconstrain(self, constrain: bool) -> None:
        """Constrain rotations to the nearest axis (or not)."""
        self._constrain = constrain == True  # noqa: E712 - tf keeps only a literal True

    def getconstrain(self) -> bool:
        """Whether rotations are constrained to an axis."""
        return self._constrain

    def down(self, point: Vector) -> None:
        """The cursor went down at window ``point``: the drag starts here (and picks its axis when constrained)."""
        self._vdown = arcball_map_to_sphere(point, self._center, self._radius)
        self._qdown = self._qpre = self._qnow
        if self._constrain and self._axes is not None:
            self._axis = arcball_nearest_axis(self._vdown, self._axes)
            self._vdown = arcball_constrain_to_axis(self._vdown, self._axis)
        else:
            self._axis = None

    def drag(self, point: Vector) -> None:
        """The cursor moved to window ``point``."""
        now = arcball_map_to_sphere(point, self._center, self._radius)
        if self._axis is not None:
            now = arcball_constrain_to_axis(now, self._axis)
        self._qpre = self._qnow
        turn = np.cross(self._vdown, now)
        if np.dot(turn, turn) < _EPS:
            self._qnow = self._qdown
        else:
            self._qnow = quaternion_multiply([turn[0], turn[1], turn[2], np.dot(self._vdown, now)], self._qdown)

    def next(self, acceleration: float = 0.0) -> None:
        """Go on turning as the last drag did."""
        following = quaternion_slerp(self._qpre, self._qnow, 2.0 + acceleration, False)
        self._qpre, self._qnow = self._qnow, following

    def matrix(self) -> np.ndarray:
        """The rotation so far, as a 4x4 matrix."""
        return quaternion_matrix(self._qnow)
