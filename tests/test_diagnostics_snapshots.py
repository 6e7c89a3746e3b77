"""SVG snapshots of `rostui diagnostics` (stored in snapshots/test_diagnostics_snapshots/), at 80x24 and 100x40.

The app draws a stored picture: the statuses Debian's aggregator publishes for tests/diagnostics_helpers.py's
robot (the same names, levels, messages and values; test_diagnostics_cli.py checks those against the real
aggregator), a second update of the battery for its history, at a fixed clock in UTC, so each run draws the same
screen. Regenerate with ``pytest tests/test_diagnostics_snapshots.py --snapshot-update`` and look at the SVGs
before committing them.
"""

from __future__ import annotations

import time
from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.diagnostics.app import DiagnosticsApp
from rostui.apps.diagnostics.table import StatusTree
from rostui.models.diagnostics.levels import ERROR, OK, WARN
from rostui.models.diagnostics.store import AGGREGATED, DiagnosticsStore

from test_diagnostics_model import status
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)

SIZES = [(80, 24), (100, 40)]
BATTERY = "/Power/robot_driver: battery charge"


@pytest.fixture(autouse=True)
def utc(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """History times in UTC on every machine."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    yield
    monkeypatch.undo()
    time.tzset()


def robot_picture() -> DiagnosticsStore:
    """What the aggregator said twice, 1 s apart: the battery went from low to critical."""
    store = DiagnosticsStore()
    first = [
        status("/Motors", WARN, "Warning"),
        status("/Motors/robot_driver: motor temperature", WARN, "Running hot", "robot-1", temperature="71.5"),
        status("/Power", ERROR, "Error"),
        status(BATTERY, ERROR, "Charge low", "robot-1", voltage="10.9", percentage="7"),
        status("/Sensors", OK, "All OK"),
        status("/Sensors/robot_driver: laser connection", OK, "Scanning", "robot-1", frequency="10.0",
               frame_id="laser"),
    ]
    store.take(AGGREGATED, first, 1_700_000_000.0)
    store.take(AGGREGATED, first[:3] + [status(BATTERY, ERROR, "Charge critical", "robot-1", voltage="10.2",
                                               percentage="2")] + first[4:], 1_700_000_001.0)
    return store


def still_app() -> DiagnosticsApp:
    """The app on the stored picture, 0.4 s after its last update."""
    return DiagnosticsApp(store=robot_picture(), clock=lambda: 1_700_000_001.4)


async def to_battery(pilot: Pilot) -> None:
    """The cursor on the battery's status."""
    table = pilot.app.query_one(StatusTree)
    while table.cursor_name != BATTERY:
        await pilot.press("down")
    await pilot.pause()


@pytest.mark.parametrize("size", SIZES, ids=["80x24", "100x40"])
def test_the_tree_with_the_battery_selected(snap_compare: Any, size: tuple[int, int]) -> None:
    """Groups and statuses coloured by level; the battery's values and the history of what it said."""
    assert snap_compare(still_app(), run_before=to_battery, terminal_size=size)


@pytest.mark.parametrize("size", SIZES, ids=["80x24", "100x40"])
def test_warnings_and_worse_filtered_by_name(snap_compare: Any, size: tuple[int, int]) -> None:
    """l once (WARN and worse), then / and "pow": only the power group, and the summary says what is hidden."""
    async def run_before(pilot: Pilot) -> None:
        await pilot.press("l", "slash", *"pow")
        await pilot.pause()

    assert snap_compare(still_app(), run_before=run_before, terminal_size=size)
