"""ReconfigureApp: rqt_reconfigure in the terminal.

Left, the reconfigure servers on the master (asked again every second); right, the selected server's groups
and parameters with their live values (they follow the server's ``parameter_updates``), each number with a
range drawn as a bar. ←/→ step a number (shift: ten steps), space flips a bool or moves an enum to its next
constant, Enter edits any value (an enum from its constants), ``d`` sets the default. Each change goes to the
server's ``set_parameters`` at once; the line under the table says what the server kept and how long it took,
or, in red, why it failed. Nothing is sent unless a key asks for it; the status line names the server that
changes go to.
"""

from __future__ import annotations

import asyncio
from dataclasses import replace
from pathlib import Path
from typing import Any, ClassVar

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal, Vertical
from textual.widgets import DataTable, OptionList, Static

from rostui.apps.reconfigure.panels import EditScreen, ParamTable, detail_text
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.name_list import NameList
from rostui.apps.widgets.notice import Notice
from rostui.core.masteruri import master_uri_from_env
from rostui.models.master_link import MasterState, SourceState
from rostui.models.reconfigure import SERVER_PERIOD, Change, GroupRow, ParamRow, ReconfigureSource

__all__ = ["ReconfigureApp", "run_app"]

KEYS = key_line("←→ step  space flip  Enter edit  d default  Tab servers/parameters")



