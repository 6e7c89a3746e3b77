"""ConsoleApp: rqt_console in the terminal.

Live, the app runs a node on Textual's loop that subscribes to /rosout_agg
(:class:`~rostui.models.console.source.LiveSource`); offline, it shows the
messages of a rosout.log read before it started.  Either way messages reach
the :class:`~rostui.models.console.model.ConsoleModel` through :meth:`ConsoleApp.ingest`,
in batches on a timer, and the table repaints once per batch, never per
message.  Filters apply to the model; the table draws only visible rows.
"""

from __future__ import annotations

import gc
import time
from dataclasses import replace
from pathlib import Path
from typing import Any, ClassVar, Iterable

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.reactive import reactive
from textual.timer import Timer
from textual.widgets import Input, Static

from rostui.apps.console.bars import KEY_HELP, LEVEL_KEYS, Bar, StatusInfo, detail_markup, filter_markup, status_markup
from rostui.apps.console.table import LogTable
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry, RosoutLog, entries_text
from rostui.core.network import master_uri_from_env
from rostui.models.console.filters import FilterError, FilterSpec, HighlightRule, compile_text
from rostui.models.console.model import ConsoleModel, ConsoleOptions
from rostui.models.console.source import LiveSource
from rostui.models.master_link import MasterState, SourceState

__all__ = ["ConsoleApp", "ConsoleOptions", "run_app"]

#: Batches per second: how often arrived messages are taken into the model and the screen updated.
INGEST_RATE = 20.0

#: Seconds a notice (saved, cleared...) stays in the status line.
NOTICE_SECONDS = 4.0

#: Seconds the search waits after a keystroke before filtering (typing fast filters once).
SEARCH_DELAY = 0.06

#: The app's state the filter bar and status line show besides the model's counters: a change to any
#: repaints them (one watch, set up in :meth:`ConsoleApp.on_mount`).
BAR_STATE = ("spec", "regex_error", "highlights", "notice", "source_state")


class Prompt(LineInput):
    """The one-line input for search text, highlight rules and the save path; Escape cancels it."""

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "cancel", show=False)]

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.purpose = ""

    def action_cancel(self) -> None:
        """Close without applying (a search goes back to what it was)."""
        app = self.app
        assert isinstance(app, ConsoleApp)
        app.close_prompt(cancelled=True)


