"""SVG snapshots of `rostui loggers` (stored in snapshots/test_loggers_snapshots/).

A fixed set of nodes runs under `rostui core`: /rosout, and /talker and
/listener (rostui nodes of package agitr, on an engine thread of this test;
/talker has an extra ros.agitr.motor logger at WARN).  The master line shows
the default URI instead of the test's free port.  Regenerate with
``pytest tests/test_loggers_snapshots.py --snapshot-update`` and look at the
SVGs before committing them.
"""

from __future__ import annotations

from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.loggers.app import LoggersApp
from rostui.core.node import AsyncNode
from rostui.core.node.engine import Engine

from loggers_helpers import DEADLINE, listed_nodes, notice, select_node, until
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)


class StillMasterApp(LoggersApp):
    """The real app, naming the master by the default URI so that every run draws the same line."""

    def master_label(self) -> str:
        """The default master URI."""
        return "http://localhost:11311/"


class Graph:
    """/talker and /listener on an engine thread; ``stop(name)`` shuts one down."""

    def __init__(self) -> None:
        self.engine = Engine()
        self.nodes: dict[str, AsyncNode] = {}
        for name in ("talker", "listener"):
            self.nodes[f"/{name}"] = self.engine.run(AsyncNode(name, argv=[], package="agitr").start(),
                                                     timeout=DEADLINE)
        self.nodes["/talker"].log.tree.set_level("ros.agitr.motor", "WARN")

    def stop(self, name: str) -> None:
        """Shut ``name`` down (it unregisters from the master)."""
        node = self.nodes.pop(name)
        self.engine.run(node.shutdown("snapshot"), timeout=DEADLINE)

    def close(self) -> None:
        """Shut the remaining nodes down and stop the engine."""
        for name in list(self.nodes):
            self.stop(name)
        self.engine.stop()


@pytest.fixture
def graph(rostui_core: Any) -> Iterator[Graph]:
    """The fixed node set under a rostui core."""
    nodes = Graph()
    try:
        yield nodes
    finally:
        nodes.close()


async def settled(pilot: Pilot) -> LoggersApp:
    """The app once it lists the fixed node set."""
    app = pilot.app
    assert isinstance(app, LoggersApp)
    await until(lambda: listed_nodes(app) == ["/listener", "/rosout", "/talker"], "the fixed node set", app=app)
    return app


def test_level_changed(snap_compare: Any, graph: Graph) -> None:
    """/talker selected, ros.agitr (preselected) set to DEBUG with d: table, mark and green notice show it."""
    async def run_before(pilot: Pilot) -> None:
        app = await settled(pilot)
        await select_node(pilot, app, "/talker")
        await pilot.press("d")
        await until(lambda: notice(app, "levels") == ("ros.agitr set to DEBUG", "ok"), "ros.agitr at DEBUG", app=app)
        await pilot.pause()

    assert snap_compare(StillMasterApp(), run_before=run_before)


def test_selected_node_gone(snap_compare: Any, graph: Graph) -> None:
    """/listener selected, then it shuts down: it leaves the list, a red line under the loggers says so."""
    async def run_before(pilot: Pilot) -> None:
        app = await settled(pilot)
        await select_node(pilot, app, "/listener")
        graph.stop("/listener")
        await until(lambda: notice(app, "loggers") == ("node /listener is gone: the master no longer lists it",
                                                       "error"), "the gone node reported", app=app)
        await until(lambda: listed_nodes(app) == ["/rosout", "/talker"], "/listener gone from the list", app=app)
        await pilot.pause()

    assert snap_compare(StillMasterApp(), run_before=run_before)
