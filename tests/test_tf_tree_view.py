"""The tf tree view: rows of a hand-made tree, the widget under the pilot, live from real broadcasters.

Live: map -> odom -> base_link from Debian's rospy tf2_ros.TransformBroadcaster plus base_link ->
laser from tf2_ros's static_transform_publisher (latched /tf_static) on a real roscore; and the same
chain from rostui's client on `rostui core`. Both `rostui tf tree` (TfTreeApp) and `rostui view /tf`
(ViewApp's panel) must show that tree with each edge's broadcaster, rate and "static".
"""

from __future__ import annotations

import asyncio
import time
import xmlrpc.client
from typing import Any

import pytest
from textual.app import App
from textual.widgets import DataTable

from rostui.apps.view.app import ViewApp
from rostui.apps.view.registry import view_class
from rostui.apps.view.tf_tree_app import TfTreeApp
from rostui.apps.view.tf_tree_view import TfTreeView
from rostui.tools.tf import TfBuffer, Transform, quat_from_rpy
from rostui.tools.tf.buffer import stamp_ns as ns
from rostui.models.tf.tree import format_age, format_rate, summary, tree_rows

from interop_helpers import Spawn, spawn  # noqa: F401  (fixture)
from tf_chain import BROADCASTERS, CHAIN

DEADLINE = 60.0


def chain_buffer() -> TfBuffer:
    """The test chain as a rospy broadcaster and a static publisher would leave it, 20 Hz for one second."""
    buf = TfBuffer()
    for i in range(21):
        for parent, child, t, rpy in CHAIN[:2]:
            buf.set_transform(parent, child, Transform.of(t, quat_from_rpy(*rpy)), ns(100.0 + i * 0.05), static=False,
                              broadcaster="/rospy_tf_chain", received=1000.0 + i * 0.05)
    parent, child, t, rpy = CHAIN[2]
    buf.set_transform(parent, child, Transform.of(t, quat_from_rpy(*rpy)), ns(0.0), static=True,
                      broadcaster="/static_transform_publisher_1", received=1000.0)
    return buf


def test_rows_of_a_branching_tree_with_a_second_tree_and_a_loop() -> None:
    buf = chain_buffer()
    ident = Transform.identity()
    for parent, child in [("base_link", "camera"), ("camera", "camera_optical"), ("world", "other"), ("a", "b"),
                          ("b", "a")]:
        buf.set_transform(parent, child, ident, ns(100.0), static=False, broadcaster="/x", received=1000.0)
    labels = [(row.label(), row.in_loop) for row in tree_rows(buf)]
    assert labels == [
        ("map", False),
        ("└─ odom", False),
        ("   └─ base_link", False),
        ("      ├─ camera", False),
        ("      │  └─ camera_optical", False),
        ("      └─ laser", False),
        ("world", False),
        ("└─ other", False),
        ("a", True),
        ("b", True),
    ]
    assert summary(buf) == "10 frames, 2 trees, 1 static, 2 in a loop"


def test_rate_age_and_static_columns() -> None:
    buf = chain_buffer()
    assert format_rate(buf.edge("odom")) == "20.0 Hz"
    assert format_age(buf.edge("odom"), now=101.25) == "0.25 s"
    assert format_rate(buf.edge("laser")) == "static" and format_age(buf.edge("laser"), 5000.0) == ""
    assert format_rate(None) == "" and format_age(None, 0.0) == ""


def table_rows(view: TfTreeView) -> list[list[str]]:
    table: DataTable[Any] = view.table
    return [[str(getattr(cell, "plain", cell)) for cell in table.get_row_at(i)] for i in range(table.row_count)]


