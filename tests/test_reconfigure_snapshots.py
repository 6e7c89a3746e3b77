"""SVG snapshots of `rostui reconfigure` (stored in snapshots/test_reconfigure_snapshots/), at 80x24 and 100x40.

Debian's dynamic_reconfigure runs its own test server (Test.cfg: ints, doubles, strings, bools, an enum and
nested groups) under `rostui core`, starting from the .cfg file's defaults. The master line shows the default
URI instead of the test's free port, and a change's time a fixed figure. Regenerate with
``pytest tests/test_reconfigure_snapshots.py --snapshot-update`` and look at the SVGs before committing them.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.reconfigure.app import ReconfigureApp
from rostui.apps.reconfigure.panels import EditScreen, ParamTable
from rostui.models.reconfigure import ParamRow

from conftest import until
from reconfigure_helpers import NODE, clean_env, forget_parameters, need_debian_dynamic_reconfigure, start_server
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)


class StillApp(ReconfigureApp):
    """The real app, naming the master by the default URI and every change's time alike, so each run draws the
    same screen."""

    def master_label(self) -> str:
        """The default master URI."""
        return "http://localhost:11311/"

    def elapsed_text(self, seconds: float) -> str:
        """A fixed figure."""
        return "3 ms"


@pytest.fixture
def server(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[dict[str, str]]:
    """Debian's test server on rostui core, from its defaults."""
    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    forget_parameters(env, NODE)
    running = start_server("real", env, tmp_path / "server.log")
    try:
        yield env
    finally:
        running.interrupt()
        forget_parameters(env, NODE)


def rows(app: ReconfigureApp) -> dict[str, ParamRow]:
    """The parameter rows shown, by name."""
    return {row.name: row for row in app.query_one(ParamTable).rows_shown if isinstance(row, ParamRow)}


async def settled(pilot: Pilot) -> ReconfigureApp:
    """The app once it shows the server's parameters with their values."""
    app = pilot.app
    assert isinstance(app, ReconfigureApp)
    await until(lambda: bool(rows(app)) and all(row.value is not None for row in rows(app).values()),
                "the server's parameters with values")
    await pilot.pause()
    return app


async def to_row(pilot: Pilot, app: ReconfigureApp, name: str) -> None:
    """The table's cursor on parameter *name*."""
    table = app.query_one(ParamTable)
    table.focus()
    target = [row.key for row in table.rows_shown].index("param:" + name)
    while table.cursor_row != target:
        await pilot.press("down" if table.cursor_row < target else "up")
    await pilot.pause()


@pytest.mark.parametrize("size", [(80, 24), (100, 40)], ids=["80x24", "100x40"])
def test_a_server_shown(snap_compare: Any, server: dict[str, str], size: tuple[int, int]) -> None:
    """The server listed and selected; its groups, values (bars for ranged numbers), ranges and enum names."""
    async def run_before(pilot: Pilot) -> None:
        await settled(pilot)

    assert snap_compare(StillApp(master_uri=server["ROS_MASTER_URI"], server_period=0.3), run_before=run_before,
                        terminal_size=size)


@pytest.mark.parametrize("size", [(80, 24), (100, 40)], ids=["80x24", "100x40"])
def test_a_change_the_server_answered(snap_compare: Any, server: dict[str, str], size: tuple[int, int]) -> None:
    """int_ stepped up from 1 to 2: the server keeps it odd (3), and the green line says what it kept."""
    async def run_before(pilot: Pilot) -> None:
        app = await settled(pilot)
        await to_row(pilot, app, "int_")
        await pilot.press("right")
        await until(lambda: rows(app)["int_"].value == 3 and app.notice("params").kind == "ok", "the change kept")
        await pilot.pause()

    assert snap_compare(StillApp(master_uri=server["ROS_MASTER_URI"], server_period=0.3), run_before=run_before,
                        terminal_size=size)


def test_the_enum_editor(snap_compare: Any, server: dict[str, str]) -> None:
    """Enter on int_enum_: its four constants with their descriptions, the current one under the cursor."""
    async def run_before(pilot: Pilot) -> None:
        app = await settled(pilot)
        await to_row(pilot, app, "int_enum_")
        await pilot.press("enter")
        await until(lambda: isinstance(app.screen, EditScreen), "the editor")
        await pilot.pause()

    assert snap_compare(StillApp(master_uri=server["ROS_MASTER_URI"], server_period=0.3), run_before=run_before,
                        terminal_size=(80, 24))
