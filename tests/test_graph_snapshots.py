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

from pathlib import Path
from typing import Any, Iterator

import pytest
from conftest import until
from graph_helpers import book_system, settled, stop_programs
from live_helpers import Program
from textual.pilot import Pilot
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)

from rostui.apps.graph.app import GraphApp
from rostui.models.graph.view import GraphOptions, ViewMode, book_setup

SIZE = (110, 16)


@pytest.fixture(autouse=True)
def truecolor(monkeypatch: pytest.MonkeyPatch) -> None:
    """The same colour system on every machine."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)


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
        await pilot.pause()

    assert snap_compare(GraphApp(book_setup(), period=0.2), run_before=run_before, terminal_size=(110, 18))


def test_grouped_namespace(snap_compare, book: list[Program]) -> None:
    """The book's setup grouped by namespace: /turtle1's four topics in one double box."""
    options = book_setup().with_(group_namespaces=True)
    assert snap_compare(GraphApp(options, period=0.2), run_before=drawn, terminal_size=(80, 10))


def test_book_setup_at_80x24(snap_compare, book: list[Program]) -> None:
    """The book's setup in an 80x24 terminal: the key line starts with `? help  q quit`, never cut."""
    assert snap_compare(GraphApp(book_setup(), period=0.2), run_before=drawn, terminal_size=(80, 24))
