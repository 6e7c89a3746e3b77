"""The core of ``tf.transformations``: 4x4 homogeneous transforms, Euler angles and (x, y, z, w) quaternions.

The functions ROS 1's ``tf.transformations`` offers, under the same names and arguments and with the same
conventions, so that a script written against tf gets the same numbers: matrices act on column vectors,
quaternions are ``(x, y, z, w)`` (tf's order, not the ``(w, x, y, z)`` of later releases of the module it came
from), and Euler angles are named by a four-letter string ``[sr][xyz]{3}``: ``s`` for static (extrinsic)
axes, ``r`` for rotating (intrinsic) ones, then the axes in the order the angles apply (``'sxyz'``, the
default, is roll about x, pitch about y, yaw about z, all about the fixed frame).  Euler conversions follow
Ken Shoemake's scheme (Graphics Gems IV), which names each convention by its first axis, parity, repetition
and frame.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

__all__ = [
    "concatenate_matrices", "euler_from_matrix", "euler_from_quaternion", "euler_matrix", "identity_matrix",
    "inverse_matrix", "is_same_transform", "quaternion_about_axis", "quaternion_conjugate",
    "quaternion_from_euler", "quaternion_from_matrix", "quaternion_inverse", "quaternion_matrix",
    "quaternion_multiply", "quaternion_slerp", "random_quaternion", "random_rotation_matrix", "random_vector",
    "reflection_matrix", "rotation_matrix", "scale_matrix", "translation_from_matrix", "translation_matrix",
    "unit_vector", "vector_norm",
]

#: Anything numpy reads as a vector: a list, a tuple, an array (tf's functions take them all).
Vector = Any

#: Below this, a length or a sine counts as zero (four machine epsilons, as tf).
_EPS = np.finfo(float).eps * 4.0

#: The axis after each one (x -> y -> z -> x), indexed as Shoemake's scheme reads it.
_NEXT_AXIS = [1, 2, 0, 1]


def _axes_table() -> dict[str, tuple[int, int, int, int]]:
    """Each of the 24 conventions' name -> (first axis, parity, repetition, frame)."""
    table = {}
    for frame, kind in ((0, "s"), (1, "r")):
        for first in range(3):
            for parity in (0, 1):
                for repetition in (0, 1):
                    i = first
                    j = _NEXT_AXIS[i + parity]
                    k = i if repetition else _NEXT_AXIS[i - parity + 1]
                    order = (i, j, k) if not frame else (k, j, i)
                    table[kind + "".join("xyz"[a] for a in order)] = (first, parity, repetition, frame)
    return table


_AXES2TUPLE = _axes_table()
_TUPLE2AXES = {value: key for key, value in _AXES2TUPLE.items()}


def _convention(axes: str | Sequence[int]) -> tuple[int, int, int, int]:
    """(first axis, parity, repetition, frame) of a convention given by name or as that tuple."""
    if isinstance(axes, str):
        return _AXES2TUPLE[axes.lower()]
    first, parity, repetition, frame = axes
    _TUPLE2AXES[(first, parity, repetition, frame)]  # refuses a tuple that names no convention (KeyError)
    return first, parity, repetition, frame


def _axis_indices(first: int, parity: int) -> tuple[int, int, int]:
    return first, _NEXT_AXIS[first + parity], _NEXT_AXIS[first - parity + 1]


# -- matrices ----------------------------------------------------------------------------------------------
def identity_matrix() -> np.ndarray:
    """The 4x4 identity."""
    return np.identity(4)


def translation_matrix(direction: Vector) -> np.ndarray:
    """The matrix that moves points by ``direction``."""
    matrix = np.identity(4)
    matrix[:3, 3] = direction[:3]
    return matrix


def translation_from_matrix(matrix: Any) -> np.ndarray:
    """The translation part of a transform."""
    return np.array(matrix, copy=True)[:3, 3].copy()


def reflection_matrix(point: Vector, normal: Vector) -> np.ndarray:
    """The mirror in the plane through ``point`` with ``normal``."""
    unit = unit_vector(normal[:3])
    matrix = np.identity(4)
    matrix[:3, :3] -= 2.0 * np.outer(unit, unit)
    matrix[:3, 3] = (2.0 * np.dot(point[:3], unit)) * unit
    return matrix


