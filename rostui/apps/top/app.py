"""TopApp: rqt_top in the terminal: every node on the master with its pid, CPU, memory, threads and connections.

The master is asked for its nodes every ``interval`` seconds; a node on this host is measured with psutil, a node
elsewhere is listed as remote. The detail line spells out the node under the cursor (URI, command line). ``s``
changes the order (CPU, memory, name); ``k`` stops the node under the cursor after a y/n question: SIGINT, then
SIGTERM, then SIGKILL, 5 s apart, and the line under the table says what it took. Nothing else is sent.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import ClassVar

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.widgets import Static

from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.confirm import ConfirmScreen
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_table import Line, LineTable
from rostui.apps.widgets.notice import Notice
from rostui.core.master_errors import MasterUnreachableError
from rostui.core.masteruri import master_uri_from_env
from rostui.models.top import SORTS, NodeRow, StopRefused, TopSource, sort_rows, table_lines

__all__ = ["TopApp", "NodeTable", "run_app"]

KEYS = key_line("s sort  k stop node  r refresh  ↑↓ nodes")


class NodeTable(LineTable):
    """One row per node: its name, pid, CPU, memory, threads, connections and where it runs."""

    COMPONENT_CLASSES: ClassVar[set[str]] = {"node-table--remote", "node-table--problem"}

    DEFAULT_CSS = """
    NodeTable { overflow-x: auto; }
    NodeTable > .node-table--remote { color: $text-muted; }
    NodeTable > .node-table--problem { color: $text-warning; }
    """

    def show_rows(self, rows: list[NodeRow]) -> None:
        """Draw ``rows`` in this order, the columns as wide as their widest cell."""
        header, *lines = table_lines(rows)
        self.show(header, [Line(row.name, line, "node-table--problem" if row.problem else
                                "" if row.here else "node-table--remote") for row, line in zip(rows, lines)])


class TopApp(ReleasesOnExit, KeysApp):
    """Every node on the master at ``master_uri``, measured every ``interval`` seconds, in ``sort`` order."""

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui top"

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("s", "sort", "order by CPU, memory or name"),
        Binding("k", "stop", "stop the node under the cursor (asks first): SIGINT, SIGTERM, SIGKILL"),
        Binding("r", "refresh", "measure again now"),
    ]
    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = (("↑/↓ PgUp/PgDn", "move between nodes"),)

    def __init__(self, *, master_uri: str | None = None, sort: str = "cpu", interval: float = 1.0) -> None:
        super().__init__()
        self.master_uri = master_uri or master_uri_from_env()
        self.sort = sort
        self.interval = interval
        self.source = TopSource(self.master_uri)
        self.rows: list[NodeRow] = []
        self.polls = 0
        self.master_lost = False
        self.started = asyncio.Event()
        self._wake = asyncio.Event()

    def compose(self) -> ComposeResult:
        """Summary, the node table, the detail of the node under the cursor, what a stop did, master and keys."""
        yield Notice(id="summary")
        yield NodeTable(id="nodes")
        yield Static(id="detail", markup=False)
        yield Notice(id="stopped")
        yield Notice(id="master")
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Start measuring; stop cleanly on SIGTERM/SIGHUP."""
        self.query_one(NodeTable).focus()
        self.query_one("#summary", Notice).say(f"asking the master {self.master_uri}…")
        self.query_one("#stopped", Notice).display = False
        self.say_master()
        self.run_worker(self._measure(), name="measure", exit_on_error=False)
        quit_on_signals(self)

    def master_label(self) -> str:
        """How the master is named on screen (its URI)."""
        return self.master_uri

    def say_master(self) -> None:
        """The master line: measured, or gone."""
        if self.master_lost:
            self.query_one("#master", Notice).say(f"master {self.master_label()} does not answer: asking again",
                                                  "error")
        else:
            self.query_one("#master", Notice).say(f"master {self.master_label()} · measuring every "
                                                  f"{self.interval:g} s (only k signals anything)")

    async def _measure(self) -> None:
        await self.source.start()
        self.started.set()
        while True:
            try:
                rows = await self.source.poll()
                self.master_lost = False
            except MasterUnreachableError:
                self.master_lost, rows = True, []
            self.polls += 1
            self.rows = rows
            self.redraw()
            self._wake.clear()
            try:
                await asyncio.wait_for(self._wake.wait(), self.interval)
            except asyncio.TimeoutError:
                pass

    def redraw(self) -> None:
        """Table, summary, detail and master line from the last measure."""
        rows = sort_rows(self.rows, self.sort)
        self.query_one(NodeTable).show_rows(rows)
        here = sum(row.here for row in rows)
        cpu = sum(row.usage.cpu_percent for row in rows if row.usage)
        summary = (f"{len(rows)} node{'' if len(rows) == 1 else 's'} · {here} here, {len(rows) - here} elsewhere · "
                   f"{cpu:.0f}% CPU here · by {self.sort}") if rows else "no node on the master"
        self.query_one("#summary", Notice).say(summary)
        self.say_master()
        self.show_detail()

    def current(self) -> NodeRow | None:
        """The node under the cursor."""
        key = self.query_one(NodeTable).cursor_key
        return next((row for row in self.rows if row.name == key), None)

    def show_detail(self) -> None:
        """The node under the cursor: its URI, pid and command line."""
        row = self.current()
        if row is None:
            text = ""
        else:
            command = row.usage.command if row.usage and row.usage.command else ""
            text = f"{row.name} at {row.uri or '?'}" + (f" · {row.problem}" if row.problem else "") + \
                (f"\n{command}" if command else "")
        self.query_one("#detail", Static).update(Text(text))

    def on_line_table_moved(self, event: LineTable.Moved) -> None:
        """The detail follows the cursor."""
        self.show_detail()

    # -- keys ----------------------------------------------------------------------------------------
    def action_sort(self) -> None:
        """s: the next order (CPU, memory, name)."""
        self.sort = SORTS[(SORTS.index(self.sort) + 1) % len(SORTS)]
        self.redraw()

    def action_refresh(self) -> None:
        """r: measure again now."""
        self._wake.set()

    def action_stop(self) -> None:
        """k: ask, then stop the node under the cursor."""
        row = self.current()
        if row is None:
            return
        if not row.here or row.pid is None:
            self.say_stopped(f"{row.name} does not run on this host: stop it where it runs", "error")
            return

        def answered(yes: bool | None) -> None:
            if yes:
                self.run_worker(self._stop(row), group="stop", exit_on_error=False)
            else:
                self.say_stopped(f"{row.name} left running")

        self.push_screen(ConfirmScreen(f"Stop {row.name} (pid {row.pid})?\nSIGINT now, SIGTERM after 5 s, "
                                       f"SIGKILL after 10 s."), answered)

    async def _stop(self, row: NodeRow) -> None:
        try:
            said = await self.source.stop(row, said=self.say_stopped)
        except StopRefused as exc:
            self.say_stopped(str(exc), "error")
            return
        self.say_stopped(said, "ok")
        self._wake.set()

    def say_stopped(self, text: str, kind: str = "info") -> None:
        """The line under the table about a stop."""
        notice = self.query_one("#stopped", Notice)
        notice.display = True
        notice.say(text, kind)

    async def release(self) -> None:
        """Shut the measuring node down."""
        try:
            await asyncio.wait_for(self.source.close(), 5.0)
        except Exception:  # the process is ending; nothing left to tell the user
            pass


def run_app(sort: str = "cpu", interval: float = 1.0) -> int:
    """Run :class:`TopApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui top", "use `rostui top --once` without one"):
        return 1
    app = TopApp(sort=sort, interval=interval)
    app.run()
    return app.return_code or 0
