"""Highlighted rows keep their text readable: contrast >= 3 between text and highlight, in 16, 256 and truecolor.

The apps colour a row by what it holds (a log level, a topic's liveness) and
then lay the cursor's or the selection's background over it; where the two
would blend (red text on the blue cursor in 16 colours, for example) the text
is lightened or darkened (rostui.apps.widgets.terminal_colors.readable).
These tests read the styles of the cells the widgets really render.
"""

from __future__ import annotations

import asyncio
import time
from pathlib import Path
from typing import Any

import pytest
from rich.color import ColorSystem
from textual.geometry import Region
from textual.pilot import Pilot
from textual.widget import Widget

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.bagview.timeline import TimelineView
from rostui.apps.console.app import ConsoleApp
from rostui.apps.graph.app import GraphApp
from rostui.apps.monitor.app import MonitorApp
from rostui.models.monitor.rows import Liveness
from rostui.core.log.rosout_read import read_rosout_log
from rostui.models.console.model import ConsoleOptions
from rostui.models.contrast import MINIMUM, RGB, contrast_ratio

from bag_view_helpers import write_counts
from colour_modes import MODES, force_mode, shown
from conftest import until
from console_helpers import write_sample_log
from graph_helpers import book_system, run_graph, settled, stop_programs
from monitor_helpers import start_publishers, stop_all


@pytest.fixture(params=list(MODES), ids=lambda m: m.name.lower())
def mode(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> ColorSystem:
    """Each colour mode in turn, forced through the environment as a terminal would set it; UTC stamps."""
    system: ColorSystem = request.param
    force_mode(monkeypatch, system)
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    return system


def faint_text(widget: Widget, system: ColorSystem) -> list[tuple[str, RGB, RGB, float]]:
    """Rendered text (not blanks) of ``widget`` whose colour has contrast < 3 on its own background."""
    width, height = widget.size
    faint = []
    for line in widget.render_lines(Region(0, 0, width, height)):
        for segment in line:
            if not segment.text.strip() or segment.style is None:
                continue
            fg = shown(segment.style.color, system, True)
            bg = shown(segment.style.bgcolor, system, False)
            if fg is not None and bg is not None and contrast_ratio(fg, bg) < MINIMUM:
                faint.append((segment.text.strip(), fg, bg, round(contrast_ratio(fg, bg), 2)))
    return faint


def run(app: Any, scenario: Any, size: tuple[int, int] = (120, 30)) -> None:
    """Run ``app`` headless and play ``scenario``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            await scenario(pilot, app)

    asyncio.run(main())


def test_console_cursor_on_every_level_keeps_contrast(mode: ColorSystem, tmp_path: Path) -> None:
    """The cursor row of rostui console on a DEBUG, INFO, WARN, ERROR and FATAL message: text readable on it."""
    log = write_sample_log(tmp_path / "rosout.log")
    app = ConsoleApp(ConsoleOptions(), read_rosout_log(log), log_name="rosout.log")

    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert app.console.color_system == MODES[mode][2]
        levels = set()
        for row in range(len(app.model)):
            app.table.select_row(row)
            await pilot.pause()
            levels.add(app.model.entry(app.model.seq_at(row)).level)
            assert faint_text(app.table, mode) == [], f"cursor on row {row}"
        assert len(levels) == 5

    run(app, scenario, size=(140, 30))


def test_bag_view_selected_topic_and_cursor_keep_contrast(mode: ColorSystem, tmp_path: Path) -> None:
    """rostui bag view's timeline: the selected topic's name and the cursor column stay readable."""
    bag = write_counts(tmp_path / "counts.mcap")
    app = BagViewApp([str(bag)], publish=False)

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        assert app.console.color_system == MODES[mode][2]
        await until(lambda: app.transport is not None, "the bag to be read")
        await pilot.pause()
        timeline = app.query_one(TimelineView)
        for key in ("5", "down", "2"):
            await pilot.press(key)
            await pilot.pause()
            assert faint_text(timeline, mode) == [], f"after {key}"
        await app.action_quit()

    run(app, scenario)


def test_graph_selection_and_its_neighbours_keep_contrast(
        mode: ColorSystem, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """rostui graph with the book's turtlesim system: the selected box (Tab) and its highlighted neighbours."""
    programs = book_system(ros_env, tmp_path)

    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert app.console.color_system == MODES[mode][2]
        await pilot.press("v", "v")
        await settled(app)
        for _ in range(3):
            await pilot.press("tab")
            await pilot.pause()
            assert app.selected is not None
            assert faint_text(app.graph_view, mode) == [], f"with {app.selected} selected"
        await pilot.press("q")

    try:
        run_graph(GraphApp(period=0.5), scenario)
    finally:
        stop_programs(programs)


def test_monitor_cursor_on_a_live_and_a_quiet_topic_keeps_contrast(
        mode: ColorSystem, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """rostui monitor: the cursor row on a live topic (green text) and on a topic nobody publishes (muted text)."""
    publishers = start_publishers(ros_env, tmp_path, [("/fast", "std_msgs/String", "data: hi", 10)])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        assert app.console.color_system == MODES[mode][2]

        def fast_is_live() -> bool:
            return any(r.name == "/fast" and r.liveness is Liveness.LIVE for r in app.shown)

        await until(fast_is_live, "/fast live in the table")
        table = app.table
        quiet = next(r.name for r in app.shown if r.liveness is not Liveness.LIVE)
        for topic in ("/fast", quiet):
            assert table.select_topic(topic)
            await pilot.pause()
            assert faint_text(table, mode) == [], f"cursor on {topic}"
        await pilot.press("q")

    try:
        run(MonitorApp(), scenario)
    finally:
        stop_all(publishers)
