"""`rostui reconfigure` driven headless (Textual's pilot) against real reconfigure servers.

dynamic_reconfigure's own test server (tests/python_compat/real/dynamic_reconfigure/test/testserver.py, its
``Test.cfg``: ints, doubles, strings, bools, an enum, nested groups) runs under Debian's rospy (the real
dynamic_reconfigure) and under ``rostui python``. The app lists it, shows its groups and live values, and each
key sends a change the server really gets: Debian's own ``dynparam get`` reads it back. The server's callback
keeps ints odd, flips bools and appends "A" to strings, so what it kept differs from what was asked, as a
real driver's clamping does, and the app says so.
"""

from __future__ import annotations

import ast
import asyncio
import subprocess
from pathlib import Path
from typing import Any, Awaitable, Callable

import pytest
from textual.pilot import Pilot

from rostui.apps.reconfigure.app import ReconfigureApp
from rostui.apps.reconfigure.panels import EditScreen, ParamTable
from rostui.apps.widgets.name_list import NameList
from rostui.models.reconfigure import GroupRow, ParamRow

from conftest import SYSTEM_PYTHON, until
from reconfigure_helpers import DEBIAN_DYNPARAM, NODE, clean_env, forget_parameters, need_debian_dynamic_reconfigure, \
    start_server

DEADLINE = 30.0
Scenario = Callable[[Pilot, ReconfigureApp], Awaitable[None]]


def run_app(app: ReconfigureApp, scenario: Scenario, size: tuple[int, int] = (100, 30)) -> None:
    """Run *app* headless and play *scenario*."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await asyncio.wait_for(app.started.wait(), DEADLINE)
            await scenario(pilot, app)

    asyncio.run(main())


def debian_get(env: dict[str, str]) -> dict[str, Any]:
    """The server's configuration as Debian's dynparam reads it."""
    done = subprocess.run([SYSTEM_PYTHON, str(DEBIAN_DYNPARAM), "get", NODE], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return dict(ast.literal_eval(done.stdout.strip()))


def shown(app: ReconfigureApp) -> dict[str, ParamRow]:
    """The parameter rows the table shows, by name."""
    return {row.name: row for row in app.query_one(ParamTable).rows_shown if isinstance(row, ParamRow)}


async def cursor_to(pilot: Pilot, app: ReconfigureApp, name: str) -> None:
    """Move the table's cursor to parameter *name* with the arrow keys."""
    table = app.query_one(ParamTable)
    table.focus()
    keys = [row.key for row in table.rows_shown]
    target = keys.index("param:" + name)
    while table.cursor_row != target:
        await pilot.press("down" if table.cursor_row < target else "up")
    await pilot.pause()


def notice(app: ReconfigureApp) -> str:
    """What the line under the table says."""
    return app.notice("params").text


@pytest.fixture
def server(request: pytest.FixtureRequest, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Any:
    """dynamic_reconfigure's test server on rostui core: Debian's (``real``) or under rostui python (``shim``)."""
    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    running = start_server(request.param, env, tmp_path / "server.log")
    try:
        yield env
    finally:
        running.interrupt()
        forget_parameters(env, NODE)


@pytest.mark.parametrize("server", ["real", "shim"], indirect=True)
def test_keys_change_the_real_server(server: dict[str, str]) -> None:
    env = server

    async def scenario(pilot: Pilot, app: ReconfigureApp) -> None:
        await until(lambda: app.query_one(NameList).names == [NODE], "the server listed")
        await until(lambda: shown(app).get("int_") is not None and shown(app)["int_"].value is not None,
                    "the server's parameters")
        rows = app.query_one(ParamTable).rows_shown
        assert [row.name for row in rows if isinstance(row, GroupRow)] == ["Group_One", "GROUP2", "Group3",
                                                                          "Upper_Group_2"]
        assert shown(app)["int_enum_"].value_text() == "Small (0)"
        assert shown(app)["int_"].range_text() == "-10 … 10"
        before = debian_get(env)

        await cursor_to(pilot, app, "int_")
        await pilot.press("right")
        asked = before["int_"] + 1
        await until(lambda: app.last_change is not None, "the step answered", timeout=DEADLINE)
        assert app.last_change is not None and app.last_change.asked == asked and not app.last_change.error
        assert debian_get(env)["int_"] == asked | 1  # the server keeps ints odd
        if asked % 2 == 0:
            assert notice(app).startswith(f"int_: asked {asked}, {NODE} kept {asked | 1} ("), notice(app)
        await until(lambda: shown(app)["int_"].value == asked | 1, "the table follows the server's update")

        await cursor_to(pilot, app, "int_enum_")
        await pilot.press("enter")
        assert isinstance(app.screen, EditScreen)
        await pilot.press("down", "down", "enter")
        await until(lambda: app.last_change is not None and app.last_change.name == "int_enum_", "Large answered")
        assert debian_get(env)["int_enum_"] == 2
        await until(lambda: shown(app)["int_enum_"].value_text() == "Large (2)", "the table follows the server")

        await cursor_to(pilot, app, "str_")
        await pilot.press("enter")
        field = app.screen.query_one("#field")
        field.value = "hello"  # type: ignore[attr-defined]
        await pilot.press("enter")
        await until(lambda: app.last_change is not None and app.last_change.name == "str_", "the string answered")
        assert debian_get(env)["str_"] == "helloA"  # the server appends A
        await pilot.press("right")
        await until(lambda: "is a string: Enter edits it" in notice(app), "strings are typed, not stepped")

        await cursor_to(pilot, app, "double_")
        await pilot.press("enter")
        app.screen.query_one("#field").value = "not a number"  # type: ignore[attr-defined]
        await pilot.press("enter")
        assert "can't set parameter 'double_'" in str(app.screen.query_one("#edit-error").render())
        await pilot.press("escape")
        assert not isinstance(app.screen, EditScreen)

    run_app(ReconfigureApp(master_uri=env["ROS_MASTER_URI"], server_period=0.3), scenario)


def test_no_server_and_a_named_one_that_comes_later(rostui_core: Any, ros_env: dict[str, str],
                                                    tmp_path: Path) -> None:
    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    started: list[Any] = []

    async def scenario(pilot: Pilot, app: ReconfigureApp) -> None:
        await until(lambda: app.notice("servers").text == "no reconfigure server", "the empty list said")
        assert app.notice("params").text.startswith(f"{NODE} is not on the master")
        started.append(await asyncio.to_thread(start_server, "real", env, tmp_path / "server.log"))
        await until(lambda: app.source.selected == NODE and bool(shown(app)), "the named server shown once it came")
        assert f"changes go to {NODE}" in app.notice("master").text
        started.pop().interrupt()
        await until(lambda: "is gone" in notice(app), "the server's end said")

    try:
        run_app(ReconfigureApp(master_uri=env["ROS_MASTER_URI"], node=NODE, server_period=0.3), scenario)
    finally:
        for running in started:
            running.interrupt()
        forget_parameters(env, NODE)