class ReconfigureApp(ReleasesOnExit, KeysApp):
    """Lists reconfigure servers, shows the selected one's parameters live, and changes them with keys.

    *node* is the server selected first (by its name, as ``rostui reconfigure NODE`` gives it).
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui reconfigure"

    # Priority keys: the table's own arrows and Enter would take them first. Over the editor they stay out of
    # its field's way (KeysApp.check_action).
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("right", "step(1)", "a number one step up", priority=True),
        Binding("left", "step(-1)", "a number one step down", priority=True),
        Binding("shift+right", "step(1, True)", "a number ten steps up", priority=True),
        Binding("shift+left", "step(-1, True)", "a number ten steps down", priority=True),
        Binding("space", "flip", "flip a bool, or an enum to its next constant", priority=True),
        Binding("enter", "edit", "edit the value (type it, or choose a constant); on a server: its parameters",
                priority=True),
        Binding("d", "default", "the parameter back to its default"),
    ]
    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = (
        ("↑/↓", "move between servers, or between parameters"),
        ("Tab", "between the servers and the parameters"),
    )

    def __init__(self, *, master_uri: str | None = None, node: str | None = None,
                 server_period: float = SERVER_PERIOD) -> None:
        super().__init__()
        self.master_uri = master_uri or master_uri_from_env()
        self.wanted = node
        self.source = ReconfigureSource(self.master_uri, on_change=self._source_changed, on_state=self._state_changed,
                                        server_period=server_period)
        self.last_change: Change | None = None
        self.started = asyncio.Event()
        self._refresh_pending = False

    # -- composition -----------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Servers beside parameters, the detail and notice lines, the master line and the key footer."""
        with Horizontal(id="panels"):
            with Vertical(id="servers-panel", classes="panel"):
                yield NameList(id="servers")
                yield Notice(id="servers-notice")
            with Vertical(id="params-panel", classes="panel"):
                yield ParamTable(id="params")
                yield Notice(id="detail")
                yield Notice(id="params-notice")
        yield Notice(id="master")
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Titles and first notices; start the source; stop cleanly on SIGTERM/SIGHUP."""
        self.query_one("#servers-panel").border_title = "Servers"
        self._set_title()
        self.notice("servers").say("asking the master…")
        self.notice("params").say("select a server")
        self.notice("master").say(f"waiting for master {self.master_label()}")
        self.query_one(NameList).focus()
        self.run_worker(self._run_source(), name="source", exit_on_error=False)
        quit_on_signals(self)

    async def _run_source(self) -> None:
        self.started.set()
        await self.source.run()

    def notice(self, name: str) -> Notice:
        """The notice line ``servers``, ``params``, ``detail`` or ``master``."""
        return self.query_one(f"#{name}" if name in ("detail", "master") else f"#{name}-notice", Notice)

    def _set_title(self) -> None:
        selected = self.source.selected
        self.query_one("#params-panel").border_title = f"Parameters · {selected}" if selected else "Parameters"

    # -- what the source says ------------------------------------------------------------
    def _state_changed(self, state: SourceState) -> None:
        self._say_master(state)
        if state.status is not MasterState.CONNECTED:
            self.notice("servers").say("no master" if state.status is MasterState.LOST else "waiting for the master",
                                       "error" if state.status is MasterState.LOST else "info")

    def master_label(self) -> str:
        """How the master is named on screen (its URI)."""
        return self.master_uri

    def elapsed_text(self, seconds: float) -> str:
        """How long a change took, as the notice says it."""
        return f"{seconds * 1000:.0f} ms"

    def _say_master(self, state: SourceState | None = None) -> None:
        state = replace(state or self.source.state, master_uri=self.master_label())
        text = state.text()
        if state.status is MasterState.CONNECTED and self.source.selected:
            text += f" · changes go to {self.source.selected}"
        kind = "error" if state.status is MasterState.LOST else "info"
        self.notice("master").say(text, kind)

    def _source_changed(self) -> None:
        """Coalesce the source's news into one refresh of the screen per message-queue turn."""
        if not self._refresh_pending:
            self._refresh_pending = True
            self.call_later(self._refresh)

    def _refresh(self) -> None:
        self._refresh_pending = False
        if not self.is_running:
            return
        self._set_title()
        self._say_master()
        servers = self.source.servers
        server_list = self.query_one(NameList)
        server_list.show_names(servers, self.source.selected)
        if self.source.servers_read:
            count = len(servers)
            self.notice("servers").say(("1 server" if count == 1 else f"{count} servers") if count
                                       else "no reconfigure server")
        if self.source.selected is None:
            if self.wanted and self.wanted in servers:
                self.select_server(self.wanted)
            elif self.wanted and self.source.servers_read:
                self.notice("params").say(f"{self.wanted} is not on the master (yet)")
            elif not self.wanted and servers:
                self.select_server(servers[0])
        if self.source.selected and self.source.servers_read and self.source.selected not in servers:
            self.notice("params").say(f"{self.source.selected} is gone: the master no longer lists it", "error")
        rows = self.source.rows()
        table = self.query_one(ParamTable)
        table.show_rows(rows)
        if self.source.selected and self.source.server is not None and self.last_change is None \
                and self.notice("params").kind == "info":
            self.notice("params").say(_counted(rows) if rows else f"waiting for {self.source.selected}'s description…")
        self._show_detail()

    def _show_detail(self) -> None:
        self.notice("detail").say(detail_text(self.query_one(ParamTable).highlighted_row))

    # -- servers ---------------------------------------------------------------------------
    def on_option_list_option_highlighted(self, event: OptionList.OptionHighlighted) -> None:
        """Highlighting a server selects it."""
        if event.option_list.id == "servers" and event.option.id and event.option.id != self.source.selected:
            self.select_server(event.option.id)

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        """Enter or a click on a server: go to its parameters."""
        if event.option_list.id == "servers":
            if event.option.id and event.option.id != self.source.selected:
                self.select_server(event.option.id)
            self.query_one(ParamTable).focus()

    def select_server(self, name: str) -> None:
        """Follow server *name*."""
        self.wanted = None
        self.last_change = None
        self.query_one(NameList).highlight_name(name)
        self.query_one(ParamTable).clear_rows()
        self.notice("params").say(f"asking {name}…")
        self.run_worker(self.source.select(name), group="select", exclusive=True, exit_on_error=False)

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        """The detail line follows the cursor."""
        self._show_detail()

    def on_data_table_row_selected(self, event: DataTable.RowSelected) -> None:
        """Enter or a click on a parameter: edit it."""
        self.action_edit()

    # -- changes -----------------------------------------------------------------------------
    def _param_under_cursor(self) -> ParamRow | None:
        table = self.query_one(ParamTable)
        row = table.highlighted_row
        if not table.has_focus or not isinstance(row, ParamRow):
            return None
        if row.value is None:
            self.notice("params").say(f"{row.name} has no value yet", "error")
            return None
        return row

    def action_step(self, direction: int, coarse: bool = False) -> None:
        """←/→: the number under the cursor one step down or up; on a bool or an enum, as space."""
        row = self._param_under_cursor()
        if row is None:
            return
        value = row.stepped(direction, coarse)
        if value is None:
            self.notice("params").say(f"{row.name} is a string: Enter edits it", "error")
            return
        self.send(row.name, value)

    def action_flip(self) -> None:
        """Space: a bool flipped, an enum to its next constant."""
        row = self._param_under_cursor()
        if row is not None and (row.type == "bool" or row.choices):
            self.send(row.name, row.stepped(1))

    def action_default(self) -> None:
        """d: the parameter under the cursor back to its default."""
        row = self._param_under_cursor()
        if row is not None and row.default is not None:
            self.send(row.name, row.default)

    def action_edit(self) -> None:
        """Enter: edit the value under the cursor (on the server list: go to the parameters)."""
        servers = self.query_one(NameList)
        if servers.has_focus:
            if servers.highlighted_name and servers.highlighted_name != self.source.selected:
                self.select_server(servers.highlighted_name)
            self.query_one(ParamTable).focus()
            return
        row = self._param_under_cursor()
        if row is None:
            return

        def sent(value: Any) -> None:
            if value is not None:
                self.send(row.name, value)

        self.push_screen(EditScreen(row), sent)

    def send(self, name: str, value: Any) -> None:
        """Send *name* = *value* to the selected server; the answer is said under the table."""
        self.notice("params").say(f"setting {name} to {value!r}…")
        self.run_worker(self._send(name, value), group="set", exit_on_error=False)

    async def _send(self, name: str, value: Any) -> None:
        change = await self.source.set_value(name, value)
        self.last_change = change
        if change.error:
            self.notice("params").say(f"{name}: {change.error}", "error")
            return
        took = self.elapsed_text(change.seconds)
        said = f"{name} = {change.kept!r} in {took}"
        if change.kept != change.asked:
            said = f"{name}: asked {change.asked!r}, {change.server} kept {change.kept!r} ({took})"
        self.notice("params").say(said, "ok")

    # -- app ---------------------------------------------------------------------------------
    async def release(self) -> None:
        """Shut the source's node down."""
        try:
            await asyncio.wait_for(self.source.stop(), 5.0)
        except Exception:  # the process is ending; nothing left to tell the user
            pass


def _counted(rows: list[GroupRow | ParamRow]) -> str:
    """How many parameters and groups the rows hold."""
    params = sum(isinstance(row, ParamRow) for row in rows)
    groups = sum(isinstance(row, GroupRow) for row in rows)
    said = "1 parameter" if params == 1 else f"{params} parameters"
    return said + (f" in {groups + 1} groups" if groups else "")


def run_app(node: str | None = None) -> int:
    """Run :class:`ReconfigureApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui reconfigure", "use `rostui dynparam` without one"):
        return 1
    app = ReconfigureApp(node=node)
    app.run()
    return app.return_code or 0
