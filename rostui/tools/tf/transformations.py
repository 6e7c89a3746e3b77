"""``tf.transformations``: every function of ROS 1's module, under its names, with its numbers.

The rotations, quaternions, Euler conventions and vectors are in :mod:`.rotations` (read its docstring for the
conventions); taking matrices apart and the rarer matrices in :mod:`.matrix_parts`; the trackball in
:mod:`.arcball`.
"""

from __future__ import annotations

from rostui.tools.tf.arcball import Arcball, arcball_constrain_to_axis, arcball_map_to_sphere, arcball_nearest_axis
from rostui.tools.tf.matrix_parts import (
    clip_matrix, compose_matrix, decompose_matrix, orthogonalization_matrix, projection_from_matrix,
    projection_matrix, reflection_from_matrix, rotation_from_matrix, scale_from_matrix, shear_from_matrix,
    shear_matrix, superimposition_matrix,
)
from rostui.tools.tf.rotations import (
    _AXES2TUPLE, _EPS, _NEXT_AXIS, _TUPLE2AXES, concatenate_matrices, euler_from_matrix, euler_from_quaternion,
    euler_matrix, identity_matrix, inverse_matrix, is_same_transform, quaternion_about_axis, quaternion_conjugate,
    quaternion_from_euler, quaternion_from_matrix, quaternion_inverse, quaternion_matrix, quaternion_multiply,
    quaternion_slerp, random_quaternion, random_rotation_matrix, random_vector, reflection_matrix, rotation_matrix,
    scale_matrix, translation_from_matrix, translation_matrix, unit_vector, vector_norm,
)

__all__ = [
    "Arcball", "_AXES2TUPLE", "_EPS", "_NEXT_AXIS", "_TUPLE2AXES", "arcball_constrain_to_axis",
    "arcball_map_to_sphere", "arcball_nearest_axis", "clip_matrix", "compose_matrix", "concatenate_matrices",
    "decompose_matrix", "euler_from_matrix", "euler_from_quaternion", "euler_matrix", "identity_matrix",
    "inverse_matrix", "is_same_transform", "orthogonalization_matrix", "projection_from_matrix",
    "projection_matrix", "quaternion_about_axis", "quaternion_conjugate", "quaternion_from_euler",
    "quaternion_from_matrix", "quaternion_inverse", "quaternion_matrix", "quaternion_multiply", "quaternion_slerp",
    "random_quaternion", "random_rotation_matrix", "random_vector", "reflection_from_matrix", "reflection_matrix",
    "rotation_from_matrix", "rotation_matrix", "scale_from_matrix", "scale_matrix", "shear_from_matrix",
    "shear_matrix", "superimposition_matrix", "translation_from_matrix", "translation_matrix", "unit_vector",
    "vector_norm",
]
