"""SVG snapshots of `rostui console` (stored in snapshots/test_console_snapshots/).

The real app opens the sample rosout.log (console_helpers: the book's
count_and_log at every level, turtlesim, a listener) through the same reader
and ingest path as `rostui console PATH`; stamps are fixed and shown in UTC,
so every run draws the same screen.  Regenerate with
``pytest tests/test_console_snapshots.py --snapshot-update`` and look at the
SVGs before committing them.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from console_helpers import T0, write_sample_log
from textual.pilot import Pilot
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)

from rostui.apps.console.app import ConsoleApp
from rostui.apps.console.columns import clock_text
from rostui.core.log.rosout_read import RosoutEntry, read_rosout_log
from rostui.models.console.model import ConsoleOptions


@pytest.fixture(autouse=True)
def fixed_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """Truecolor, UTC stamps."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    clock_text.cache_clear()


def sample_app(tmp_path: Path, **options: object) -> ConsoleApp:
    """The console on the sample rosout.log, named as a user in its folder would name it."""
    log = read_rosout_log(write_sample_log(tmp_path / "rosout.log"))
    return ConsoleApp(ConsoleOptions(**options), log, log_name="rosout.log")  # type: ignore[arg-type]


def test_mixed_levels(snap_compare, tmp_path: Path) -> None:
    """Every level in its colour, every column, newest at the bottom, following."""
    assert snap_compare(sample_app(tmp_path), terminal_size=(140, 32))


def test_filtered_highlighted_with_details(snap_compare, tmp_path: Path) -> None:
    """DEBUG and INFO hidden, /turtlesim excluded, 'by 10' highlighted, the listener's error in the detail pane."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.press("1", "2")
        await pilot.press("home", "down")  # the turtlesim wall warning
        await pilot.press("x")
        await pilot.press("h", *"by", "space", "1", "0", "enter")
        app = pilot.app
        assert isinstance(app, ConsoleApp)
        row = next(i for i, (_, e) in enumerate(app.model.shown()) if e.node == "/listener")
        app.table.select_row(row)
        await pilot.press("enter")
        await pilot.pause()

    assert snap_compare(sample_app(tmp_path), run_before=run_before, terminal_size=(120, 30))


def test_paused_small_terminal_with_drops(snap_compare, tmp_path: Path) -> None:
    """80x24, --max 30: drops counted; paused with 3 new messages waiting; narrow columns."""
    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, ConsoleApp)
        await pilot.press("p")
        app.ingest([RosoutEntry((T0 + 60 + n) * 1_000_000_000, 4, "/late", f"late {n}", "late.py", 1, "f", ())
                    for n in range(3)])
        await pilot.pause()

    assert snap_compare(sample_app(tmp_path, max_messages=30), run_before=run_before, terminal_size=(80, 24))


def test_key_line_at_80x24(snap_compare, tmp_path: Path) -> None:
    """80x24: the key line starts with `? help  q quit`; the rest is cut with an ellipsis."""
    assert snap_compare(sample_app(tmp_path), terminal_size=(80, 24))


def test_help_panel(snap_compare, tmp_path: Path) -> None:
    """? at 80x24: the help panel lists the app's keys (hidden ones too), then the table's, over the app."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.press("question_mark")
        await pilot.pause()

    assert snap_compare(sample_app(tmp_path), run_before=run_before, terminal_size=(80, 24))
