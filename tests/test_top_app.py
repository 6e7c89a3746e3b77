"""`rostui top` driven headless (Textual's pilot) against real nodes: a rospy and a roscpp node on this host and a
node registered from another host (tests/top_helpers.py). The table follows the master, s orders it, k stops a node
after y (and not after n), and a node elsewhere or one whose pid changed is never signalled.
"""

from __future__ import annotations

import asyncio
import re
from typing import Any, Awaitable, Callable

from textual.pilot import Pilot

from rostui.apps.top.app import NodeTable, TopApp
from rostui.apps.widgets.confirm import ConfirmScreen
from rostui.apps.widgets.notice import Notice
from rostui.models.top import StopRefused

from conftest import until
from interop_helpers import roscpp_peer_bin, spawn  # noqa: F401  (fixtures)
from top_helpers import REMOTE_NODE, register_remote_node, start_nodes

DEADLINE = 60.0
Scenario = Callable[[Pilot, TopApp], Awaitable[None]]


def run_app(app: TopApp, scenario: Scenario) -> None:
    """Run *app* headless until it measured once, play *scenario*, then q."""
    async def main() -> None:
        async with app.run_test(size=(100, 30)) as pilot:
            await asyncio.wait_for(app.started.wait(), DEADLINE)
            await scenario(pilot, app)
            await pilot.press("q")
    asyncio.run(main())


def said(app: TopApp, notice: str) -> str:
    """A notice's text."""
    return app.query_one(f"#{notice}", Notice).text


async def cursor_to(pilot: Pilot, app: TopApp, name: str) -> None:
    """The table's cursor on node *name*, with the arrow keys."""
    table = app.query_one(NodeTable)
    await until(lambda: name in table.keys, f"{name} listed", timeout=DEADLINE)
    while table.cursor_key != name:
        await pilot.press("down" if table.keys.index(table.cursor_key or "") < table.keys.index(name) else "up")


def test_measure_sort_and_stop(rostui_core: Any, ros_env: dict[str, str], spawn: Any, roscpp_peer_bin: Any) -> None:
    rospy_node, rospy_name, roscpp_node, roscpp_name = start_nodes(spawn, roscpp_peer_bin, ros_env)
    register_remote_node(ros_env)
    app = TopApp(master_uri=ros_env["ROS_MASTER_URI"], interval=0.3)

    async def scenario(pilot: Pilot, app: TopApp) -> None:
        await until(lambda: {rospy_name, roscpp_name, REMOTE_NODE} <= {row.name for row in app.rows}
                    and all(row.usage for row in app.rows if row.name in (rospy_name, roscpp_name)),
                    "both nodes measured and the remote one listed", timeout=DEADLINE)
        assert re.fullmatch(r"4 nodes · 3 here, 1 elsewhere · \d+% CPU here · by cpu", said(app, "summary")), \
            said(app, "summary")  # /rosout, the two nodes, the remote one
        await pilot.press("s")
        assert said(app, "summary").endswith("by memory")
        await pilot.press("s")
        assert app.query_one(NodeTable).keys == sorted(app.query_one(NodeTable).keys)
        await cursor_to(pilot, app, REMOTE_NODE)
        await pilot.press("k")
        assert said(app, "stopped") == f"{REMOTE_NODE} does not run on this host: stop it where it runs"
        await cursor_to(pilot, app, rospy_name)
        assert f"{rospy_name} at http://" in str(app.query_one("#detail").render())
        await pilot.press("k")
        await until(lambda: isinstance(app.screen, ConfirmScreen), "the question")
        await pilot.press("n")
        assert said(app, "stopped") == f"{rospy_name} left running" and rospy_node.proc.poll() is None
        row = next(row for row in app.rows if row.name == roscpp_name)
        try:
            await app.source.stop(row.__class__(**{**row.__dict__, "pid": rospy_node.proc.pid}))
            raise AssertionError("a pid the node does not say was signalled")
        except StopRefused as exc:
            assert str(exc) == f"{roscpp_name} is pid {roscpp_node.proc.pid} now, not {rospy_node.proc.pid}: look again"
        await pilot.press("k")
        await until(lambda: isinstance(app.screen, ConfirmScreen), "the question")
        await pilot.press("y")
        await until(lambda: said(app, "stopped") == f"{rospy_name} ended after SIGINT", "the stop", timeout=DEADLINE)
        assert rospy_node.proc.poll() is not None and roscpp_node.proc.poll() is None
        await until(lambda: rospy_name not in {row.name for row in app.rows}, "the stopped node gone from the table",
                    timeout=DEADLINE)

    run_app(app, scenario)


def test_a_master_that_goes_away_is_said(ros_env: dict[str, str]) -> None:
    app = TopApp(master_uri=ros_env["ROS_MASTER_URI"], interval=0.3)

    async def scenario(pilot: Pilot, app: TopApp) -> None:
        await until(lambda: app.polls >= 1, "a first try")
        assert "does not answer: asking again" in said(app, "master")
        assert said(app, "summary") == "no node on the master"

    run_app(app, scenario)
