"""DiagnosticsApp: rqt_robot_monitor and rqt_runtime_monitor in the terminal.

Above, the aggregator's /diagnostics_agg as its tree, or /diagnostics as a flat list while no aggregator speaks
(``t`` switches between them); each row coloured by its level, a status not heard for 5 s shown as STALE. Below,
the status under the cursor: its message, hardware id, age, key/values and the history of what it said. ``l``
raises the least level shown (all, warn, error, stale), ``/`` filters by name. The app only listens.
"""

from __future__ import annotations

import asyncio
import time
from dataclasses import replace
from pathlib import Path
from typing import Callable, ClassVar

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.widgets import Input, Static

from rostui.apps.diagnostics.table import StatusTree
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.apps.widgets.notice import Notice
from rostui.core.masteruri import master_uri_from_env
from rostui.models.diagnostics.detail import detail_lines, summary_text
from rostui.models.diagnostics.levels import ERROR, level_name, severity
from rostui.models.diagnostics.source import DiagnosticsSource
from rostui.models.diagnostics.store import AGGREGATED, FLAT, DiagnosticsStore
from rostui.models.diagnostics.tree import DiagRow, Filter, counts, flat_rows, tree_rows
from rostui.models.master_link import MasterState, SourceState

__all__ = ["DiagnosticsApp", "run_app", "REFRESH_EVERY"]

KEYS = key_line("l level  / filter  t aggregated/flat  ↑↓ statuses")

#: Seconds between redraws while news comes (ages and staleness move on without news too, once a second).
REFRESH_EVERY = 0.25


