"""Run by Debian's Python: rostui's tf.transformations (rostui from the checkout given) against Debian's tf.

Prints one line per function: its name and the largest absolute difference seen over random inputs (every
Euler convention, gimbal lock included), then ``MAX`` and the largest of all.
"""
import json
import math
import random
import sys

import numpy as np
import tf.transformations as ref

sys.path.insert(0, sys.argv[1])
import rostui.tools.tf.transformations as ours  # noqa: E402
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
    # taking matrices apart, and the rarer matrices
    Rp = ref.rotation_matrix(ang, axis, pt)
    cmp('rotation_from_matrix', np.hstack([[ours.rotation_from_matrix(Rp)[0]], *ours.rotation_from_matrix(Rp)[1:]]),
        np.hstack([[ref.rotation_from_matrix(Rp)[0]], *ref.rotation_from_matrix(Rp)[1:]]))
    F = ref.reflection_matrix(pt, axis)
    cmp('reflection_from_matrix', np.hstack(ours.reflection_from_matrix(F)), np.hstack(ref.reflection_from_matrix(F)))
    for S in (ref.scale_matrix(fac, pt), ref.scale_matrix(fac, pt, axis)):
        got, want = ours.scale_from_matrix(S), ref.scale_from_matrix(S)
        cmp('scale_from_matrix', np.hstack([[got[0]], got[1], got[2] if got[2] is not None else []]),
            np.hstack([[want[0]], want[1], want[2] if want[2] is not None else []]))
    normal = [rng.uniform(-1, 1) for _ in range(3)]
    persp = [rng.uniform(-5, 5) for _ in range(3)]
    direc = [rng.uniform(-1, 1) for _ in range(3)]
    for kw in ({}, {'direction': direc}, {'perspective': persp}, {'perspective': persp, 'pseudo': True}):
        cmp('projection_matrix', ours.projection_matrix(pt, normal, **kw), ref.projection_matrix(pt, normal, **kw))
    P = ref.projection_matrix(pt, normal, perspective=persp)
    flat = lambda parts: np.hstack([np.ravel(p) for p in parts if p is not None and not isinstance(p, bool)])
    cmp('projection_from_matrix', flat(ours.projection_from_matrix(P)), flat(ref.projection_from_matrix(P)))
    P = ref.projection_matrix(pt, normal)
    cmp('projection_from_matrix', flat(ours.projection_from_matrix(P)), flat(ref.projection_from_matrix(P)))
    bounds = sorted(rng.uniform(-5, 5) for _ in range(2)) + sorted(rng.uniform(-5, 5) for _ in range(2)) + \
        sorted(rng.uniform(0.1, 10) for _ in range(2))
    for persp_flag in (False, True):
        cmp('clip_matrix', ours.clip_matrix(*bounds, perspective=persp_flag), ref.clip_matrix(*bounds, perspective=persp_flag))
    n = ours.unit_vector(normal)
    d = np.cross(n, [rng.uniform(-1, 1) for _ in range(3)])
    sh = rng.uniform(-1.2, 1.2)
    cmp('shear_matrix', ours.shear_matrix(sh, d, pt, n), ref.shear_matrix(sh, d, pt, n))
    Sh = ref.shear_matrix(sh, d, pt, n)
    cmp('shear_from_matrix', flat(ours.shear_from_matrix(Sh)), flat(ref.shear_from_matrix(Sh)))
    scale = [rng.uniform(0.5, 2) for _ in range(3)]; shear = [rng.uniform(-1, 1) for _ in range(3)]
    persp4 = [rng.uniform(-0.1, 0.1) for _ in range(3)] + [1.0]
    C = ref.compose_matrix(scale, shear, a, pt, persp4)
    cmp('compose_matrix', ours.compose_matrix(scale, shear, a, pt, persp4), C)
    cmp('decompose_matrix', flat(ours.decompose_matrix(C)), flat(ref.decompose_matrix(C)))
    lengths = [rng.uniform(1, 10) for _ in range(3)]; cell = [rng.uniform(60, 120) for _ in range(3)]
    cmp('orthogonalization_matrix', ours.orthogonalization_matrix(lengths, cell), ref.orthogonalization_matrix(lengths, cell))
    v0 = np.random.RandomState(trial).rand(3, 10)
    v1 = ref.concatenate_matrices(Rp, ref.scale_matrix(1.5))[:3, :3].dot(v0) + 1.0
    for scaling in (False, True):
        for svd in (True, False):
            cmp('superimposition_matrix', ours.superimposition_matrix(v0, v1, scaling, svd),
                ref.superimposition_matrix(v0, v1, scaling, svd))
    ball_o, ball_r = ours.Arcball(q0 if trial % 2 else None), ref.Arcball(q0 if trial % 2 else None)
    for ball in (ball_o, ball_r):
        ball.place([320, 320], 320)
        ball.setaxes([1, 1, 0], [-1, 1, 0])
        ball.setconstrain(trial % 3 == 0)
        ball.down([rng.Random(trial).uniform(0, 640) if False else 200, 300])
        ball.drag([500, 250])
        ball.next()
    cmp('Arcball', ball_o.matrix(), ball_r.matrix())
    cmp('arcball_map_to_sphere', ours.arcball_map_to_sphere([200, 900], [320, 320], 320),
        ref.arcball_map_to_sphere([200, 900], [320, 320], 320))
print(json.dumps(worst))
