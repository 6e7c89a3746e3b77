"""The parts of ``tf.transformations`` that take a 4x4 matrix apart or build less common ones: the axis, plane or
factor of a rotation, reflection, scaling or shear matrix, projections and clipping, composing and decomposing a
general transform, the crystallographic orthogonalisation and the best superimposition of two point sets.

Each takes its answer from the same eigenvectors, in the same order, as tf's module, so that an ambiguous case
(any point on an axis will do) gives the point tf gives.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rostui.tools.tf.rotations import _EPS, Vector, euler_matrix, quaternion_matrix, unit_vector, vector_norm

__all__ = [
    "clip_matrix", "compose_matrix", "decompose_matrix", "orthogonalization_matrix", "projection_from_matrix",
    "projection_matrix", "reflection_from_matrix", "rotation_from_matrix", "scale_from_matrix", "shear_from_matrix",
    "shear_matrix", "superimposition_matrix",
]


def _eigenvectors(matrix: Any, where: Any) -> tuple[np.ndarray, np.ndarray]:
    """The real parts of ``matrix``'s eigenvectors (as columns) whose eigenvalues pass ``where``, and those values."""
    values, vectors = np.linalg.eig(matrix)
    chosen = np.where(where(np.real(values)))[0]
    return np.real(vectors[:, chosen]), chosen


def _fixed_point(matrix: np.ndarray, what: str = "eigenvalue 1") -> np.ndarray:
    """A point the transform leaves where it is: its last eigenvector of eigenvalue 1, made homogeneous."""
    vectors, chosen = _eigenvectors(matrix, lambda values: abs(values - 1.0) < 1e-8)
    if not len(chosen):
        raise ValueError(f"no eigenvector corresponding to {what}")
    point = vectors[:, -1].squeeze()
    return point / point[3]


def reflection_from_matrix(matrix: Any) -> tuple[np.ndarray, np.ndarray]:
    """The mirror plane of a reflection matrix: a point on it and its normal."""
    m = np.array(matrix, dtype=np.float64)
    vectors, chosen = _eigenvectors(m[:3, :3], lambda values: abs(values + 1.0) < 1e-8)
    if not len(chosen):
        raise ValueError("no unit eigenvector corresponding to eigenvalue -1")
    normal = vectors[:, 0].squeeze()
    return _fixed_point(m), normal


def rotation_from_matrix(matrix: Any) -> tuple[float, np.ndarray, np.ndarray]:
    """The angle (radians), axis direction and a point on the axis of a rotation matrix."""
    m = np.array(matrix, dtype=np.float64)
    rotation = m[:3, :3]
    vectors, chosen = _eigenvectors(rotation.T, lambda values: abs(values - 1.0) < 1e-8)
    if not len(chosen):
        raise ValueError("no unit eigenvector corresponding to eigenvalue 1")
    direction = vectors[:, -1].squeeze()
    point = _fixed_point(m)
    cosine = (np.trace(rotation) - 1.0) / 2.0
    if abs(direction[2]) > 1e-8:
        sine = (m[1, 0] + (cosine - 1.0) * direction[0] * direction[1]) / direction[2]
    elif abs(direction[1]) > 1e-8:
        sine = (m[0, 2] + (cosine - 1.0) * direction[0] * direction[2]) / direction[1]
    else:
        sine = (m[2, 1] + (cosine - 1.0) * direction[1] * direction[2]) / direction[0]
    return math.atan2(sine, cosine), direction, point


def scale_from_matrix(matrix: Any) -> tuple[float, np.ndarray, np.ndarray | None]:
    """The factor, origin and direction (None for a uniform scaling) of a scaling matrix."""
    m = np.array(matrix, dtype=np.float64)
    factor = float(np.trace(m[:3, :3]) - 2.0)
    vectors, chosen = _eigenvectors(m[:3, :3], lambda values: abs(values - factor) < 1e-8)
    direction: np.ndarray | None
    if len(chosen):
        direction = vectors[:, 0].squeeze()
        direction = direction / vector_norm(direction)
    else:
        factor = (factor + 2.0) / 3.0
        direction = None
    return factor, _fixed_point(m), direction


