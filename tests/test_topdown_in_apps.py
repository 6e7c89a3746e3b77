"""The top-down view inside other apps: the monitor's Enter on /scan, and the bag view's inspector.

The monitor runs headless against `rostui core` with tests/peers/topdown_talker.py (rostui's
client); Enter on /scan opens the view over the table, listening to tf while open, and Escape
goes back and unsubscribes.  A bag holds two LaserScans of a wall (2.05 m, then 1.05 m ahead,
frame "laser"); no master is needed, and the inspector's view must not listen to tf (it draws
recorded messages).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.monitor.app import MonitorApp
from rostui.apps.view.app import ViewScreen
from rostui.apps.view.topdown_view import TopDownView
from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection

from bag_view_helpers import inspector_open
from conftest import until
from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from monitor_helpers import run_monitor
from topdown_helpers import TALKER_SPOTS, LaserScan, sync, wall_scan

T0 = 1_700_000_000_000_000_000


def scan_bag(path: Path) -> Path:
    """/scan: a wall 2.05 m ahead, then 1.05 m ahead, 100 ms apart."""
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/scan", "sensor_msgs/LaserScan", LaserScan._md5sum, LaserScan._full_text,
                                     "/scan"))
    for i, x in enumerate([2.05, 1.05]):
        msg = wall_scan(x)
        msg.header.stamp.secs = T0 // 10**9
        writer.write(0, T0 + i * 100_000_000, msg.serialize())
    writer.close()
    return path


def wall_columns(view: TopDownView) -> set[int]:
    """The canvas columns the scan's wall is drawn in; none while the view has no canvas (being laid out)."""
    vp = view.viewport
    if vp is None:
        return set()
    return {c for r in range(vp.rows) for c in range(vp.cols) if view.cell_topic(c, r) == "/scan"}


def column_of(view: TopDownView, x: float) -> int:
    """The canvas column showing (x, 0); -1 while the view has no canvas there (being laid out)."""
    cell = view.viewport.cell_of(x, 0.0) if view.viewport is not None else None
    return cell[0] if cell is not None else -1


@sync
async def test_bag_inspector_draws_the_scan_under_the_cursor(tmp_path: Path) -> None:
    app = BagViewApp([str(scan_bag(tmp_path / "scan.mcap"))], publish=False)
    async with app.run_test(size=(100, 40)) as pilot:
        await inspector_open(app, pilot)
        await until(lambda: isinstance(app.inspector_view.view, TopDownView)
                    and bool(wall_columns(app.inspector_view.view)), "the first scan in the inspector")
        view = app.inspector_view.view
        assert isinstance(view, TopDownView)
        assert view.tf_source is None and view.tf_buffer is None
        assert wall_columns(view) == {column_of(view, 2.05)}
        await pilot.press("end")
        await until(lambda: wall_columns(view) == {column_of(view, 1.05)}, "the second scan, 1.05 m ahead")
        await app.action_quit()


def test_monitor_enter_on_a_scan_opens_the_top_down_view(rostui_core: Any, ros_env: dict[str, str],
                                                         spawn: Spawn) -> None:
    talker = spawn([sys.executable, str(PEERS / "topdown_talker.py"), "rostui"], label="topdown talker")
    talker.wait_for("ready")

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: app.topic_type("/scan") == "sensor_msgs/LaserScan", "/scan listed")
        await until(lambda: app.table.select_topic("/scan"), "the row of /scan")
        await pilot.press("enter")
        assert isinstance(app.screen, ViewScreen)
        panel = app.screen.grid.panels[0]

        def drawn() -> bool:
            view = panel.view
            if not isinstance(view, TopDownView) or view.viewport is None:
                return False
            cell = view.viewport.cell_of(*TALKER_SPOTS["/scan"])
            return cell is not None and view.cell_topic(*cell) == "/scan"

        await until(drawn, "the scan drawn over the monitor")
        view = panel.view
        assert isinstance(view, TopDownView) and view.tf_source is not None
        assert panel.feed.subscribed
        await pilot.press("escape")
        await until(lambda: not isinstance(app.screen, ViewScreen), "back to the table")
        assert not panel.feed.subscribed and view.tf_source is None

    run_monitor(MonitorApp(period=0.3), scenario, size=(120, 40))
