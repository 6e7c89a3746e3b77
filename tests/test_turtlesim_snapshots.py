"""SVG snapshots of `rostui turtlesim` (stored in snapshots/test_turtlesim_snapshots/).

The app runs for real (embedded master, turtlesim and teleop nodes); the
world is driven through the model itself, step by step, so every run draws
the same picture, and the status line shows fixed rate and master values.
Regenerate with ``pytest tests/test_turtlesim_snapshots.py --snapshot-update``
and look at the SVGs before committing them.
"""

from __future__ import annotations

import asyncio
import dataclasses
import math

import pytest
from textual.pilot import Pilot

from rostui.turtlesim.app import StatusInfo, TurtlesimApp
from rostui.turtlesim.render import TurtleView
from rostui.turtlesim.world import UPDATE_PERIOD, TurtleWorld

from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)

START_DEADLINE = 30.0


class StillStatusApp(TurtlesimApp):
    """The real app with the two values that vary between runs fixed: update rate and master URI."""

    def status_info(self) -> StatusInfo:
        """The live status with rate 62.5 Hz and the default master URI."""
        return dataclasses.replace(super().status_info(), rate=62.5, master_uri="http://localhost:11311/")


@pytest.fixture(autouse=True)
def truecolor(ros_env: dict[str, str], monkeypatch: pytest.MonkeyPatch) -> None:
    """The same colour system on every machine; no master at ROS_MASTER_URI, so the app embeds one."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)


def drive(world: TurtleWorld, name: str, linear: float, angular: float, seconds: float) -> None:
    """Advance the model as turtlesim would with this command held for ``seconds``."""
    for _ in range(round(seconds / UPDATE_PERIOD)):
        world.command(name, linear, 0.0, angular)
        world.update(UPDATE_PERIOD)
    world.command(name, 0.0, 0.0, 0.0)


async def started(pilot: Pilot) -> TurtlesimApp:
    """Wait until the app's nodes run."""
    app = pilot.app
    assert isinstance(app, TurtlesimApp)
    await asyncio.wait_for(app.started.wait(), START_DEADLINE)
    return app


async def show(pilot: Pilot) -> None:
    """Draw the current world and status now rather than on the next timer tick."""
    app = pilot.app
    assert isinstance(app, TurtlesimApp)
    app.query_one(TurtleView).draw_frame()
    app.refresh_status()
    await pilot.pause()


def square_path(world: TurtleWorld) -> None:
    """Forward, quarter turn left, forward, and a curve: trails in three directions."""
    drive(world, "turtle1", 2.0, 0.0, 1.0)
    drive(world, "turtle1", 0.0, math.pi / 2, 1.0)
    drive(world, "turtle1", 2.0, 0.0, 1.0)
    drive(world, "turtle1", 2.0, 2.0, 1.2)


def test_empty_world(snap_compare) -> None:
    """turtle1 alone at the centre facing east, on the default blue background."""
    async def run_before(pilot: Pilot) -> None:
        await started(pilot)
        await show(pilot)

    assert snap_compare(StillStatusApp(), run_before=run_before)


def test_after_driving(snap_compare) -> None:
    """turtle1 after driving a corner and a curve: pen trails in the default pen colour."""
    async def run_before(pilot: Pilot) -> None:
        app = await started(pilot)
        square_path(app.sim.world)
        await show(pilot)

    assert snap_compare(StillStatusApp(), run_before=run_before)


def test_two_turtles(snap_compare) -> None:
    """A spawned turtle2 drove north-east and is selected with Tab (highlighted); turtle1 is not."""
    async def run_before(pilot: Pilot) -> None:
        app = await started(pilot)
        world = app.sim.world
        await app.sim.spawn("turtle2", 2.0, 2.0, math.pi / 4)
        drive(world, "turtle2", 2.0, 0.0, 1.0)
        drive(world, "turtle1", 2.0, 0.0, 0.5)
        await pilot.press("tab")
        await show(pilot)

    assert snap_compare(StillStatusApp(), run_before=run_before)


def test_small_terminal(snap_compare) -> None:
    """The driven world of test_after_driving in a 40x12 terminal: compact turtle, same square world."""
    async def run_before(pilot: Pilot) -> None:
        app = await started(pilot)
        square_path(app.sim.world)
        await show(pilot)

    assert snap_compare(StillStatusApp(), run_before=run_before, terminal_size=(40, 12))


def test_yellow_background(snap_compare) -> None:
    """Chapter 7's yellow background (255, 255, 0) after a clear: the selected turtle1 and turtle2 keep contrast
    (black and dark green instead of gold and light green), the default pen's trail is darkened to stay visible."""
    async def run_before(pilot: Pilot) -> None:
        app = await started(pilot)
        world = app.sim.world
        world.clear((255, 255, 0))
        await app.sim.spawn("turtle2", 2.0, 2.0, math.pi / 4)
        drive(world, "turtle2", 2.0, 0.0, 1.0)
        square_path(world)
        app.select("turtle1")
        await show(pilot)

    assert snap_compare(StillStatusApp(), run_before=run_before)
