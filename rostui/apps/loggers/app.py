"""LoggersApp: rqt_logger_level in the terminal.

Left, the nodes that serve ``get_loggers`` (the master's service list, asked
again every second); middle, the selected node's loggers and levels; right,
the five levels with the selected logger's current one marked.  A key
(``d`` ``i`` ``w`` ``e`` ``f``), Enter on a level or a click sets it through
the node's ``set_logger_level``.  Whatever fails (no
master, node gone, a call refused or timed out) is said in red under the
panel it concerns, and the app keeps running and retrying.

A node's ``get_loggers`` is called only when it is selected, after a level
is set and on ``r``; in between the selected node is pinged through its slave
API (``getPid``, as ``rosnode ping`` does), so a node that died is reported
promptly.  Reading loggers on a timer would be harmful: the roscpp of Debian
12 (rosconsole 1.14 on log4cxx 1.0) crashes on the logger service call that
follows a ``get_loggers``, so polling would kill a roscpp node that the user
only looked at.
"""

from __future__ import annotations

import asyncio
from functools import partial
from pathlib import Path

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import DataTable, Footer, OptionList
from textual.worker import Worker

from rostui.apps.loggers.panels import LevelList, LoggerTable, NodeList, Notice
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core.master_errors import MasterUnreachableError, unreachable_text
from rostui.models.loggers import (
    DEFAULT_TIMEOUT, LOGGER_ERRORS, LoggerLevel, LoggerLevels, LoggerNode, NodeGoneError, preferred_logger,
)

#: Seconds between two readings of the master's node list.
NODE_PERIOD = 1.0

#: Seconds between two pings of the selected node.
PING_PERIOD = 2.0

SET_HINT = "d i w e f or Enter: set level"