def projection_matrix(point: Vector, normal: Vector, direction: Vector | None = None,
                      perspective: Vector | None = None, pseudo: bool = False) -> np.ndarray:
    """The projection onto the plane through ``point`` with ``normal``: from the ``perspective`` point, along
    ``direction``, or orthogonal when neither is given (``pseudo`` keeps relative depth in a perspective one)."""
    matrix = np.identity(4)
    origin = np.asarray(point[:3], dtype=np.float64)
    unit = unit_vector(normal[:3])
    if perspective is not None:
        eye = np.asarray(perspective[:3], dtype=np.float64)
        matrix[0, 0] = matrix[1, 1] = matrix[2, 2] = np.dot(eye - origin, unit)
        matrix[:3, :3] -= np.outer(eye, unit)
        if pseudo:
            matrix[:3, :3] -= np.outer(unit, unit)
            matrix[:3, 3] = np.dot(origin, unit) * (eye + unit)
        else:
            matrix[:3, 3] = np.dot(origin, unit) * eye
        matrix[3, :3] = -unit
        matrix[3, 3] = np.dot(eye, unit)
    elif direction is not None:
        along = np.asarray(direction[:3], dtype=np.float64)
        scale = np.dot(along, unit)
        matrix[:3, :3] -= np.outer(along, unit) / scale
        matrix[:3, 3] = along * (np.dot(origin, unit) / scale)
    else:
        matrix[:3, :3] -= np.outer(unit, unit)
        matrix[:3, 3] = np.dot(origin, unit) * unit
    return matrix


def projection_from_matrix(matrix: Any, pseudo: bool = False) -> tuple[Any, Any, Any, Any, bool]:
    """``(point, normal, direction, perspective, pseudo)`` of a projection matrix: the arguments
    :func:`projection_matrix` would make it from."""
    m = np.array(matrix, dtype=np.float64)
    m33 = m[:3, :3]
    values, vectors = np.linalg.eig(m)
    ones = np.where(abs(np.real(values) - 1.0) < 1e-8)[0]
    if not pseudo and len(ones):
        point = np.real(vectors[:, ones[-1]]).squeeze()
        point /= point[3]
        zeros, chosen = _eigenvectors(m33, lambda found: abs(found) < 1e-8)
        if not len(chosen):
            raise ValueError("no eigenvector corresponding to eigenvalue 0")
        direction = zeros[:, 0].squeeze()
        direction /= vector_norm(direction)
        normals, chosen = _eigenvectors(m33.T, lambda found: abs(found) < 1e-8)
        if len(chosen):
            normal = normals[:, 0].squeeze()
            normal /= vector_norm(normal)
            return point, normal, direction, None, False
        return point, direction, None, None, False
    others = np.where(abs(np.real(values)) > 1e-8)[0]
    if not len(others):
        raise ValueError("no eigenvector not corresponding to eigenvalue 0")
    point = np.real(vectors[:, others[-1]]).squeeze()
    point /= point[3]
    normal = -m[3, :3]
    perspective = m[:3, 3] / np.dot(point[:3], normal)
    if pseudo:
        perspective -= normal
    return point, normal, None, perspective, pseudo


def clip_matrix(left: float, right: float, bottom: float, top: float, near: float, far: float,
                perspective: bool = False) -> np.ndarray:
    """The matrix from the frustum (a pyramid from the origin along z when ``perspective``, else a box) to
    normalised device coordinates, in [-1, 1] inside it."""
    if left >= right or bottom >= top or near >= far:
        raise ValueError("invalid frustrum")
    width, height, depth = right - left, top - bottom, far - near
    if perspective:
        if near <= _EPS:
            raise ValueError("invalid frustrum: near <= 0")
        twice_near = 2.0 * near
        rows = ((-twice_near / width, 0.0, (right + left) / width, 0.0),
                (0.0, -twice_near / height, (top + bottom) / height, 0.0),
                (0.0, 0.0, -(far + near) / depth, twice_near * far / depth),
                (0.0, 0.0, -1.0, 0.0))
    else:
        rows = ((2.0 / width, 0.0, 0.0, (right + left) / (left - right)),
                (0.0, 2.0 / height, 0.0, (top + bottom) / (bottom - top)),
                (0.0, 0.0, 2.0 / depth, (far + near) / (near - far)),
                (0.0, 0.0, 0.0, 1.0))
    return np.array(rows, dtype=np.float64)


