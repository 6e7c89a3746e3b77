"""SVG snapshots of the top-down view (stored in snapshots/test_topdown_snapshots/).

The scene (topdown_helpers.scene_app): an 8 m x 5 m room from an occupancy
grid, a wall scanned 2.05 m ahead, a path to the robot, the robot's odometry
arrow at 30 degrees and two poses of a pose array, all in frame "laser".
The markers: one of every visualization_msgs/Marker type in its own colour over the room
(topdown_helpers.every_marker_type).
Regenerate with ``pytest tests/test_topdown_snapshots.py --snapshot-update``
and look at the SVGs (as PNG) before committing them.
"""

from __future__ import annotations

import pytest
from textual.pilot import Pilot
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)

from topdown_helpers import ViewTestApp, every_marker_type, odometry, room, scene_app


@pytest.fixture(autouse=True)
def fixed_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """Truecolor."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)


async def settle(pilot: Pilot) -> None:
    """Let the messages arrive and one frame be drawn."""
    await pilot.pause(0.2)


def test_scene_80x24(snap_compare) -> None:
    """Every layer in its colour, legend on top, 1 m scale bar and frame below."""
    assert snap_compare(scene_app(), run_before=settle, terminal_size=(80, 24))


def test_scene_100x40_zoomed_out_with_a_missing_transform(snap_compare) -> None:
    """One step out; odometry in "odom" has no transform to "laser": left out, with the note in the legend."""
    async def run_before(pilot: Pilot) -> None:
        await settle(pilot)
        app = pilot.app
        app.view.show_topic_message("/odom", odometry(0.0, 0.0, 0.0, frame="odom"))  # type: ignore[attr-defined]
        await pilot.press("minus")
        await pilot.pause(0.2)

    assert snap_compare(scene_app(), run_before=run_before, terminal_size=(100, 40))


def test_every_marker_type_80x24(snap_compare) -> None:
    """Arrow, cube, sphere, cylinder / line strip, line list, cube list, sphere list / points (a red and a blue
    one), text "hi", mesh (a box), triangle: each in its marker's colour, the legend counting 12 markers."""
    app = ViewTestApp(["/map", "/markers"], frame="map", show_rates=False)

    def feed() -> None:
        app.view.show_topic_message("/map", room(frame="map"))
        app.view.show_topic_message("/markers", every_marker_type())

    app.call_after_refresh(feed)
    assert snap_compare(app, run_before=settle, terminal_size=(80, 24))
