"""The tf chain the tf tests broadcast (map -> odom -> base_link dynamic, base_link -> laser static), and
its expected compositions computed independently with 4x4 numpy matrices."""

from __future__ import annotations

import math
import sys
from typing import Iterator

import numpy as np
import pytest

from interop_helpers import Peer, Spawn, rospy_peer
from conftest import REPO

CHAIN = [
    ("map", "odom", (1.0, 2.0, 0.0), (0.0, 0.0, 0.5)),
    ("odom", "base_link", (0.5, -0.25, 0.1), (0.1, -0.2, 1.2)),
    ("base_link", "laser", (0.2, 0.0, 0.3), (math.pi, 0.0, -0.3)),
]
"""parent, child, translation, roll/pitch/yaw; the last is the static one."""

STATIC_PUBLISHER = "/usr/lib/tf2_ros/static_transform_publisher"
HZ = "20"


def _rot(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def pose_in(target: str, source: str) -> np.ndarray:
    """The 4x4 matrix taking points of ``source`` into ``target`` (tf_echo TARGET SOURCE's transform)."""
    frames = {"map": np.eye(4)}
    for parent, child, t, rpy in CHAIN:
        m = np.eye(4)
        m[:3, :3] = _rot(*rpy)
        m[:3, 3] = t
        frames[child] = frames[parent] @ m
    return np.linalg.inv(frames[target]) @ frames[source]


def start_rospy_chain(spawn: Spawn) -> list[Peer]:
    """Debian's rospy tf2_ros broadcaster and tf2_ros's static_transform_publisher (C++), both running."""
    parent, child, (x, y, z), (roll, pitch, yaw) = CHAIN[-1]
    static = spawn([STATIC_PUBLISHER, repr(x), repr(y), repr(z), repr(yaw), repr(pitch), repr(roll), parent, child],
                   label="static_transform_publisher")
    dynamic = spawn(rospy_peer("rospy_tf_chain.py", HZ), label="rospy_tf_chain")
    dynamic.wait_for("broadcasting")
    return [static, dynamic]


def start_rostui_chain(spawn: Spawn) -> list[Peer]:
    """The same chain from rostui's client (tests/peers/rostui_tf_chain.py)."""
    peer = spawn([sys.executable, str(REPO / "tests" / "peers" / "rostui_tf_chain.py"), HZ], label="rostui_tf_chain")
    peer.wait_for("broadcasting")
    return [peer]


BROADCASTERS = {"rospy": start_rospy_chain, "rostui": start_rostui_chain}