def shear_matrix(angle: float, direction: Vector, point: Vector, normal: Vector) -> np.ndarray:
    """The shear by ``angle`` along ``direction`` on the plane through ``point`` with ``normal`` (orthogonal to it)."""
    unit_normal = unit_vector(normal[:3])
    unit_direction = unit_vector(direction[:3])
    if abs(np.dot(unit_normal, unit_direction)) > 1e-6:
        raise ValueError("direction and normal vectors are not orthogonal")
    slope = math.tan(angle)
    matrix = np.identity(4)
    matrix[:3, :3] += slope * np.outer(unit_direction, unit_normal)
    matrix[:3, 3] = -slope * np.dot(point[:3], unit_normal) * unit_direction
    return matrix


def shear_from_matrix(matrix: Any) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """The angle, direction, a point of the plane and its normal of a shear matrix."""
    m = np.array(matrix, dtype=np.float64)
    m33 = m[:3, :3]
    values, vectors = np.linalg.eig(m33)
    ones = np.where(abs(np.real(values) - 1.0) < 1e-4)[0]
    if len(ones) < 2:
        raise ValueError(f"No two linear independent eigenvectors found {values}")
    rows = np.real(vectors[:, ones]).squeeze().T
    longest, normal = -1.0, np.zeros(3)
    for a, b in ((0, 1), (0, 2), (1, 2)):
        candidate = np.cross(rows[a], rows[b])
        length = vector_norm(candidate)
        if length > longest:
            longest, normal = length, candidate
    normal = normal / longest
    direction = np.dot(m33 - np.identity(3), normal)
    slope = vector_norm(direction)
    direction = direction / slope
    return math.atan(slope), direction, _fixed_point(m), normal


def decompose_matrix(matrix: Any) -> tuple[np.ndarray, list[float], list[float], np.ndarray, np.ndarray]:
    """``(scale, shear, angles, translate, perspective)`` of a transform: three scale factors, the x-y, x-z and y-z
    shears, Euler angles about the static x, y and z axes, the translation and the perspective row.

    ValueError for a matrix with a zero [3, 3] or a singular one.
    """
    m = np.array(matrix, dtype=np.float64, copy=True).T
    if abs(m[3, 3]) < _EPS:
        raise ValueError("M[3, 3] is zero")
    m /= m[3, 3]
    affine = m.copy()
    affine[:, 3] = 0.0, 0.0, 0.0, 1.0
    if not np.linalg.det(affine):
        raise ValueError("Matrix is singular")
    scale = np.zeros(3)
    shear = [0.0, 0.0, 0.0]
    angles = [0.0, 0.0, 0.0]
    if any(abs(m[:3, 3]) > _EPS):
        perspective = np.dot(m[:, 3], np.linalg.inv(affine.T))
        m[:, 3] = 0.0, 0.0, 0.0, 1.0
    else:
        perspective = np.array((0.0, 0.0, 0.0, 1.0))
    translate = m[3, :3].copy()
    m[3, :3] = 0.0
    row = m[:3, :3].copy()
    scale[0] = vector_norm(row[0])
    row[0] /= scale[0]
    shear[0] = np.dot(row[0], row[1])
    row[1] -= row[0] * shear[0]
    scale[1] = vector_norm(row[1])
    row[1] /= scale[1]
    shear[0] /= scale[1]
    shear[1] = np.dot(row[0], row[2])
    row[2] -= row[0] * shear[1]
    shear[2] = np.dot(row[1], row[2])
    row[2] -= row[1] * shear[2]
    scale[2] = vector_norm(row[2])
    row[2] /= scale[2]
    shear[1] /= scale[2]
    shear[2] /= scale[2]
    if np.dot(row[0], np.cross(row[1], row[2])) < 0:
        scale *= -1.0
        row *= -1.0
    angles[1] = math.asin(-row[0, 2])
    if math.cos(angles[1]):
        angles[0] = math.atan2(row[1, 2], row[2, 2])
        angles[2] = math.atan2(row[0, 1], row[0, 0])
    else:
        angles[0] = math.atan2(-row[2, 1], row[1, 1])
        angles[2] = 0.0
    return scale, shear, angles, translate, perspective