def test_view_in_the_pilot_keeps_the_cursor_and_spells_out_the_frame() -> None:
    buf = chain_buffer()

    async def main() -> None:
        view = TfTreeView(buffer=buf, clock=lambda: 101.0)
        app = TfTreeApp(master_uri="http://localhost:11311/", view=view)
        async with app.run_test(size=(100, 20)) as pilot:
            await pilot.pause()
            rows = table_rows(view)
            assert [r[0] for r in rows] == ["map", "└─ odom", "   └─ base_link", "      └─ laser"]
            assert rows[1][1:] == ["/rospy_tf_chain", "20.0 Hz", "0.00 s"]
            assert rows[3][1:3] == ["/static_transform_publisher_1", "static"]
            await pilot.press("down", "down", "down")
            await pilot.pause()
            detail = str(view.detail.render())
            assert "laser in base_link: xyz [0.200, 0.000, 0.300]  rpy° [180.0, 0.0, -17.2]" in detail
            assert "laser in map: xyz [1.571, 2.160, 0.432]" in detail
            buf.set_transform("map", "gps", Transform.identity(), ns(101.0), static=False, broadcaster="/gps",
                              received=1001.0)
            view.redraw()
            assert view.table.cursor_row == 4 and table_rows(view)[4][0] == "      └─ laser"
            assert str(view.summary_line.render()) == "5 frames, 1 tree, 1 static"
            await pilot.press("q")
        assert app.return_code == 0

    asyncio.run(main())


def test_registry_shows_tf_messages_with_the_tree() -> None:
    assert view_class("tf2_msgs/TFMessage") is TfTreeView


async def wait_for_chain(view: TfTreeView, app: App[Any], static_broadcaster: str, dynamic_broadcaster: str) -> None:
    def shown() -> bool:
        rows = table_rows(view)
        return ([r[0] for r in rows] == ["map", "└─ odom", "   └─ base_link", "      └─ laser"]
                and rows[1][1] == dynamic_broadcaster and rows[2][1] == dynamic_broadcaster
                and rows[3][1].startswith(static_broadcaster) and rows[3][2] == "static"
                and rows[1][2].endswith(" Hz") and rows[2][2].endswith(" Hz"))

    deadline = time.monotonic() + DEADLINE
    while not shown():
        assert time.monotonic() < deadline, f"the tree never showed the chain: {table_rows(view)}"
        await asyncio.sleep(0.1)
    rate = float(table_rows(view)[1][2].split()[0])
    assert 5.0 < rate < 40.0, rate  # broadcast at 20 Hz; generous for a loaded machine


def tf_subscribers(env: dict[str, str]) -> set[str]:
    """The nodes the master lists as subscribers of /tf or /tf_static."""
    _, _, (_, subs, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/tf_test")
    return {node for name, nodes in subs if name in ("/tf", "/tf_static") for node in nodes}


BROADCASTER_NAMES = {
    "rospy": ("/static_transform_publisher", "/rospy_tf_chain"),
    "rostui": ("/rostui_tf_chain", "/rostui_tf_chain"),
}


@pytest.mark.parametrize("broadcaster,master", [("rospy", "real_roscore"), ("rostui", "rostui_core")])
def test_live_tree_in_tf_tree_and_in_view(broadcaster: str, master: str, request: pytest.FixtureRequest,
                                          ros_env: dict[str, str], rospy_available: None, spawn: Spawn) -> None:
    request.getfixturevalue(master)
    BROADCASTERS[broadcaster](spawn)
    static_name, dynamic_name = BROADCASTER_NAMES[broadcaster]

    async def in_tf_tree() -> None:
        app = TfTreeApp()
        async with app.run_test(size=(100, 24)) as pilot:
            await wait_for_chain(app.view, app, static_name, dynamic_name)
            assert "4 frames, 1 tree, 1 static" in str(app.view.summary_line.render())
            assert any(n.startswith("/rostui_tf_tree_") for n in tf_subscribers(ros_env))
            await pilot.press("q")
        assert not any(n.startswith("/rostui_tf_tree_") for n in tf_subscribers(ros_env))

    async def in_view() -> None:
        app = ViewApp(["/tf"])
        async with app.run_test(size=(100, 24)) as pilot:
            deadline = time.monotonic() + DEADLINE
            while not app.query(TfTreeView):
                assert time.monotonic() < deadline, "rostui view /tf never mounted the tf tree"
                await asyncio.sleep(0.1)
            await wait_for_chain(app.query_one(TfTreeView), app, static_name, dynamic_name)
            await pilot.press("q")

    asyncio.run(in_tf_tree())
    asyncio.run(in_view())
