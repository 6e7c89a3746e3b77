"""SVG snapshots of `rostui graph` on the book's turtlesim graph (stored in snapshots/test_graph_snapshots/).

The app runs for real against a `rostui core` master while headless
turtlesim and a teleop_turtle (agitr's pubvel) run as processes; the test
waits until every registration is in place before the app starts, so the
first poll already holds the whole, unchanging graph (no "new" marks), and
the drawing is taken once it shows the current view.  Regenerate with
``pytest tests/test_graph_snapshots.py --snapshot-update`` and look at the
SVGs before committing them.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest
from conftest import stop_process, until, wait_until
from graph_helpers import book_system, has_edges, master_graph, settled, status, stop_programs
from live_helpers import Program
from textual.pilot import Pilot
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)

from rostui.apps.graph.app import GraphApp
from rostui.models.graph.model import RosGraph
from rostui.models.graph.view import GraphOptions, ViewMode, book_setup

SIZE = (110, 16)


@pytest.fixture
def book(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[list[Program]]:
    """The book's turtlesim system on a `rostui core` master."""
    programs = book_system(ros_env, tmp_path)
    yield programs
    stop_programs(programs)


async def drawn(pilot: Pilot) -> None:
    """Wait for two polls and the drawing of the current view."""
    app = pilot.app
    assert isinstance(app, GraphApp)
    await until(lambda: app.polls >= 2, "two polls")
    await settled(app)
    await pilot.pause()


@pytest.mark.parametrize("view", list(ViewMode), ids=[v.value for v in ViewMode])
def test_book_graph_in_each_view(snap_compare, book: list[Program], view: ViewMode) -> None:
    """Figure 2.2 (nodes only), the active topics, and Figure 2.4 (all topics; the book's setup)."""
    assert snap_compare(GraphApp(GraphOptions(view=view), period=0.2), run_before=drawn, terminal_size=SIZE)


def test_topic_selected_with_details(snap_compare, book: list[Program]) -> None:
    """The book's setup with /turtle1/command_velocity selected: its edges lit, type and both ends listed."""
    async def run_before(pilot: Pilot) -> None:
        await drawn(pilot)
        app = pilot.app
        assert isinstance(app, GraphApp)
        app.select("t:/turtle1/command_velocity")
        await until(lambda: app.graph_view.overflows() and "arrows scroll" in status(app),
                    "the status to say that the drawing beside the details overflows")
        await pilot.pause()

    assert snap_compare(GraphApp(book_setup(), period=0.2), run_before=run_before, terminal_size=(110, 18))


def test_grouped_namespace(snap_compare, book: list[Program]) -> None:
    """The book's setup grouped by namespace: /turtle1's four topics in one double box."""
    options = book_setup().with_(group_namespaces=True)
    assert snap_compare(GraphApp(options, period=0.2), run_before=drawn, terminal_size=(80, 10))


@pytest.fixture
def book_with_subpose(book: list[Program], ros_env: dict[str, str], tmp_path: Path) -> Iterator[None]:
    """The book's system plus agitr's subpose (turtlesim -> /turtle1/pose -> subscribe_to_pose), registered."""
    sub = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
    try:
        wait_until(lambda: has_edges(ros_env, (("/turtlesim", "/turtle1/pose", "/subscribe_to_pose"),)),
                   "subpose to register")
        yield
    finally:
        sub.stop()


@pytest.mark.parametrize("size", [(80, 24), (100, 32)], ids=["80x24", "100x32"])
def test_nodes_only_edge_labels(snap_compare, book_with_subpose: None, size: tuple[int, int]) -> None:
    """Nodes only, edges labelled with their topics: numbered keys and a legend at 80x24, abbreviations at 100x32."""
    assert snap_compare(GraphApp(GraphOptions(), period=0.2), run_before=drawn, terminal_size=size)


@pytest.fixture
def pub_only(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[None]:
    """A master with only `rostui topic pub /greeting` running (a tool node) besides rosout."""
    proc = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "pub", "/greeting", "std_msgs/String",
                             "data: hello", "-r", "1"], env=ros_env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: bool((master_graph(ros_env) or RosGraph()).publishers.get("/greeting")),
                   "rostui topic pub to register")
        yield
    finally:
        stop_process(proc)


@pytest.mark.parametrize("size", [(80, 24), (100, 32)], ids=["80x24", "100x32"])
def test_empty_screen_explains_hide_debug(snap_compare, pub_only: None, size: tuple[int, int]) -> None:
    """Only a tool node runs: the first screen says what hide debug hides and that d shows it.

    The tool node's name holds its pid and start time, so the snapshot is taken of a
    master that is asked under a fixed name: the app's source is handed a stand-in graph
    with the same registrations renamed (``/rostopic_4711_1700000000000``).
    """
    app = GraphApp(GraphOptions(), period=0.2)
    real_fetch = app.source.fetch

    async def fetch() -> RosGraph:
        return _fixed_tool_name(await real_fetch())

    app.source.fetch = fetch  # type: ignore[method-assign]

    async def run_before(pilot: Pilot) -> None:
        await drawn(pilot)
        await until(lambda: "hide debug is on" in str(app.query_one("#empty").render()), "the explanation")
        await pilot.pause()

    assert snap_compare(app, run_before=run_before, terminal_size=size)


def _fixed_tool_name(graph: RosGraph) -> RosGraph:
    """``graph`` with every /rostopic_<pid>_<ms> node called /rostopic_4711_1700000000000."""
    def rename(table: Any) -> dict[str, list[str]]:
        return {k: [re.sub(r"^/rostopic_\d+_\d+$", "/rostopic_4711_1700000000000", n) for n in v]
                for k, v in table.items()}

    return RosGraph.build(rename(graph.publishers), rename(graph.subscribers), rename(graph.services),
                          graph.topic_types)


def test_book_setup_at_80x24(snap_compare, book: list[Program]) -> None:
    """The book's setup in an 80x24 terminal: the key line starts with `? help  q quit`, never cut."""
    assert snap_compare(GraphApp(book_setup(), period=0.2), run_before=drawn, terminal_size=(80, 24))