def compose_matrix(scale: Vector | None = None, shear: Vector | None = None, angles: Vector | None = None,
                   translate: Vector | None = None, perspective: Vector | None = None) -> np.ndarray:
    """The transform :func:`decompose_matrix` takes apart: perspective, translation, rotation, shear, scale."""
    matrix = np.identity(4)
    if perspective is not None:
        part = np.identity(4)
        part[3, :] = perspective[:4]
        matrix = np.dot(matrix, part)
    if translate is not None:
        part = np.identity(4)
        part[:3, 3] = translate[:3]
        matrix = np.dot(matrix, part)
    if angles is not None:
        matrix = np.dot(matrix, euler_matrix(angles[0], angles[1], angles[2], "sxyz"))
    if shear is not None:
        part = np.identity(4)
        part[1, 2], part[0, 2], part[0, 1] = shear[2], shear[1], shear[0]
        matrix = np.dot(matrix, part)
    if scale is not None:
        matrix = np.dot(matrix, np.diag([scale[0], scale[1], scale[2], 1.0]))
    matrix /= matrix[3, 3]
    return matrix


def orthogonalization_matrix(lengths: Vector, angles: Vector) -> np.ndarray:
    """The orthogonalisation matrix of a crystallographic cell: edge ``lengths`` and ``angles`` in degrees."""
    a, b, c = lengths
    radians = np.radians(angles)
    sin_a, sin_b, _ = np.sin(radians)
    cos_a, cos_b, cos_g = np.cos(radians)
    co = (cos_a * cos_b - cos_g) / (sin_a * sin_b)
    return np.array((
        (a * sin_b * math.sqrt(1.0 - co * co), 0.0, 0.0, 0.0),
        (-a * sin_b * co, b * sin_a, 0.0, 0.0),
        (a * cos_b, b * cos_a, c, 0.0),
        (0.0, 0.0, 0.0, 1.0)), dtype=np.float64)


def superimposition_matrix(v0: Any, v1: Any, scaling: bool = False, usesvd: bool = True) -> np.ndarray:
    """The rotation and translation (and uniform scale with ``scaling``) that best map the points ``v0`` onto
    ``v1`` (shape (3, N) or (4, N), N >= 3): Kabsch's SVD method, or Horn's quaternion one without ``usesvd``."""
    first = np.array(v0, dtype=np.float64)[:3]
    second = np.array(v1, dtype=np.float64)[:3]
    if first.shape != second.shape or first.shape[1] < 3:
        raise ValueError("Vector sets are of wrong shape or type.")
    centre0, centre1 = np.mean(first, axis=1), np.mean(second, axis=1)
    first = first - centre0.reshape(3, 1)
    second = second - centre1.reshape(3, 1)
    if usesvd:
        u, singular, vh = np.linalg.svd(np.dot(second, first.T))
        rotation = np.dot(u, vh)
        if np.linalg.det(rotation) < 0.0:
            rotation -= np.outer(u[:, 2], vh[2, :] * 2.0)
            singular[-1] *= -1.0
        matrix = np.identity(4)
        matrix[:3, :3] = rotation
    else:
        xx, yy, zz = np.sum(first * second, axis=1)
        xy, yz, zx = np.sum(first * np.roll(second, -1, axis=0), axis=1)
        xz, yx, zy = np.sum(first * np.roll(second, -2, axis=0), axis=1)
        horn = ((xx + yy + zz, yz - zy, zx - xz, xy - yx),
                (yz - zy, xx - yy - zz, xy + yx, zx + xz),
                (zx - xz, xy + yx, -xx + yy - zz, yz + zy),
                (xy - yx, zx + xz, yz + zy, -xx - yy + zz))
        values, vectors = np.linalg.eig(horn)
        quaternion = vectors[:, np.argmax(values)]
        quaternion = np.roll(quaternion / vector_norm(quaternion), -1)  # (w, x, y, z) to tf's (x, y, z, w)
        matrix = quaternion_matrix(quaternion)
    if scaling:
        matrix[:3, :3] *= math.sqrt(np.sum(second * second) / np.sum(first * first))
    matrix[:3, 3] = centre1
    shift = np.identity(4)
    shift[:3, 3] = -centre0
    return np.dot(matrix, shift)