class ConsoleApp(ReleasesOnExit, KeysApp):
    """Browse ROS log messages: live from /rosout_agg, or a rosout.log (``log``).

    ``master_uri`` defaults to ROS_MASTER_URI.  ``log_name`` is how the file
    is named on screen (the path as the user gave it).  ``freeze_gc`` (for
    the process that runs only this app): every repaint leaves Textual strips
    in reference cycles, so full garbage collections run about once a second;
    freezing what exists once the app is up (modules, the widget tree, a
    loaded file) keeps each of them from walking ~50 000 objects that will
    never be garbage (100 ms pauses otherwise).
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui console"
    KEY_NOTES = (("click a level", "show or hide that level"),)

    TYPE_AHEAD_ACTIONS = frozenset({"open_prompt"})
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        *(Binding(key, f"toggle_level({int(level)})", f"{level.name} on/off", show=False) for level, key in LEVEL_KEYS.items()),
        Binding("slash", "open_prompt('search')", "search", priority=True),
        Binding("r", "toggle_regex", "regex"),
        Binding("escape", "clear_search", "clear search", show=False),
        Binding("h", "open_prompt('highlight')", "highlight", priority=True),
        Binding("H", "clear_highlights", "clear highlights", show=False),
        Binding("n", "include_node", "only this node"),
        Binding("x", "exclude_node", "hide this node"),
        Binding("N", "clear_nodes", "all nodes", show=False),
        Binding("p,space", "toggle_pause", "pause"),
        Binding("c", "clear", "clear"),
        Binding("enter", "toggle_detail", "detail"),
        Binding("s", "open_prompt('save')", "save", priority=True),
        Binding("F,f", "follow", "follow"),
    ]

    spec: reactive[FilterSpec] = reactive(FilterSpec, init=False)
    """The filters in force."""
    regex_error: reactive[str] = reactive("", init=False)
    """Why the last regular expression typed was refused ('' when it was not)."""
    highlights: reactive[tuple[HighlightRule, ...]] = reactive(tuple, init=False)
    """The highlight rules, in the order they were added."""
    notice: reactive[tuple[float, str]] = reactive((0.0, ""), init=False)
    """When a notice was given (monotonic seconds) and its text, shown for :data:`NOTICE_SECONDS`."""
    source_state: reactive[SourceState | None] = reactive(None, init=False)
    """The live source's link to the master (None when reading a file)."""

    def __init__(self, options: ConsoleOptions | None = None, log: RosoutLog | None = None, *,
                 master_uri: str | None = None, log_name: str | None = None, freeze_gc: bool = False) -> None:
        super().__init__()
        self.freeze_gc = freeze_gc
        self.options = options or ConsoleOptions()
        self.model = ConsoleModel(self.options.max_messages, min_level=self.options.min_level)
        self.spec = self.options.filter_spec()
        self.log_file = log
        self.log_name = log_name or (str(log.path) if log is not None else "")
        self.master_uri = master_uri or master_uri_from_env()
        self.source: LiveSource | None = None if log is not None else LiveSource(self.master_uri, self._on_state)
        self.source_state = self.source.state if self.source else None
        self._before_prompt: FilterSpec | None = None
        self._search_timer: Timer | None = None
        self._shown_version = -1
        self.filter_bar = Bar(id="filters")
        self.status_bar = Bar(id="status")
        self.table = LogTable(self.model, id="table")
        self.detail = VerticalScroll(id="detail")
        self.detail_text = Static(id="detail-text")
        self.prompt = Prompt(id="prompt")

    # -- composition -----------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Filter bar, table, detail pane, prompt, status line and key help."""
        yield self.filter_bar
        yield self.table
        with self.detail:
            yield self.detail_text
        yield self.prompt
        yield self.status_bar
        yield Bar(KEY_HELP, id="keys")

    def on_mount(self) -> None:
        """Apply the first filters, load the file or start listening, and start the ingest timer."""
        try:
            self.model.set_filter(self.spec)
        except FilterError as exc:
            self.regex_error = str(exc)
            self.spec = _with(self.spec, search="", regex=True)
            self.model.set_filter(self.spec)
        self.prompt.display = False
        self.detail.display = False
        if self.log_file is not None:
            self.model.dropped += self.log_file.dropped
            self.model.below_level += self.log_file.below_level
            self.ingest(self.log_file.entries)
            if self.log_file.malformed_count:
                self.notify(self.log_file.malformed_summary(), title="malformed lines", severity="warning", timeout=8)
        elif self.source is not None:
            self.run_worker(self.source.run(), name="rosout_agg", exclusive=True, exit_on_error=False)
        self.set_interval(1.0 / INGEST_RATE, self.take_batch)
        self.table.focus()
        for name in BAR_STATE:
            self.watch(self, name, self.refresh_bars, init=False)
        self.watch(self.table, "follow", self.refresh_bars, init=False)  # FOLLOW or SCROLL
        self.refresh_bars()
        if self.freeze_gc:
            self.call_after_refresh(gc.freeze)
        quit_on_signals(self)

    # -- messages in ---------------------------------------------------------------------------------
    def ingest(self, entries: Iterable[RosoutEntry]) -> int:
        """Take a batch of messages into the model and update the screen once; returns how many were kept."""
        taken = self.model.ingest(entries)
        self.show_model()
        return taken

    def take_batch(self) -> None:
        """Timer: move what the live source received into the model (one screen update per batch)."""
        if self.source is not None and self.source.inbox:
            self.ingest(self.source.take())
        else:
            self.refresh_bars()

    def show_model(self) -> None:
        """Repaint the table if the rows changed, and the bars."""
        if self.model.version != self._shown_version:
            self._shown_version = self.model.version
            self.table.sync()
        self.refresh_bars()

    def _on_state(self, state: SourceState) -> None:
        previous, self.source_state = self.source_state, state
        if state.status is MasterState.LOST:
            self.notify(state.text(), title="master", severity="error", timeout=6)
        elif state.status is MasterState.CONNECTED and previous is not None and previous.status is MasterState.LOST:
            self.notify(f"master {state.master_uri} is back: listening to /rosout_agg again", title="master",
                        timeout=6)

    # -- bars ------------------------------------------------------------------------------------------
    def say(self, text: str) -> None:
        """Show a notice in the status line for a few seconds."""
        self.notice = (time.monotonic(), text)

    def status_info(self) -> StatusInfo:
        """The status line's state besides the model's counters."""
        stamp, notice = self.notice
        notice = notice if time.monotonic() - stamp < NOTICE_SECONDS else ""
        if self.log_file is not None:
            source, ok = f"file {self.log_name}", True
            malformed = self.log_file.malformed_summary()
        else:
            state = self.source_state or SourceState(MasterState.WAITING, self.master_uri)
            source, ok, malformed = state.text(), state.status is MasterState.CONNECTED, ""
        return StatusInfo(follow=self.table.follow, source=source, source_ok=ok, malformed=malformed, notice=notice)

    def refresh_bars(self) -> None:
        """Bring the filter bar and status line up to date (each repaints only if its text changed)."""
        self.filter_bar.show(filter_markup(self.spec, self.model, list(self.highlights), self.regex_error))
        self.status_bar.show(status_markup(self.model, self.status_info()))

    def on_log_table_cursor_moved(self, message: LogTable.CursorMoved) -> None:
        """The detail pane follows the selected message."""
        if self.detail.display:
            self._show_detail(message.seq)

    def _show_detail(self, seq: int | None) -> None:
        entry = None
        if seq is not None and self.model.first <= seq < self.model.end:
            entry = self.model.entry(seq)
        self.detail_text.update(detail_markup(seq, entry, self.log_name))

    # -- filters -------------------------------------------------------------------------------------------
    def apply_filter(self, spec: FilterSpec) -> bool:
        """Show the messages passing ``spec``; a bad regular expression is reported and changes nothing."""
        if spec == self.spec and not self.regex_error:
            return True
        try:
            self.model.set_filter(spec)
        except FilterError as exc:
            self.regex_error = str(exc)
            return False
        self._shown_version = self.model.version
        self.table.refilter()
        self.spec = spec
        self.regex_error = ""
        return True

    def action_toggle_level(self, level: int) -> None:
        """Show or hide one level; a level under --min-level starts being kept from now on."""
        if level < self.model.min_level:
            self.model.set_min_level(level)
            self.apply_filter(_with(self.spec, levels=self.spec.levels | {level}))
            self.say(f"keeping {Level(level).name} messages from now on")
            return
        self.apply_filter(self.spec.toggle_level(level))

    def _selected_node(self) -> str | None:
        seq = self.table.cursor_seq
        if seq is None or not self.model.first <= seq < self.model.end:
            self.say("select a message first")
            return None
        return self.model.entry(seq).node

    def action_include_node(self) -> None:
        """Show only the selected message's node (again: undo; on several rows: several nodes)."""
        node = self._selected_node()
        if node is not None:
            self.apply_filter(self.spec.toggle_include(node))

    def action_exclude_node(self) -> None:
        """Hide the selected message's node (undo with N)."""
        node = self._selected_node()
        if node is not None:
            self.apply_filter(self.spec.toggle_exclude(node))

    def action_clear_nodes(self) -> None:
        """Show every node again."""
        self.apply_filter(self.spec.without_nodes())

    def action_toggle_regex(self) -> None:
        """Switch search and new highlight rules between plain text and regular expressions."""
        if not self.apply_filter(_with(self.spec, regex=not self.spec.regex)):
            self.regex_error = ""
            self.say(f"{self.spec.search!r} is not a regular expression: still searching plain text")

    def action_clear_search(self) -> None:
        """Escape: drop the search."""
        if self.spec.search or self.regex_error:
            self.regex_error = ""
            self.apply_filter(_with(self.spec, search=""))

    def action_clear_highlights(self) -> None:
        """Remove every highlight rule."""
        self._set_highlights(())

    def add_highlight(self, pattern: str, regex: bool) -> bool:
        """Mark messages matching ``pattern`` with the next highlight colour; False for a bad regex."""
        try:
            rule = HighlightRule(pattern, regex)
        except FilterError as exc:
            self.regex_error = str(exc)
            return False
        self.regex_error = ""
        self._set_highlights((*self.highlights, rule))
        return True

    def _set_highlights(self, rules: tuple[HighlightRule, ...]) -> None:
        self.table.highlights = list(rules)
        self.table.restyle()
        self.highlights = rules

    # -- pause, clear, follow, detail ------------------------------------------------------------------------
    def action_toggle_pause(self) -> None:
        """Freeze the view (messages keep arriving into the buffer) or show what arrived meanwhile."""
        if self.model.paused:
            count = self.model.resume()
            self.say(f"resumed: {count:,} new messages")
            self.show_model()
        else:
            self.model.pause()
            self.show_model()

    def action_clear(self) -> None:
        """Forget the messages shown so far."""
        self.model.clear()
        self.show_model()
        self.say("cleared")

    def action_follow(self) -> None:
        """Follow the newest messages."""
        self.table.set_follow(True)

    def action_toggle_detail(self) -> None:
        """Show or hide every field of the selected message."""
        detail = self.detail
        detail.display = not detail.display
        if detail.display:
            self._show_detail(self.table.cursor_seq)

    # -- prompt ------------------------------------------------------------------------------------------------
    def action_open_prompt(self, purpose: str) -> None:
        """Open the input line for ``search``, ``highlight`` or ``save``."""
        prompt = self.prompt
        prompt.purpose = purpose
        kind = "regex" if self.spec.regex else "text"
        if purpose == "search":
            self._before_prompt = self.spec
            prompt.placeholder = f"search messages ({kind}; Enter keeps it, Escape cancels)"
            prompt.value = self.spec.search
        elif purpose == "highlight":
            prompt.placeholder = f"highlight messages matching ({kind})"
            prompt.value = ""
        else:
            prompt.placeholder = "save the shown messages (rosout.log format) to"
            prompt.value = time.strftime("rostui_console_%Y%m%d-%H%M%S.log")
        prompt.border_title = {"search": f"search ({kind})", "highlight": f"highlight ({kind})",
                               "save": "save shown messages as rosout.log"}[purpose]
        prompt.display = True
        focus_now(prompt)
        prompt.cursor_position = len(prompt.value)

    def close_prompt(self, cancelled: bool = False) -> None:
        """Hide the input line (a cancelled search goes back to the filter before it)."""
        prompt = self.prompt
        if cancelled and prompt.purpose == "search" and self._before_prompt is not None:
            self.regex_error = ""
            self.apply_filter(self._before_prompt)
        prompt.remove_class("-invalid")
        prompt.display = False
        prompt.purpose = ""
        self._before_prompt = None
        self.table.focus()

    def on_input_changed(self, event: Input.Changed) -> None:
        """Search as the user types (after a short pause), marking an invalid regex."""
        prompt = self.prompt
        if prompt.purpose == "search":
            if self._search_timer is not None:
                self._search_timer.stop()
            self._search_timer = self.set_timer(SEARCH_DELAY, lambda: self._search(event.value))
        elif prompt.purpose == "highlight" and self.spec.regex:
            try:
                compile_text(event.value, True)
                prompt.remove_class("-invalid")
            except FilterError:
                prompt.add_class("-invalid")

    def _search(self, text: str) -> None:
        self._search_timer = None
        ok = self.apply_filter(_with(self.spec, search=text))
        self.prompt.set_class(not ok, "-invalid")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """Enter: keep the search, add the highlight rule, or save the file."""
        prompt = self.prompt
        value = event.value
        if prompt.purpose == "search":
            if self._search_timer is not None:
                self._search_timer.stop()
                self._search_timer = None
            if not self.apply_filter(_with(self.spec, search=value)):
                prompt.add_class("-invalid")
                return
        elif prompt.purpose == "highlight":
            if value and not self.add_highlight(value, self.spec.regex):
                prompt.add_class("-invalid")
                return
        elif prompt.purpose == "save":
            if not self.save(value):
                return
        self.close_prompt()

    def save(self, path_text: str) -> bool:
        """Write the shown messages to ``path_text`` in rosout.log format; False (and a notice) on failure."""
        if not path_text.strip():
            self.say("save: no file name given")
            return False
        path = Path(path_text.strip()).expanduser()
        entries = [entry for _, entry in self.model.shown()]
        try:
            path.write_text(entries_text(entries), encoding="utf-8")
        except OSError as exc:
            self.say(f"save failed: {path}: {exc.strerror or exc}")
            self.notify(f"{path}: {exc.strerror or exc}", title="save failed", severity="error")
            return False
        self.say(f"saved {len(entries):,} messages to {path}")
        return True

    # -- leaving ---------------------------------------------------------------------------------------------------
    async def release(self) -> None:
        """Unregister the app's node."""
        if self.source is not None:
            await self.source.stop()


def _with(spec: FilterSpec, **changes: Any) -> FilterSpec:
    return replace(spec, **changes)


def run_app(options: ConsoleOptions, log: RosoutLog | None = None, log_name: str | None = None) -> int:
    """Run :class:`ConsoleApp` in this terminal; returns the exit status (1 without a terminal)."""
    if terminal_missing("rostui console", "use `rostui topic echo /rosout_agg` without one"):
        return 1
    app = ConsoleApp(options, log, log_name=log_name, freeze_gc=True)
    app.run()
    return app.return_code or 0