class DiagnosticsApp(ReleasesOnExit, KeysApp):
    """The robot's diagnostics, live. *level* and *text* are the first filter (``rostui diagnostics -l warn``).

    With ``store`` given the app draws that store and listens to nothing (tests, snapshots); ``clock`` is "now"
    for ages and staleness.
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui diagnostics"

    TYPE_AHEAD_ACTIONS = frozenset({"filter"})
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("l", "level", "show only statuses at least one level worse (all, warn, error, stale)"),
        Binding("slash", "filter", "filter statuses by name (a regular expression)", priority=True),
        Binding("t", "topic", "switch between the aggregator's tree and the flat /diagnostics"),
        Binding("escape", "clear_filter", "close the filter and show every name again", show=False),
    ]
    KEY_NOTES: ClassVar[tuple[tuple[str, str], ...]] = (
        ("↑/↓ PgUp/PgDn", "move between statuses"),
    )

    def __init__(self, *, master_uri: str | None = None, level: int = 0, text: str = "",
                 store: DiagnosticsStore | None = None, clock: Callable[[], float] = time.time) -> None:
        super().__init__()
        self.master_uri = master_uri or master_uri_from_env()
        self.clock = clock
        self.live = store is None
        self.store = store if store is not None else DiagnosticsStore()
        self.source: DiagnosticsSource | None = None
        if self.live:
            self.source = DiagnosticsSource(self.master_uri, store=self.store, on_change=self._news,
                                            on_state=self._state_changed, clock=clock)
        self.only = Filter(level, text)
        self.chosen_topic: str | None = None
        """The topic the user chose with ``t``; None follows the aggregator when there is one."""
        self.rows: list[DiagRow] = []
        self._cursors: dict[str, str] = {}
        self._dirty = True
        self._drawn_at = 0.0
        self.started = asyncio.Event()

    def compose(self) -> ComposeResult:
        """Summary, the status table, the detail of the status under the cursor, the filter, master and keys."""
        yield Notice(id="summary")
        yield Notice(id="filtered")
        yield StatusTree(id="statuses")
        yield Static(id="detail", markup=False)
        yield LineInput(placeholder="filter names (a regular expression); Enter keeps it, Esc clears it", id="filter")
        yield Notice(id="master")
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Start listening (live), draw now and keep drawing; stop cleanly on SIGTERM/SIGHUP."""
        self.query_one("#filter", Input).display = False
        self.query_one(StatusTree).focus()
        self.say_master()
        if self.source is not None:
            self.run_worker(self._run_source(), name="source", exit_on_error=False)
        self.redraw()
        self.set_interval(REFRESH_EVERY, self._tick)
        quit_on_signals(self)

    async def _run_source(self) -> None:
        self.started.set()
        assert self.source is not None
        await self.source.run()

    # -- what is shown -------------------------------------------------------------------------------
    @property
    def topic(self) -> str:
        """The topic shown: the user's choice, else the aggregator's once it spoke, else the flat topic."""
        if self.chosen_topic is not None:
            return self.chosen_topic
        return AGGREGATED if self.store.has_aggregator else FLAT

    def _news(self) -> None:
        self._dirty = True

    def _tick(self) -> None:
        if self._dirty or self.clock() - self._drawn_at >= 1.0:
            self.redraw()

    def redraw(self) -> None:
        """Rows, summary and detail from the store as it is now."""
        self._dirty = False
        now = self._drawn_at = self.clock()
        topic = self.topic
        table = self.store.table(topic)
        make = flat_rows if topic == FLAT else tree_rows
        self.rows = make(table, now, self.store.stale_after, self.only)
        self.query_one(StatusTree).show_rows(self.rows)
        every = make(table, now, self.store.stale_after) if self.only.active else self.rows
        self.query_one("#summary", Notice).say(
            summary_text(topic, topic != FLAT, counts(every)),
            "error" if any(severity(row.level) >= ERROR for row in every if row.record) else "info")
        filtered = self.query_one("#filtered", Notice)
        filtered.say(self._hidden_text(len(every)))
        filtered.display = self.only.active
        self.show_detail()

    def _hidden_text(self, total: int) -> str:
        if not self.only.active:
            return ""
        parts = []
        if self.only.level:
            parts.append(f"{level_name(self.only.level)} and worse")
        if self.only.text:
            parts.append(f"names matching {self.only.text!r}")
        return f"showing {len(self.rows)} of {total} rows: {', '.join(parts)}"

    def show_detail(self) -> None:
        """The detail panel for the row under the cursor."""
        lines = detail_lines(self.query_one(StatusTree).current, self.rows, self.clock())
        self.query_one("#detail", Static).update(Text("\n".join(lines)))

    def on_line_table_moved(self, event: StatusTree.Moved) -> None:
        """The detail follows the cursor."""
        self.show_detail()

    # -- the master ----------------------------------------------------------------------------------
    def _state_changed(self, state: SourceState) -> None:
        self.say_master(state)

    def say_master(self, state: SourceState | None = None) -> None:
        """The master line: where the app listens, or that it waits for the master."""
        if self.source is None:
            self.query_one("#master", Notice).say("showing a stored picture (not listening)")
            return
        state = replace(state or self.source.state, master_uri=self.master_uri)
        text = state.text()
        if state.status is MasterState.CONNECTED:
            text += " · listening to /diagnostics_agg and /diagnostics (publishing nothing)"
        self.query_one("#master", Notice).say(text, "error" if state.status is MasterState.LOST else "info")

    # -- keys ----------------------------------------------------------------------------------------
    def action_level(self) -> None:
        """l: the least level shown one step worse (after stale: all again)."""
        self.only = replace(self.only, level=(self.only.level + 1) % 4)
        self.redraw()

    def action_topic(self) -> None:
        """t: the other topic (the aggregator's tree or the flat /diagnostics); the cursor goes back to the status
        it was on there."""
        table = self.query_one(StatusTree)
        if table.cursor_name is not None:
            self._cursors[self.topic] = table.cursor_name
        self.chosen_topic = FLAT if self.topic == AGGREGATED else AGGREGATED
        table.cursor_name = self._cursors.get(self.chosen_topic)
        self.redraw()

    def action_filter(self) -> None:
        """/: open the name filter."""
        field = self.query_one("#filter", Input)
        field.display = True
        field.value = self.only.text
        focus_now(field)

    def action_clear_filter(self) -> None:
        """Esc: close the filter and show every name."""
        field = self.query_one("#filter", Input)
        field.display = False
        self.only = replace(self.only, text="")
        self.query_one(StatusTree).focus()
        self.redraw()

    def on_input_changed(self, event: Input.Changed) -> None:
        """The filter follows what is typed."""
        self.only = replace(self.only, text=event.value)
        self.redraw()

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """Enter: keep the filter, back to the table."""
        event.input.display = False
        self.query_one(StatusTree).focus()

    # -- app -----------------------------------------------------------------------------------------
    async def release(self) -> None:
        """Shut the source's node down."""
        if self.source is not None:
            try:
                await asyncio.wait_for(self.source.stop(), 5.0)
            except Exception:  # the process is ending; nothing left to tell the user
                pass


def run_app(level: int = 0, text: str = "") -> int:
    """Run :class:`DiagnosticsApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui diagnostics", "use `rostui diagnostics --once` without one"):
        return 1
    app = DiagnosticsApp(level=level, text=text)
    app.run()
    return app.return_code or 0
