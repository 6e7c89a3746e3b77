"""geometry_tutorials' turtle_tf and turtle_tf2 demos, unmodified, in rostui's turtlesim under both rospys.

The demo of the tf tutorials: a broadcaster per turtle sends its pose on /tf (tf's or tf2_ros's
TransformBroadcaster, tf.transformations for the quaternion), and a listener spawns turtle2 and steers it
towards turtle1 from the transform it looks up (tf's TransformListener.lookupTransform with slashed frame
names, or tf2_ros's Buffer.lookup_transform). Each demo runs under `rostui python` (rostui's rospy, tf and
tf2_ros) and under Debian's python3 with the real ones, against a fresh headless rostui turtlesim, on rostui
core and on a real roscore. A user sees turtle2 drive up to turtle1 and stop there; tf2's listener node also
offers its buffer's ``~tf2_frames`` service, tf's does not. Sources: tests/python_compat/real/SOURCES.md.
"""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from conftest import REPO, wait_until
from test_interop_turtlesim import turtlesim_python  # noqa: F401  (genpy's turtlesim for Debian's side)
from test_turtlesim_scripts import CENTRE, SIDES, command, sides, world  # noqa: F401  (fixtures)

DEMOS = REPO / "tests" / "python_compat" / "real" / "geometry_tutorials"
#: How close turtle2 must come to turtle1 (m): the listener drives at half the distance per second.
CLOSE = 0.3


def services(env: dict[str, str]) -> list[str]:
    """`rostui service list`."""
    out = subprocess.run([sys.executable, "-m", "rostui", "service", "list"], env=env, capture_output=True,
                         text=True, timeout=60)
    return out.stdout.split()


@pytest.mark.parametrize("demo", ["turtle_tf", "turtle_tf2"])
def test_turtle2_follows_turtle1(demo: str, world, sides: dict[str, dict[str, str]]) -> None:  # noqa: F811
    suffix = demo.removeprefix("turtle_")
    nodes = DEMOS / demo / "nodes"
    for side in SIDES:
        w = world()
        leader, follower = w.echo("/turtle1/pose"), w.echo("/turtle2/pose")
        assert leader.last().x == pytest.approx(CENTRE)
        for turtle in ("turtle1", "turtle2"):
            w.run(command(side, nodes / f"turtle_{suffix}_broadcaster.py", f"__name:={turtle}_{suffix}_broadcaster",
                          f"_turtle:={turtle}"), sides[side], f"{side} {turtle} broadcaster")
        listener = w.run(command(side, nodes / f"turtle_{suffix}_listener.py"), sides[side], f"{side} listener")

        def close() -> bool:
            poses = follower.poses()
            return bool(poses) and math.dist((poses[-1].x, poses[-1].y), (CENTRE, CENTRE)) < CLOSE

        wait_until(lambda: close() or listener.proc.poll() is not None, f"turtle2 near turtle1 ({side})", timeout=90)
        assert listener.proc.poll() is None, listener.output
        # Where the listener spawned it, as turtlesim says. The echo's first pose is not that: the listener drives
        # as soon as turtle2 exists, and the echo connects to its new pose topic only after the master tells it.
        w.sim.wait_for(r"Spawning turtle \[turtle2\] at x=\[4\.000000\], y=\[2\.000000\]")
        frames_service = f"/turtle_{suffix}_listener/tf2_frames"
        assert (frames_service in services(w.env)) == (demo == "turtle_tf2"), side
        assert "Traceback" not in listener.output, listener.output
