"""SVG snapshots of the tf tree (stored in snapshots/test_tf_snapshots/).

The buffer is filled by hand with the test chain (map -> odom -> base_link at 20 Hz from
/rospy_tf_chain, base_link -> laser static) and "now" is fixed, so every run draws the same
rates and ages. Regenerate with ``pytest tests/test_tf_snapshots.py --snapshot-update`` and look
at the SVGs before committing them.
"""

from __future__ import annotations

from typing import Any

import pytest
from textual.pilot import Pilot

from rostui.apps.view.tf_tree_app import TfTreeApp
from rostui.apps.view.tf_tree_view import TfTreeView
from rostui.tools.tf import Transform
from rostui.tools.tf.buffer import stamp_ns as ns

from test_tf_tree_view import chain_buffer
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)


def still_app(with_camera: bool = False) -> TfTreeApp:
    buf = chain_buffer()
    if with_camera:
        buf.set_transform("base_link", "camera", Transform.of((0.1, 0.0, 0.5), (0, 0, 0, 1)), ns(100.9), static=False,
                          broadcaster="/camera_driver", received=1000.9)
        buf.set_transform("world", "gps", Transform.identity(), ns(95.0), static=False, broadcaster="/gps_driver",
                          received=996.0)
    return TfTreeApp(master_uri="http://localhost:11311/", view=TfTreeView(buffer=buf, clock=lambda: 101.25))


def test_chain_with_the_static_laser_selected(snap_compare: Any) -> None:
    """The chain; the cursor on laser spells out laser in base_link and in map."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.pause()
        await pilot.press("down", "down", "down")
        await pilot.pause()

    assert snap_compare(still_app(), run_before=run_before, terminal_size=(100, 16))


def test_branches_and_a_second_tree(snap_compare: Any) -> None:
    """A camera beside the laser, a stale gps in another tree; the root map is selected."""
    assert snap_compare(still_app(with_camera=True), terminal_size=(100, 16))