def rotation_matrix(angle: float, direction: Vector, point: Vector | None = None) -> np.ndarray:
    """The rotation by ``angle`` (radians) about the axis ``direction`` through ``point`` (the origin if None)."""
    sine, cosine = math.sin(angle), math.cos(angle)
    axis = unit_vector(direction[:3])
    rotation = np.diag([cosine, cosine, cosine]) + np.outer(axis, axis) * (1.0 - cosine)
    x, y, z = axis * sine
    rotation += np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    matrix = np.identity(4)
    matrix[:3, :3] = rotation
    if point is not None:
        origin = np.asarray(point[:3], dtype=np.float64)
        matrix[:3, 3] = origin - np.dot(rotation, origin)
    return matrix


def scale_matrix(factor: float, origin: Vector | None = None,
                 direction: Vector | None = None) -> np.ndarray:
    """Scaling by ``factor`` about ``origin``: in every direction, or only along ``direction``."""
    if direction is None:
        matrix = np.diag([factor, factor, factor, 1.0])
        if origin is not None:
            matrix[:3, 3] = np.asarray(origin[:3], dtype=np.float64) * (1.0 - factor)
        return matrix
    axis = unit_vector(direction[:3])
    shrink = 1.0 - factor
    matrix = np.identity(4)
    matrix[:3, :3] -= shrink * np.outer(axis, axis)
    if origin is not None:
        matrix[:3, 3] = (shrink * np.dot(origin[:3], axis)) * axis
    return matrix


def inverse_matrix(matrix: Any) -> np.ndarray:
    """The inverse of a transform."""
    return np.linalg.inv(matrix)


def concatenate_matrices(*matrices: Any) -> np.ndarray:
    """The product of the matrices, the first applied last (as written: ``M0 @ M1 @ ...``)."""
    product = np.identity(4)
    for matrix in matrices:
        product = np.dot(product, matrix)
    return product


def is_same_transform(matrix0: Any, matrix1: Any) -> bool:
    """Whether two homogeneous matrices describe the same transform (each scaled by its [3, 3])."""
    first = np.array(matrix0, dtype=np.float64, copy=True)
    first /= first[3, 3]
    second = np.array(matrix1, dtype=np.float64, copy=True)
    second /= second[3, 3]
    return bool(np.allclose(first, second))


# -- Euler angles ------------------------------------------------------------------------------------------
def euler_matrix(ai: float, aj: float, ak: float, axes: str | Sequence[int] = "sxyz") -> np.ndarray:
    """The rotation matrix of Euler angles ``ai``, ``aj``, ``ak`` (radians) in convention ``axes``."""
    first, parity, repetition, frame = _convention(axes)
    i, j, k = _axis_indices(first, parity)
    if frame:
        ai, ak = ak, ai
    if parity:
        ai, aj, ak = -ai, -aj, -ak
    si, sj, sk = math.sin(ai), math.sin(aj), math.sin(ak)
    ci, cj, ck = math.cos(ai), math.cos(aj), math.cos(ak)
    cc, cs, sc, ss = ci * ck, ci * sk, si * ck, si * sk
    matrix = np.identity(4)
    if repetition:
        matrix[i, i], matrix[i, j], matrix[i, k] = cj, sj * si, sj * ci
        matrix[j, i], matrix[j, j], matrix[j, k] = sj * sk, -cj * ss + cc, -cj * cs - sc
        matrix[k, i], matrix[k, j], matrix[k, k] = -sj * ck, cj * sc + cs, cj * cc - ss
    else:
        matrix[i, i], matrix[i, j], matrix[i, k] = cj * ck, sj * sc - cs, sj * cc + ss
        matrix[j, i], matrix[j, j], matrix[j, k] = cj * sk, sj * ss + cc, sj * cs - sc
        matrix[k, i], matrix[k, j], matrix[k, k] = -sj, cj * si, cj * ci
    return matrix


def euler_from_matrix(matrix: Any, axes: str | Sequence[int] = "sxyz") -> tuple[float, float, float]:
    """The Euler angles (radians) of a rotation matrix's 3x3 part in convention ``axes``."""
    first, parity, repetition, frame = _convention(axes)
    i, j, k = _axis_indices(first, parity)
    m = np.array(matrix, dtype=np.float64, copy=True)[:3, :3]
    if repetition:
        sy = math.sqrt(m[i, j] * m[i, j] + m[i, k] * m[i, k])
        if sy > _EPS:
            ax, ay, az = math.atan2(m[i, j], m[i, k]), math.atan2(sy, m[i, i]), math.atan2(m[j, i], -m[k, i])
        else:
            ax, ay, az = math.atan2(-m[j, k], m[j, j]), math.atan2(sy, m[i, i]), 0.0
    else:
        cy = math.sqrt(m[i, i] * m[i, i] + m[j, i] * m[j, i])
        if cy > _EPS:
            ax, ay, az = math.atan2(m[k, j], m[k, k]), math.atan2(-m[k, i], cy), math.atan2(m[j, i], m[i, i])
        else:
            ax, ay, az = math.atan2(-m[j, k], m[j, j]), math.atan2(-m[k, i], cy), 0.0
    if parity:
        ax, ay, az = -ax, -ay, -az
    if frame:
        ax, az = az, ax
    return ax, ay, az