class LoggersApp(ReleasesOnExit, KeysApp):
    """Lists nodes, their loggers and levels; sets a logger's level with a key or a click.

    ``master_uri`` defaults to ROS_MASTER_URI; ``timeout`` bounds every master
    query and service call.
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui loggers"

    BINDINGS = [
        Binding("q", "quit", "quit"),
        Binding("r", "refresh", "refresh"),
        Binding("d", "set_level('DEBUG')", "DEBUG"),
        Binding("i", "set_level('INFO')", "INFO"),
        Binding("w", "set_level('WARN')", "WARN"),
        Binding("e", "set_level('ERROR')", "ERROR"),
        Binding("f", "set_level('FATAL')", "FATAL"),
    ]

    def __init__(self, *, master_uri: str | None = None, timeout: float = DEFAULT_TIMEOUT,
                 node_period: float = NODE_PERIOD, ping_period: float = PING_PERIOD) -> None:
        super().__init__()
        self.client = LoggerLevels(master_uri, timeout=timeout)
        self.node_period = node_period
        self.ping_period = ping_period
        self.node = ""
        self.logger = ""
        self.nodes: dict[str, LoggerNode] = {}
        self.loggers: dict[str, LoggerLevel] = {}
        self.master_ok: bool | None = None
        self.started = asyncio.Event()
        self._nodes_worker: Worker[None] | None = None
        self._loggers_worker: Worker[None] | None = None
        self._ping_failed = False
        self._loggers_read = False  # whether the selected node's loggers were read since it was selected
        self._picked_first = False

    # -- composition -----------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Three panels side by side, the master line and the key footer."""
        with Horizontal(id="panels"):
            with Vertical(id="nodes-panel", classes="panel"):
                yield NodeList(id="nodes")
                yield Notice(id="nodes-notice")
            with Vertical(id="loggers-panel", classes="panel"):
                yield LoggerTable(id="loggers")
                yield Notice(id="loggers-notice")
            with Vertical(id="levels-panel", classes="panel"):
                yield LevelList(id="levels")
                yield Notice(id="levels-notice")
        yield Notice(id="master")
        yield Footer()

    def on_mount(self) -> None:
        """Titles and first notices; start asking the master; stop cleanly on SIGTERM/SIGHUP."""
        self.query_one("#nodes-panel").border_title = "Nodes"
        self._set_titles()
        self.notice("nodes").say("asking the master…")
        self.notice("loggers").say("select a node")
        self.notice("levels").say("select a logger")
        self.notice("master").say(f"master {self.master_label()}")
        self.query_one(NodeList).focus()
        self.run_worker(self._start(), name="start", exit_on_error=False)
        quit_on_signals(self)

    async def _start(self) -> None:
        await self.client.start()
        self.set_interval(self.node_period, self._tick_nodes)
        self.set_interval(self.ping_period, self._tick_ping)
        await self._refresh_nodes()
        self.started.set()

    def notice(self, panel: str) -> Notice:
        """The notice line of ``nodes``, ``loggers``, ``levels`` or ``master``."""
        return self.query_one(f"#{panel}" if panel == "master" else f"#{panel}-notice", Notice)

    def master_label(self) -> str:
        """How the master is named on screen (its URI)."""
        return self.client.master_uri

    def _set_titles(self) -> None:
        self.query_one("#loggers-panel").border_title = f"Loggers · {self.node}" if self.node else "Loggers"
        self.query_one("#levels-panel").border_title = f"Level · {self.logger}" if self.logger else "Level"

    # -- nodes ---------------------------------------------------------------------------
    def _tick_nodes(self) -> None:
        if self._nodes_worker is None or self._nodes_worker.is_finished:
            self._nodes_worker = self.run_worker(self._refresh_nodes(), group="nodes", exit_on_error=False)

    async def _refresh_nodes(self) -> None:
        try:
            nodes = await self.client.nodes()
        except LOGGER_ERRORS as exc:
            self._master_lost(str(exc))
            return
        self._master_found(nodes)

    def _master_lost(self, reason: str) -> None:
        self.master_ok = False
        self.notice("master").say(f"{reason}; retrying every {self.node_period:g} s", "error")
        self.notice("nodes").say("no master", "error")
        self.nodes = {}
        self.query_one(NodeList).show_nodes([], None)
        if self.node:
            self._drop_node(f"{self.node}: {unreachable_text(self.client.master_uri)}", "error")

    def _master_found(self, nodes: list[LoggerNode]) -> None:
        if self.master_ok is False:
            self.notice("master").say(f"master {self.master_label()} is answering again", "ok")
        elif self.master_ok is None:
            self.notice("master").say(f"master {self.master_label()}")
        self.master_ok = True
        self.nodes = {node.name: node for node in nodes}
        node_list = self.query_one(NodeList)
        node_list.show_nodes(nodes, node_list.highlighted_name or self.node)
        if nodes and not self._picked_first:
            self._pick_first(node_list)
        count = len(nodes)
        serve = "1 node serves" if count == 1 else f"{count} nodes serve"
        self.notice("nodes").say(f"{serve} get_loggers" if count else "no node serves get_loggers")
        if self.node and self.node not in self.nodes:
            self._drop_node(f"node {self.node} is gone: the master no longer lists it", "error")

    def _pick_first(self, node_list: NodeList) -> None:
        """The first time nodes are listed, select the first one, so Enter works before any arrow key."""
        self._picked_first = True
        if self.node or node_list.highlighted is not None:
            return
        with node_list.prevent(OptionList.OptionHighlighted):
            node_list.highlighted = 0
        if node_list.highlighted_name:
            self.select_node(node_list.highlighted_name)

    def on_option_list_option_highlighted(self, event: OptionList.OptionHighlighted) -> None:
        """Highlighting a node selects it."""
        if event.option_list.id == "nodes" and event.option.id and event.option.id != self.node:
            self.select_node(event.option.id)

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        """Enter or a click: on a node, go to its loggers; on a level, set it."""
        if event.option_list.id == "nodes":
            if event.option.id and event.option.id != self.node:
                self.select_node(event.option.id)
            self.query_one(LoggerTable).focus()
        elif event.option_list.id == "levels" and event.option.id:
            self.action_set_level(event.option.id)

    def select_node(self, name: str) -> None:
        """Make ``name`` the selected node and ask it for its loggers."""
        self.node = name
        self.logger = ""
        self.loggers = {}
        self.query_one(LoggerTable).clear_loggers()
        self._show_levels()
        self.notice("loggers").say(f"asking {name}…")
        self._loggers_read = False
        self._load(name)

    def _drop_node(self, message: str, kind: str) -> None:
        """Forget the selected node, saying why under the loggers panel (a failed set stays said under levels)."""
        self.node = ""
        self.logger = ""
        self.loggers = {}
        self.query_one(LoggerTable).clear_loggers()
        self._show_levels(hint=self.notice("levels").kind != "error")
        self.notice("loggers").say(message, kind)

    # -- loggers --------------------------------------------------------------------------
    def _tick_ping(self) -> None:
        if self.node and (self._loggers_worker is None or self._loggers_worker.is_finished):
            # the function, not a coroutine object: a worker cancelled before it starts leaves nothing unawaited
            self._loggers_worker = self.run_worker(partial(self._ping, self.node), group="loggers", exclusive=True,
                                                   exit_on_error=False)

    async def _ping(self, node: str) -> None:
        try:
            await self.client.ping(node)
        except LOGGER_ERRORS as exc:
            if node == self.node:
                self._loggers_failed(exc)
                self._ping_failed = True
            return
        if node != self.node:
            return
        if not self._loggers_read:  # the first ask failed (a slow node or machine): ask for its loggers again
            await self._load_loggers(node)
        elif self._ping_failed:  # it answers again: its loggers are still the last read
            self._ping_failed = False
            self._say_logger_count()

    def _load(self, node: str) -> None:
        self._loggers_worker = self.run_worker(partial(self._load_loggers, node), group="loggers", exclusive=True,
                                               exit_on_error=False)

    async def _load_loggers(self, node: str) -> None:
        try:
            items = await self.client.loggers(node)
        except LOGGER_ERRORS as exc:
            if node == self.node:
                self._loggers_failed(exc)
            return
        if node == self.node:
            self._show_loggers(items)

    def _loggers_failed(self, exc: Exception) -> None:
        if isinstance(exc, (NodeGoneError, MasterUnreachableError)):
            self._drop_node(str(exc), "error")
        else:  # the node is there but did not answer this time: keep the last rows, say why
            self.notice("loggers").say(str(exc), "error")

    def _show_loggers(self, items: list[LoggerLevel]) -> None:
        self.loggers = {item.name: item for item in items}
        table = self.query_one(LoggerTable)
        keep = self.logger if self.logger in self.loggers else preferred_logger([item.name for item in items])
        table.show_loggers(items, keep)
        before, self.logger = self.logger, table.highlighted_name or ""
        self._show_levels(hint=self.logger != before)
        self._ping_failed = False
        self._loggers_read = True
        self._say_logger_count()

    def _say_logger_count(self) -> None:
        count = len(self.loggers)
        self.notice("loggers").say(("1 logger" if count == 1 else f"{count} loggers") if count else "no loggers")

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        """Moving the cursor in the logger table selects that logger."""
        name = event.row_key.value
        if name in self.loggers and name != self.logger:
            self.logger = name
            self._show_levels()

    def on_data_table_row_selected(self, event: DataTable.RowSelected) -> None:
        """Enter or a click on the selected logger: go to the levels."""
        self.query_one(LevelList).focus()

    # -- levels ----------------------------------------------------------------------------
    def _show_levels(self, *, hint: bool = True) -> None:
        """Mark the selected logger's level; with ``hint``, replace the level notice with the key help."""
        self._set_titles()
        current = self.loggers.get(self.logger)
        self.query_one(LevelList).show_current(current.level if current else None, self.logger or None)
        if hint:
            self.notice("levels").say(SET_HINT if current else "select a logger")

    def action_set_level(self, level: str) -> None:
        """Set the selected logger of the selected node to ``level``."""
        if not self.node or not self.logger:
            self.notice("levels").say("select a node and a logger first", "error")
            return
        node = self.nodes.get(self.node)
        self.run_worker(self._set_level(self.node, self.logger, level, ask_first=node is not None and not node.can_set),
                        group="set", exit_on_error=False)

    async def _set_level(self, node: str, logger: str, level: str, *, ask_first: bool = False) -> None:
        if ask_first:  # the last poll may have come between the node's two services: ask again before refusing
            try:
                served = {found.name: found for found in await self.client.nodes()}
            except LOGGER_ERRORS as exc:
                self.notice("levels").say(str(exc), "error")
                return
            if node in served and not served[node].can_set:
                self.notice("levels").say(f"{node} does not serve set_logger_level", "error")
                return
        self.notice("levels").say(f"setting {logger} to {level}…")
        try:
            sent = await self.client.set_level(node, logger, level)
        except LOGGER_ERRORS as exc:
            self.notice("levels").say(str(exc), "error")
            if node == self.node:
                self._loggers_failed(exc)
            return
        try:
            items = await self.client.loggers(node)
        except LOGGER_ERRORS as exc:
            self.notice("levels").say(f"{logger} was sent {sent}; reading it back failed: {exc}", "error")
            if node == self.node:
                self._loggers_failed(exc)
            return
        if node != self.node:
            return
        self._show_loggers(items)
        now = self.loggers.get(logger)
        if now is None or now.level != sent:
            shown = now.level if now else "nothing"
            self.notice("levels").say(f"{node} was sent {sent} for {logger} but reports {shown}", "error")
        elif logger == self.logger:
            self.notice("levels").say(f"{logger} set to {sent}", "ok")

    # -- app ---------------------------------------------------------------------------------
    def action_refresh(self) -> None:
        """Ask the master and the selected node again now."""
        self._tick_nodes()
        if self.node:
            self._load(self.node)

    async def release(self) -> None:
        """Shut the calling node down."""
        try:
            await asyncio.wait_for(self.client.close(), 5.0)
        except Exception:  # the process is ending; nothing left to tell the user
            pass


def run_app(*, timeout: float = DEFAULT_TIMEOUT) -> int:
    """Run :class:`LoggersApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui loggers", "use `rostui loggers NODE` and `rostui loggers NODE LOGGER LEVEL` without one"):
        return 1
    app = LoggersApp(timeout=timeout)
    app.run()
    return app.return_code or 0
