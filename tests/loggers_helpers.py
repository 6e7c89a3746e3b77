"""Helpers for the loggers app tests: run the app headless, wait on its state, read its notices."""

from __future__ import annotations

import asyncio
from typing import Awaitable, Callable

from textual.pilot import Pilot

from rostui.apps.loggers.app import LoggersApp
from rostui.apps.loggers.panels import LevelList, LoggerTable, NodeList

from conftest import until as poll_until

DEADLINE = 30.0
"""Seconds a test waits for something the user would see (generous: CI machines are slow)."""

Scenario = Callable[[Pilot, LoggersApp], Awaitable[None]]


def quick_app(**kwargs: float) -> LoggersApp:
    """The real app with short refresh periods and a short call timeout, so tests see changes soon."""
    settings = {"node_period": 0.3, "ping_period": 0.5, "timeout": 2.0}
    settings.update(kwargs)
    return LoggersApp(**settings)


async def until(predicate: Callable[[], bool], what: str, timeout: float = DEADLINE,
                app: LoggersApp | None = None) -> None:
    """Poll ``predicate`` on the running loop until it holds; fail with ``what`` (and ``app``'s notices)."""
    try:
        await poll_until(predicate, what, timeout)
    except AssertionError as error:
        if app is None:
            raise
        raise AssertionError(f"{error}; the app shows {notices(app)}") from None


def run_app(app: LoggersApp, scenario: Scenario, size: tuple[int, int] = (100, 30)) -> None:
    """Run ``app`` headless until it has asked the master once, then play ``scenario``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await asyncio.wait_for(app.started.wait(), DEADLINE)
            await scenario(pilot, app)

    asyncio.run(main())


def notice(app: LoggersApp, panel: str) -> tuple[str, str]:
    """``(text, kind)`` of the notice under ``nodes``, ``loggers``, ``levels``, or the ``master`` line."""
    widget = app.notice(panel)
    return widget.text, widget.kind


def notices(app: LoggersApp) -> dict[str, tuple[str, str]]:
    """Every notice of the app, for failure messages."""
    return {panel: notice(app, panel) for panel in ("master", "nodes", "loggers", "levels")}


def listed_nodes(app: LoggersApp) -> list[str]:
    """The node names the node list shows."""
    return list(app.query_one(NodeList).node_names)


def shown_levels(app: LoggersApp) -> dict[str, str]:
    """Logger name -> level text as the logger table shows them."""
    table = app.query_one(LoggerTable)
    return {name: str(table.get_cell(name, "level")) for name in table.logger_names}


def marked_level(app: LoggersApp) -> str | None:
    """The level the level list marks as current."""
    return app.query_one(LevelList).current


async def select_node(pilot: Pilot, app: LoggersApp, name: str) -> None:
    """Move the node list's cursor to ``name`` with the arrow keys and wait for its loggers."""
    await highlight_node(pilot, app, name)
    await until(lambda: app.node == name and bool(app.loggers), f"the loggers of {name}", app=app)


async def highlight_node(pilot: Pilot, app: LoggersApp, name: str) -> None:
    """Move the node list's cursor to ``name`` with the arrow keys (which asks the node for its loggers)."""
    await until(lambda: name in listed_nodes(app), f"{name} in the node list")
    node_list = app.query_one(NodeList)
    node_list.focus()
    await pilot.pause()
    while node_list.highlighted_name != name:
        names = listed_nodes(app)
        current = names.index(node_list.highlighted_name) if node_list.highlighted_name in names else -1
        await pilot.press("down" if current < names.index(name) else "up")


async def select_logger(pilot: Pilot, app: LoggersApp, logger: str) -> None:
    """Move the logger table's cursor to ``logger`` with the arrow keys."""
    table = app.query_one(LoggerTable)
    table.focus()
    await pilot.pause()
    await until(lambda: logger in table.logger_names, f"logger {logger} listed", app=app)
    while table.highlighted_name != logger:
        names = table.logger_names
        await pilot.press("down" if table.cursor_row < names.index(logger) else "up")
    await until(lambda: app.logger == logger, f"{logger} selected")
