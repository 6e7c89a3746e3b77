"""Rigid transforms as tf writes them: a translation and a unit quaternion (x, y, z, w).

A :class:`Transform` ``T_a_b`` maps points given in frame ``b`` into frame ``a`` (the pose of
``b`` in ``a``), the meaning of a ``geometry_msgs/TransformStamped`` with ``header.frame_id``
``a`` and ``child_frame_id`` ``b``. ``T_a_b * T_b_c`` is ``T_a_c``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from rostui.tools.tf.rotations import quaternion_multiply

FloatArray = npt.NDArray[np.float64]


def quat_multiply(q1: FloatArray, q2: FloatArray) -> FloatArray:
    """The Hamilton product ``q1 * q2`` of two (x, y, z, w) quaternions."""
    return quaternion_multiply(q1, q2)


def quat_rotate(q: FloatArray, v: FloatArray) -> FloatArray:
    """The vector ``v`` rotated by the unit quaternion ``q``."""
    u = q[:3]
    w = q[3]
    t = 2.0 * np.cross(u, v)
    return np.asarray(v + w * t + np.cross(u, t), dtype=np.float64)


def quat_normalize(q: FloatArray) -> FloatArray:
    """``q`` scaled to unit length; a zero quaternion is refused."""
    n = float(np.linalg.norm(q))
    if not math.isfinite(n) or n < 1e-12:
        raise ValueError(f"quaternion {list(map(float, q))} has no direction (length {n})")
    return np.asarray(q / n, dtype=np.float64)


def quat_to_rpy(q: FloatArray) -> tuple[float, float, float]:
    """Roll, pitch and yaw (radians, fixed axes x then y then z) of a unit quaternion, as tf's getRPY.

    At pitch +-90 degrees (gimbal lock) yaw is reported as 0 and the whole turn as roll.
    """
    m = _rotation_matrix(q)
    if abs(m[2, 0]) >= 1.0 - 1e-12:
        if m[2, 0] < 0:
            return math.atan2(m[0, 1], m[0, 2]), math.pi / 2, 0.0
        return math.atan2(-m[0, 1], -m[0, 2]), -math.pi / 2, 0.0
    pitch = -math.asin(float(m[2, 0]))
    roll = math.atan2(m[2, 1], m[2, 2])
    yaw = math.atan2(m[1, 0], m[0, 0])
    return roll, pitch, yaw


def _rotation_matrix(q: FloatArray) -> FloatArray:
    x, y, z, w = (float(c) for c in q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ], dtype=np.float64)


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> FloatArray:
    """The unit quaternion of roll, pitch and yaw (radians, fixed axes x, y, z)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return np.array([
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    ], dtype=np.float64)


def quat_slerp(q1: FloatArray, q2: FloatArray, t: float) -> FloatArray:
    """Spherical interpolation from ``q1`` (t=0) to ``q2`` (t=1) along the shorter arc."""
    dot = float(np.dot(q1, q2))
    if dot < 0.0:
        q2 = -q2
        dot = -dot
    if dot > 0.9995:
        return quat_normalize(q1 + t * (q2 - q1))
    theta = math.acos(min(1.0, dot))
    s = math.sin(theta)
    return np.asarray((math.sin((1 - t) * theta) * q1 + math.sin(t * theta) * q2) / s, dtype=np.float64)


@dataclass(frozen=True)
class Transform:
    """A rigid transform: ``translation`` (x, y, z) and unit quaternion ``rotation`` (x, y, z, w)."""

    translation: FloatArray
    rotation: FloatArray

    @staticmethod
    def identity() -> Transform:
        """The transform that changes nothing."""
        return Transform(np.zeros(3), np.array([0.0, 0.0, 0.0, 1.0]))

    @staticmethod
    def of(translation: tuple[float, float, float] | list[float] | FloatArray,
           rotation: tuple[float, float, float, float] | list[float] | FloatArray) -> Transform:
        """A transform from plain numbers; the quaternion is normalised, non-finite values refused."""
        t = np.asarray(translation, dtype=np.float64).reshape(3)
        q = np.asarray(rotation, dtype=np.float64).reshape(4)
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(q))):
            raise ValueError(f"transform has a non-finite value: translation {t.tolist()}, rotation {q.tolist()}")
        return Transform(t, quat_normalize(q))

    @staticmethod
    def from_msg(transform: Any) -> Transform:
        """A transform from a ``geometry_msgs/Transform`` (fields translation.x.. and rotation.x..w)."""
        tr, rot = transform.translation, transform.rotation
        return Transform.of((tr.x, tr.y, tr.z), (rot.x, rot.y, rot.z, rot.w))

    def __mul__(self, other: Transform) -> Transform:
        """``self * other``: apply ``other`` first, then ``self``."""
        t = self.translation + quat_rotate(self.rotation, other.translation)
        q = quat_normalize(quat_multiply(self.rotation, other.rotation))
        return Transform(t, q)

    def inverse(self) -> Transform:
        """The transform that undoes this one."""
        conj = np.array([-self.rotation[0], -self.rotation[1], -self.rotation[2], self.rotation[3]])
        return Transform(-quat_rotate(conj, self.translation), conj)

    def apply(self, point: tuple[float, float, float] | FloatArray) -> FloatArray:
        """A point of the child frame expressed in the parent frame."""
        return np.asarray(quat_rotate(self.rotation, np.asarray(point, dtype=np.float64)) + self.translation,
                          dtype=np.float64)

    def matrix(self) -> FloatArray:
        """The 4x4 homogeneous matrix of this transform."""
        m = np.eye(4)
        m[:3, :3] = _rotation_matrix(self.rotation)
        m[:3, 3] = self.translation
        return m

    def rpy(self) -> tuple[float, float, float]:
        """Roll, pitch and yaw of the rotation, in radians."""
        return quat_to_rpy(self.rotation)

    def yaw(self) -> float:
        """The rotation about z, in radians (what a top-down view needs)."""
        return self.rpy()[2]

    def interpolate(self, other: Transform, t: float) -> Transform:
        """The transform a fraction ``t`` of the way from this one to ``other`` (lerp and slerp)."""
        tr = self.translation + t * (other.translation - self.translation)
        return Transform(np.asarray(tr, dtype=np.float64), quat_slerp(self.rotation, other.rotation, t))


