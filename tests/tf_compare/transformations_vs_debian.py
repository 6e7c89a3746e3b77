"""Run by Debian's Python: rostui's tf.transformations (loaded from the file given) against Debian's tf.

Prints one line per function: its name and the largest absolute difference seen over random inputs (every
Euler convention, gimbal lock included), then ``MAX`` and the largest of all.
"""
import importlib.util
import json
import math
import random
import sys

import numpy as np
import tf.transformations as ref

spec = importlib.util.spec_from_file_location('ours', sys.argv[1])
ours = importlib.util.module_from_spec(spec); spec.loader.exec_module(ours)
rng = random.Random(7)
worst = {}
def cmp(name, a, b):
    a = np.asarray(a, dtype=float); b = np.asarray(b, dtype=float)
    d = float(np.max(np.abs(a - b))) if a.size else 0.0
    if a.shape != b.shape: d = float('inf')
    worst[name] = max(worst.get(name, 0.0), d)
def rq():
    q = [rng.uniform(-1, 1) for _ in range(4)]; return q
for trial in range(int(sys.argv[2])):
    a = [rng.uniform(-math.pi, math.pi) for _ in range(3)]
    if trial % 10 == 0: a[1] = math.pi / 2 * rng.choice([-1, 1])  # gimbal lock
    for axes in ref._AXES2TUPLE:
        cmp('euler_matrix', ours.euler_matrix(*a, axes=axes), ref.euler_matrix(*a, axes=axes))
        M = ref.euler_matrix(*a, axes=axes)
        cmp('euler_from_matrix', ours.euler_from_matrix(M, axes), ref.euler_from_matrix(M, axes))
        cmp('quaternion_from_euler', ours.quaternion_from_euler(*a, axes=axes), ref.quaternion_from_euler(*a, axes=axes))
        q = rq()
        cmp('euler_from_quaternion', ours.euler_from_quaternion(q, axes), ref.euler_from_quaternion(q, axes))
    q0, q1 = rq(), rq()
    cmp('quaternion_matrix', ours.quaternion_matrix(q0), ref.quaternion_matrix(q0))
    R = ref.quaternion_matrix(q0)
    cmp('quaternion_from_matrix', ours.quaternion_from_matrix(R), ref.quaternion_from_matrix(R))
    cmp('quaternion_multiply', ours.quaternion_multiply(q0, q1), ref.quaternion_multiply(q0, q1))
    cmp('quaternion_conjugate', ours.quaternion_conjugate(q0), ref.quaternion_conjugate(q0))
    cmp('quaternion_inverse', ours.quaternion_inverse(q0), ref.quaternion_inverse(q0))
    f = rng.choice([0.0, 1.0, rng.random()]); spin = rng.choice([0, 1, -1])
    sp = rng.choice([True, False])
    cmp('quaternion_slerp', ours.quaternion_slerp(q0, q1, f, spin, sp), ref.quaternion_slerp(q0, q1, f, spin, sp))
    ang = rng.uniform(-7, 7); axis = [rng.uniform(-1, 1) for _ in range(3)]; pt = [rng.uniform(-5, 5) for _ in range(3)]
    cmp('quaternion_about_axis', ours.quaternion_about_axis(ang, axis), ref.quaternion_about_axis(ang, axis))
    cmp('rotation_matrix', ours.rotation_matrix(ang, axis, pt), ref.rotation_matrix(ang, axis, pt))
    cmp('rotation_matrix0', ours.rotation_matrix(ang, axis), ref.rotation_matrix(ang, axis))
    cmp('translation_matrix', ours.translation_matrix(pt), ref.translation_matrix(pt))
    T = ref.concatenate_matrices(ref.translation_matrix(pt), R)
    cmp('translation_from_matrix', ours.translation_from_matrix(T), ref.translation_from_matrix(T))
    cmp('inverse_matrix', ours.inverse_matrix(T), ref.inverse_matrix(T))
    cmp('concatenate_matrices', ours.concatenate_matrices(T, R, T), ref.concatenate_matrices(T, R, T))
    cmp('reflection_matrix', ours.reflection_matrix(pt, axis), ref.reflection_matrix(pt, axis))
    fac = rng.uniform(-3, 3)
    cmp('scale_matrix', ours.scale_matrix(fac, pt), ref.scale_matrix(fac, pt))
    cmp('scale_matrix_dir', ours.scale_matrix(fac, pt, axis), ref.scale_matrix(fac, pt, axis))
    cmp('scale_matrix_plain', ours.scale_matrix(fac), ref.scale_matrix(fac))
    r3 = [rng.random() for _ in range(3)]
    cmp('random_quaternion', ours.random_quaternion(r3), ref.random_quaternion(r3))
    cmp('random_rotation_matrix', ours.random_rotation_matrix(r3), ref.random_rotation_matrix(r3))
    v = np.array([[rng.uniform(-3, 3) for _ in range(3)] for _ in range(4)])
    cmp('vector_norm', ours.vector_norm(v[0]), ref.vector_norm(v[0]))
    cmp('vector_norm_axis', ours.vector_norm(v, axis=1), ref.vector_norm(v, axis=1))
    cmp('unit_vector', ours.unit_vector(v[0]), ref.unit_vector(v[0]))
    cmp('unit_vector_axis', ours.unit_vector(v, axis=1), ref.unit_vector(v, axis=1))
    assert ours.is_same_transform(T, T * 2) == ref.is_same_transform(T, T * 2)
print(json.dumps(worst))