def euler_from_quaternion(quaternion: Vector, axes: str | Sequence[int] = "sxyz"
                          ) -> tuple[float, float, float]:
    """The Euler angles (radians) of an (x, y, z, w) quaternion in convention ``axes``."""
    return euler_from_matrix(quaternion_matrix(quaternion), axes)


def quaternion_from_euler(ai: float, aj: float, ak: float, axes: str | Sequence[int] = "sxyz") -> np.ndarray:
    """The (x, y, z, w) quaternion of Euler angles (radians) in convention ``axes``."""
    first, parity, repetition, frame = _convention(axes)
    i, j, k = _axis_indices(first, parity)
    if frame:
        ai, ak = ak, ai
    if parity:
        aj = -aj
    ai, aj, ak = ai / 2.0, aj / 2.0, ak / 2.0
    si, sj, sk = math.sin(ai), math.sin(aj), math.sin(ak)
    ci, cj, ck = math.cos(ai), math.cos(aj), math.cos(ak)
    cc, cs, sc, ss = ci * ck, ci * sk, si * ck, si * sk
    quaternion = np.empty(4)
    if repetition:
        quaternion[i], quaternion[j] = cj * (cs + sc), sj * (cc + ss)
        quaternion[k], quaternion[3] = sj * (cs - sc), cj * (cc - ss)
    else:
        quaternion[i], quaternion[j] = cj * sc - sj * cs, cj * ss + sj * cc
        quaternion[k], quaternion[3] = cj * cs - sj * sc, cj * cc + sj * ss
    if parity:
        quaternion[j] *= -1.0
    return quaternion


# -- quaternions -------------------------------------------------------------------------------------------
def quaternion_about_axis(angle: float, axis: Vector) -> np.ndarray:
    """The (x, y, z, w) quaternion of a rotation by ``angle`` (radians) about ``axis``."""
    quaternion = np.zeros(4)
    quaternion[:3] = axis[:3]
    length = vector_norm(quaternion)
    if length > _EPS:
        quaternion *= math.sin(angle / 2.0) / length
    quaternion[3] = math.cos(angle / 2.0)
    return quaternion


def quaternion_matrix(quaternion: Vector) -> np.ndarray:
    """The 4x4 rotation matrix of an (x, y, z, w) quaternion (normalised first; the identity for a zero one)."""
    q = np.array(quaternion[:4], dtype=np.float64, copy=True)
    norm = np.dot(q, q)
    if norm < _EPS:
        return np.identity(4)
    q *= math.sqrt(2.0 / norm)
    p = np.outer(q, q)
    return np.array([
        [1.0 - p[1, 1] - p[2, 2], p[0, 1] - p[2, 3], p[0, 2] + p[1, 3], 0.0],
        [p[0, 1] + p[2, 3], 1.0 - p[0, 0] - p[2, 2], p[1, 2] - p[0, 3], 0.0],
        [p[0, 2] - p[1, 3], p[1, 2] + p[0, 3], 1.0 - p[0, 0] - p[1, 1], 0.0],
        [0.0, 0.0, 0.0, 1.0]])


def quaternion_from_matrix(matrix: Any) -> np.ndarray:
    """The (x, y, z, w) quaternion of a rotation matrix (its 4x4 part, as tf reads it)."""
    m = np.array(matrix, dtype=np.float64, copy=True)[:4, :4]
    quaternion = np.empty(4)
    trace = np.trace(m)
    if trace > m[3, 3]:
        quaternion[:] = m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1], trace
    else:
        i, j, k = 0, 1, 2
        if m[1, 1] > m[0, 0]:
            i, j, k = 1, 2, 0
        if m[2, 2] > m[i, i]:
            i, j, k = 2, 0, 1
        trace = m[i, i] - (m[j, j] + m[k, k]) + m[3, 3]
        quaternion[i], quaternion[j], quaternion[k] = trace, m[i, j] + m[j, i], m[k, i] + m[i, k]
        quaternion[3] = m[k, j] - m[j, k]
    quaternion *= 0.5 / math.sqrt(trace * m[3, 3])
    return quaternion