def kdl_rotation(q: tuple[float, float, float, float] | FloatArray) -> FloatArray:
    """The 3x3 rotation of a quaternion (x, y, z, w) as KDL's ``Rotation.Quaternion`` builds it (no normalising)."""
    x, y, z, w = (float(c) for c in q)
    x2, y2, z2, w2 = x * x, y * y, z * z, w * w
    return np.array([
        [w2 + x2 - y2 - z2, 2 * x * y - 2 * w * z, 2 * x * z + 2 * w * y],
        [2 * x * y + 2 * w * z, w2 - x2 + y2 - z2, 2 * y * z - 2 * w * x],
        [2 * x * z - 2 * w * y, 2 * y * z + 2 * w * x, w2 - x2 - y2 + z2],
    ], dtype=np.float64)


def kdl_quaternion(m: FloatArray) -> tuple[float, float, float, float]:
    """The quaternion (x, y, z, w) of a rotation matrix as KDL's ``GetQuaternion`` picks it (trace first, then
    the largest diagonal element), so its sign is KDL's."""
    trace = float(m[0, 0] + m[1, 1] + m[2, 2])
    if trace > 1e-12:
        s = 0.5 / math.sqrt(trace + 1.0)
        return (float(m[2, 1] - m[1, 2]) * s, float(m[0, 2] - m[2, 0]) * s, float(m[1, 0] - m[0, 1]) * s, 0.25 / s)
    if m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        return 0.25 * s, float(m[0, 1] + m[1, 0]) / s, float(m[0, 2] + m[2, 0]) / s, float(m[2, 1] - m[1, 2]) / s
    if m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        return float(m[0, 1] + m[1, 0]) / s, 0.25 * s, float(m[1, 2] + m[2, 1]) / s, float(m[0, 2] - m[2, 0]) / s
    s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
    return float(m[0, 2] + m[2, 0]) / s, float(m[1, 2] + m[2, 1]) / s, 0.25 * s, float(m[1, 0] - m[0, 1]) / s


def matrix_quaternion(m: FloatArray) -> tuple[float, float, float, float]:
    """The quaternion (x, y, z, w) of a rotation matrix as tf2's ``Matrix3x3::getRotation`` picks it (w > 0 when
    the trace is positive, else led by the largest diagonal element), so its sign is tf2's."""
    trace = float(m[0, 0] + m[1, 1] + m[2, 2])
    out = [0.0, 0.0, 0.0, 0.0]
    if trace > 0.0:
        s = math.sqrt(trace + 1.0)
        out[3] = s * 0.5
        s = 0.5 / s
        out[0], out[1], out[2] = (float(m[2, 1] - m[1, 2]) * s, float(m[0, 2] - m[2, 0]) * s,
                                  float(m[1, 0] - m[0, 1]) * s)
    else:
        if m[0, 0] < m[1, 1]:
            i = 2 if m[1, 1] < m[2, 2] else 1
        else:
            i = 2 if m[0, 0] < m[2, 2] else 0
        j, k = (i + 1) % 3, (i + 2) % 3
        s = math.sqrt(float(m[i, i] - m[j, j] - m[k, k]) + 1.0)
        out[i] = s * 0.5
        s = 0.5 / s
        out[3] = float(m[k, j] - m[j, k]) * s
        out[j] = float(m[j, i] + m[i, j]) * s
        out[k] = float(m[k, i] + m[i, k]) * s
    return out[0], out[1], out[2], out[3]


def compose_as_matrices(a: Transform, b: Transform) -> Transform:
    """``a * b`` computed as tf2's ``tf2::Transform`` does, on rotation matrices, the quaternion read back with
    :func:`matrix_quaternion` (the sign tf2's advanced lookup gives)."""
    ra = _rotation_matrix(a.rotation)
    rotation = ra @ _rotation_matrix(b.rotation)
    return Transform(np.asarray(ra @ b.translation + a.translation, dtype=np.float64),
                     np.array(matrix_quaternion(rotation), dtype=np.float64))
