"""`rostui diagnostics` driven headless (Textual's pilot): keys on a stored picture, then live against Debian's
diagnostics (a rospy diagnostic_updater node, then Debian's aggregator joining; tests/diagnostics_helpers.py).
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any, Awaitable, Callable

from textual.pilot import Pilot
from textual.widgets import Input, Static

from rostui.apps.diagnostics.app import DiagnosticsApp
from rostui.apps.diagnostics.table import StatusTree
from rostui.apps.widgets.notice import Notice
from rostui.models.diagnostics.levels import ERROR, OK, WARN
from rostui.models.diagnostics.store import AGGREGATED, FLAT, DiagnosticsStore

from conftest import until
from diagnostics_helpers import clean_env, need_debian_diagnostics, start_aggregator, start_publisher
from test_diagnostics_model import ROBOT, status

DEADLINE = 60.0
Scenario = Callable[[Pilot, DiagnosticsApp], Awaitable[None]]


class Clock:
    """A clock the test moves."""

    def __init__(self, now: float) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now


def run_app(app: DiagnosticsApp, scenario: Scenario, size: tuple[int, int] = (100, 30)) -> None:
    """Run *app* headless and play *scenario*; it must still be running at the end, and q ends it with 0."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            await scenario(pilot, app)
            assert app.is_running
            await pilot.press("q")
    asyncio.run(main())
    assert app.return_code in (0, None)


def names(app: DiagnosticsApp) -> list[str]:
    """The full names of the rows shown."""
    return app.query_one(StatusTree).names


def said(app: DiagnosticsApp, widget: str) -> str:
    """What the summary, master notice or detail panel says."""
    found = app.query_one(f"#{widget}")
    return found.text if isinstance(found, Notice) else str(found.render())  # type: ignore[attr-defined]


def test_keys_on_a_stored_picture() -> None:
    store = DiagnosticsStore()
    store.take(AGGREGATED, ROBOT, 100.0)
    store.take(FLAT, [status("robot_driver: laser", OK, "Scanning")], 100.0)
    clock = Clock(100.5)
    app = DiagnosticsApp(store=store, clock=clock)

    async def scenario(pilot: Pilot, app: DiagnosticsApp) -> None:
        assert names(app)[:3] == ["/Motors", "/Motors/left", "/Motors/left/motor"]
        assert said(app, "summary") == "/diagnostics_agg tree · 2 ERROR, 1 WARN, 2 OK"
        assert said(app, "master") == "showing a stored picture (not listening)"
        for _ in range(4):
            await pilot.press("down")
        await pilot.pause()
        assert app.query_one(StatusTree).cursor_name == "/Power/battery"
        assert "voltage  10.9" in said(app, "detail") and "hardware id robot-1" in said(app, "detail")
        await pilot.press("l")
        assert names(app) == ["/Motors", "/Motors/left", "/Motors/left/motor", "/Power", "/Power/battery"]
        assert said(app, "summary") == "/diagnostics_agg tree · 2 ERROR, 1 WARN, 2 OK"
        assert said(app, "filtered") == "showing 5 of 7 rows: WARN and worse"
        await pilot.press("l")
        assert names(app) == ["/Power", "/Power/battery"]
        await pilot.press("l", "l")  # stale, then all again
        assert len(names(app)) == 7
        await pilot.press("slash")
        assert app.query_one("#filter", Input).has_focus
        await pilot.press(*"sens")
        assert names(app) == ["/Sensors", "/Sensors/laser"]
        assert said(app, "filtered") == "showing 2 of 7 rows: names matching 'sens'"
        await pilot.press("enter")
        assert app.query_one(StatusTree).has_focus and names(app) == ["/Sensors", "/Sensors/laser"]
        assert app.query_one(StatusTree).cursor_name == "/Sensors/laser"  # the battery hidden: the nearest row
        await pilot.press("escape")
        assert len(names(app)) == 7 and app.query_one(StatusTree).cursor_name == "/Sensors/laser"
        await pilot.press("t")
        assert names(app) == ["robot_driver: laser"]
        assert said(app, "summary") == "/diagnostics flat (no aggregator) · 1 OK"
        await pilot.press("t")
        assert app.query_one(StatusTree).cursor_name == "/Sensors/laser"  # back where it was in the tree
        await pilot.press("up", "up")
        clock.now = 106.0  # nothing new for 6 s
        app.redraw()
        assert said(app, "summary") == "/diagnostics_agg tree · 5 STALE"
        store.take(AGGREGATED, [status("/Power/battery", WARN, "Charging", voltage="11.5")], 106.0)
        app.redraw()
        await pilot.pause()
        assert app.query_one(StatusTree).cursor_name == "/Power/battery"
        detail = said(app, "detail")
        assert "WARN · Charging" in detail and "history (newest first):" in detail and "ERROR  Charge low" in detail

    run_app(app, scenario)


def test_live_flat_then_the_aggregators_tree(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """The publisher alone: the flat list; Debian's aggregator joins: its tree, without a key pressed."""
    need_debian_diagnostics()
    env = clean_env(ros_env)
    publisher = start_publisher(env, tmp_path / "publisher.log")
    aggregator = None
    app = DiagnosticsApp(master_uri=env["ROS_MASTER_URI"])

    async def scenario(pilot: Pilot, app: DiagnosticsApp) -> None:
        nonlocal aggregator
        await until(lambda: len(names(app)) == 3, "the flat statuses", timeout=DEADLINE)
        assert names(app) == ["robot_driver: battery charge", "robot_driver: laser connection",
                              "robot_driver: motor temperature"]
        assert said(app, "summary") == "/diagnostics flat (no aggregator) · 1 ERROR, 1 WARN, 1 OK"
        assert "listening to /diagnostics_agg and /diagnostics (publishing nothing)" in said(app, "master")
        aggregator = await asyncio.to_thread(start_aggregator, env, tmp_path / "aggregator.log")
        await until(lambda: "/Power/robot_driver: battery charge" in names(app), "the aggregator's tree",
                    timeout=DEADLINE)
        assert said(app, "summary").startswith("/diagnostics_agg tree · ")
        table = app.query_one(StatusTree)
        while table.cursor_name != "/Power/robot_driver: battery charge":
            await pilot.press("down")
        await until(lambda: "voltage" in said(app, "detail"), "the battery's values")
        assert "Charge low" in said(app, "detail") and "hardware id robot-1" in said(app, "detail")
        levels = {row.name: row.level for row in table.rows}
        assert levels["/Power"] == ERROR and levels["/Motors"] == WARN and levels["/Sensors"] == OK

    try:
        run_app(app, scenario)
    finally:
        if aggregator is not None:
            aggregator.interrupt()
        publisher.interrupt()