def quaternion_multiply(quaternion1: Vector, quaternion0: Vector) -> np.ndarray:
    """The product ``quaternion1 * quaternion0`` of two (x, y, z, w) quaternions (``quaternion0`` applied first)."""
    x0, y0, z0, w0 = quaternion0
    x1, y1, z1, w1 = quaternion1
    return np.array([
        w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
        w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
        w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0,
        w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0], dtype=np.float64)


def quaternion_conjugate(quaternion: Vector) -> np.ndarray:
    """The conjugate of an (x, y, z, w) quaternion."""
    return np.array((-quaternion[0], -quaternion[1], -quaternion[2], quaternion[3]), dtype=np.float64)


def quaternion_inverse(quaternion: Vector) -> np.ndarray:
    """The inverse of an (x, y, z, w) quaternion."""
    return quaternion_conjugate(quaternion) / np.dot(quaternion, quaternion)


def quaternion_slerp(quat0: Vector, quat1: Vector, fraction: float, spin: int = 0,
                     shortestpath: bool = True) -> np.ndarray:
    """The spherical interpolation ``fraction`` of the way from ``quat0`` to ``quat1`` (``spin`` extra half turns;
    the shorter way round unless ``shortestpath`` is False)."""
    q0 = unit_vector(quat0[:4])
    q1 = unit_vector(quat1[:4])
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    cosine = float(np.dot(q0, q1))
    if abs(abs(cosine) - 1.0) < _EPS:
        return q0
    if shortestpath and cosine < 0.0:
        cosine = -cosine
        q1 *= -1.0
    angle = math.acos(cosine) + spin * math.pi
    if abs(angle) < _EPS:
        return q0
    inverse_sine = 1.0 / math.sin(angle)
    q0 *= math.sin((1.0 - fraction) * angle) * inverse_sine
    q1 *= math.sin(fraction * angle) * inverse_sine
    q0 += q1
    return q0


def random_quaternion(rand: Vector | None = None) -> np.ndarray:
    """A uniformly random unit (x, y, z, w) quaternion; ``rand``: three numbers in [0, 1) to use instead of random."""
    if rand is None:
        rand = np.random.rand(3)
    elif len(rand) != 3:
        raise ValueError("rand must hold three numbers")
    r1, r2 = math.sqrt(1.0 - rand[0]), math.sqrt(rand[0])
    t1, t2 = 2.0 * math.pi * rand[1], 2.0 * math.pi * rand[2]
    return np.array((math.sin(t1) * r1, math.cos(t1) * r1, math.sin(t2) * r2, math.cos(t2) * r2))


def random_rotation_matrix(rand: Vector | None = None) -> np.ndarray:
    """A uniformly random rotation matrix (``rand`` as for :func:`random_quaternion`)."""
    return quaternion_matrix(random_quaternion(rand))


# -- vectors -----------------------------------------------------------------------------------------------
def vector_norm(data: Any, axis: int | None = None, out: np.ndarray | None = None) -> Any:
    """The Euclidean length of ``data`` (along ``axis``; into ``out`` when given)."""
    values = np.array(data, dtype=np.float64, copy=True)
    if out is None:
        if values.ndim == 1:
            return math.sqrt(np.dot(values, values))
        values *= values
        result = np.atleast_1d(np.sum(values, axis=axis))
        np.sqrt(result, result)
        return result
    values *= values
    np.sum(values, axis=axis, out=out)
    np.sqrt(out, out)
    return None


def unit_vector(data: Any, axis: int | None = None, out: np.ndarray | None = None) -> Any:
    """``data`` divided by its length (along ``axis``; in place in ``out`` when given)."""
    if out is None:
        values = np.array(data, dtype=np.float64, copy=True)
        if values.ndim == 1:
            values /= math.sqrt(np.dot(values, values))
            return values
    else:
        if out is not data:
            out[:] = np.asarray(data)
        values = out
    length = np.atleast_1d(np.sum(values * values, axis))
    np.sqrt(length, length)
    if axis is not None:
        length = np.expand_dims(length, axis)
    values /= length
    return values if out is None else None


def random_vector(size: int | Sequence[int]) -> np.ndarray:
    """Random numbers in [0, 1) of shape ``size``."""
    return np.random.random(size)

