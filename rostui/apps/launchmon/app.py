"""LaunchMonitorApp: a running launch with a live table of its nodes and the output of one of them.

The app runs the launch's :class:`~rostui.launch.supervisor.Supervisor` on
Textual's event loop (a task of its own, so the launch outlives no screen and
the screen outlives no launch).  Every ``period`` seconds it reads the
supervisor's processes into table rows (:mod:`rostui.apps.launchmon.rows`)
and appends the selected node's new output lines to the log pane.  s, k and
r start, stop and restart the selected node through the supervisor; q and
Ctrl-C shut the whole launch down as roslaunch does and leave once every
node has stopped.
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
import time
from pathlib import Path
from typing import Awaitable, Callable, ClassVar

from rich.text import Text
from textual import events
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.timer import Timer
from textual.widgets import DataTable, RichLog, Static

from rostui.apps.launchmon.rows import COLUMNS, NodeRow, measure, node_row
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.fitted_table import FittedTable
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import quit_on_signals
from rostui.launch.errors import LaunchError
from rostui.launch.output import OutputBuffer
from rostui.launch.process import ManagedProcess, NodeState
from rostui.launch.supervisor import Supervisor
from rostui.tools.usage import Usage, UsageSampler, children_map

__all__ = ["LaunchMonitorApp", "KEYS", "run_app"]

#: Key help under the log pane.
KEYS = key_line("↑↓ node  s start  k stop  r restart  l launcher's output  f follow  Tab log/table")
#: Most output lines added to the log pane per refresh: a node flooding its output shows its newest lines.
MAX_LINES_PER_REFRESH = 500
#: Lines the log pane holds (the newest of the node's kept lines; drawing each costs time when a node is selected).
PANE_LINES = 2000
#: Seconds a notice (a start, stop or restart done) stays in the status line.
NOTICE_SECONDS = 5.0
#: Seconds the launcher has, beyond its nodes' SIGINT and SIGTERM timeouts, to stop after SIGTERM or SIGHUP.
STOP_MARGIN = 5.0
#: Colour of each kind of state in the table.
STATE_STYLES = {
    NodeState.STARTING: "yellow",
    NodeState.RUNNING: "green",
    NodeState.RESPAWNING: "yellow",
    NodeState.DIED: "bold red",
    NodeState.FINISHED: "",
    NodeState.STOPPING: "yellow",
    NodeState.STOPPED: "dim",
    NodeState.FAILED: "bold red",
}
#: Colour of each kind of output line in the log pane.
STREAM_STYLES = {"stdout": "", "stderr": "red", "launch": "italic cyan", "error": "bold red"}


class OutputLog(RichLog):
    """The log pane: scrolling back (keys or mouse wheel) stops following until f or End."""

    def _stop_following(self) -> None:
        app = self.app
        if isinstance(app, LaunchMonitorApp) and app.following:
            app.set_following(False)

    def action_scroll_up(self) -> None:
        """Up: one line back."""
        self._stop_following()
        super().action_scroll_up()

    def action_page_up(self) -> None:
        """Page Up: one page back."""
        self._stop_following()
        super().action_page_up()

    def action_scroll_home(self) -> None:
        """Home: the first kept line."""
        self._stop_following()
        super().action_scroll_home()

    def action_scroll_end(self) -> None:
        """End: the newest line, and follow again."""
        app = self.app
        if isinstance(app, LaunchMonitorApp):
            app.set_following(True)
        else:
            super().action_scroll_end()

    def on_mouse_scroll_up(self, _event: events.MouseScrollUp) -> None:
        """The mouse wheel back: stop following (Textual's own handler then scrolls)."""
        self._stop_following()


class LaunchMonitorApp(KeysApp):
    """Run ``supervisor``'s launch and show its nodes; ``title`` names the launch in the status line.

    ``period`` is the refresh interval in seconds.  ``row_hook`` may rewrite
    each table row and ``text_hook`` the status line and each output line
    before they are drawn: tests fix what differs from run to run (pids, CPU,
    memory, the master's port, temporary paths) this way.
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui launch"

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("s", "control('start')", "start"),
        Binding("k", "control('stop')", "stop"),
        Binding("r", "control('restart')", "restart"),
        Binding("l", "show_launcher", "launcher's output"),
        Binding("f", "toggle_follow", "follow"),
        Binding("end", "follow", "follow", show=False),
        Binding("tab", "switch_focus", "log/table", priority=True, show=False),
    ]

    def __init__(self, supervisor: Supervisor, *, title: str = "", period: float = 0.25,
                 row_hook: Callable[[NodeRow], NodeRow] | None = None,
                 text_hook: Callable[[str], str] | None = None) -> None:
        super().__init__()
        self.supervisor = supervisor
        self.launch_title = title
        self.period = period
        self.row_hook = row_hook
        self.text_hook = text_hook
        self.sampler = UsageSampler()
        self.rows: dict[str, NodeRow] = {}
        self.shown: str | None = None
        """The label of the node whose output the log pane shows (None: the launcher's own output)."""
        self.following = True
        self.notice = ""
        self._notice_until: float | None = None
        self.launch_error = ""
        """A load or master error that ended the launch before it ran (printed after the app leaves)."""
        self.quitting = False
        self._shown_seq = 0
        self._ticks = 0
        self._usage: dict[str, Usage | None] = {}
        self._measuring = False
        self._run_task: asyncio.Task[None] | None = None
        self._refresh_timer: Timer | None = None
        self.terminal_gone = False
        """True after SIGHUP: the terminal is gone, nothing more is drawn."""

    # -- composition -----------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Status line, problem line, node table, log title, log pane, key help."""
        yield Static(id="status")
        yield Static(id="banner")
        table: DataTable[Text] = FittedTable(id="nodes", cursor_type="row", zebra_stripes=False)
        for key, heading, width in COLUMNS:
            table.add_column(heading, key=key, width=width)
        yield table
        yield Static(id="log-title")
        yield OutputLog(id="log", max_lines=PANE_LINES, markup=False, highlight=False, wrap=False)
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Start the launch and the refresh timer; Ctrl-C from outside (SIGINT) and SIGTERM quit; SIGHUP stops
        the launch and leaves (each within the time the launch's nodes are given to stop)."""
        options = self.supervisor.options
        quit_on_signals(self, grace=options.sigint_timeout + options.sigterm_timeout + STOP_MARGIN,
                        on_hangup=self._terminal_gone)
        loop = asyncio.get_running_loop()
        try:
            loop.add_signal_handler(signal.SIGINT, lambda: self.call_later(self.action_quit))
        except (NotImplementedError, RuntimeError, ValueError):
            pass
        self.query_one("#banner", Static).display = False
        self.table.focus()
        self._run_task = loop.create_task(self._run_launch())
        self._refresh_timer = self.set_interval(self.period, self.refresh_view)
        self._update_log_title()
        self.refresh_view()

    async def on_unmount(self) -> None:
        """Never leave the launch running: shut it down when the app ends any other way than q."""
        self.supervisor.request_stop()
        if self._run_task is not None:
            await asyncio.gather(self._run_task, return_exceptions=True)

    @property
    def table(self) -> DataTable[Text]:
        """The node table."""
        return self.query_one("#nodes", DataTable)

    @property
    def log_view(self) -> OutputLog:
        """The log pane."""
        return self.query_one("#log", OutputLog)

    # -- the launch ----------------------------------------------------------------------------------
    def _terminal_gone(self) -> None:
        """SIGHUP: stop drawing (a write to a vanished terminal can block Textual's output thread for good),
        shut the launch down, then leave at once."""
        self.terminal_gone = True
        if self._refresh_timer is not None:
            self._refresh_timer.stop()
        self.supervisor.request_stop()

    async def _run_launch(self) -> None:
        try:
            await self.supervisor.run()
        except LaunchError as exc:
            self.launch_error = str(exc)
            self.supervisor.exit_code = 1
        if self.terminal_gone:
            os._exit(self.supervisor.exit_code)  # every node is stopped; nothing is left to restore on screen
        if self.launch_error:
            self.exit(1, return_code=1)
            return
        if self.quitting:
            self.exit(self.supervisor.exit_code, return_code=self.supervisor.exit_code)
        else:
            self.refresh_view()

    # -- refresh -------------------------------------------------------------------------------------
    def refresh_view(self) -> None:
        """Read the supervisor: table rows, status line, problem line and new output lines."""
        if not self.query("#nodes"):  # quitting: the screen's widgets are gone, the timer not yet
            return
        self._ticks += 1
        processes = self.supervisor.processes
        due = self._ticks % max(1, round(1.0 / self.period)) == 1 or not self._usage
        if due and processes and not self._measuring and not self.terminal_gone:
            self._measuring = True
            self.run_worker(self._measure(list(processes)), group="usage", exit_on_error=False)
        for process in processes:
            row = node_row(process, self._usage.get(process.label))
            if self.row_hook is not None:
                row = self.row_hook(row)
            self._put_row(row)
        self._append_output()
        self.update_status()

    async def _measure(self, processes: list[ManagedProcess]) -> None:
        """CPU and memory of every running node, sampled in a thread (psutil reads /proc for each process)."""
        def sample() -> dict[str, Usage | None]:
            children = children_map()
            usage = {process.label: measure(self.sampler, process, children) for process in processes}
            self.sampler.forget_dead()
            return usage

        try:
            self._usage = await asyncio.to_thread(sample)
        finally:
            self._measuring = False

    def _put_row(self, row: NodeRow) -> None:
        table = self.table
        old = self.rows.get(row.key)
        if old == row:
            return
        style = STATE_STYLES[row.kind]
        cells = [Text(row.node), Text(row.state, style=style), Text(row.pid, justify="right"),
                 Text(row.cpu, justify="right"), Text(row.mem, justify="right"),
                 Text(row.restarts, justify="right"), Text(row.flags)]
        if old is None:
            table.add_row(*cells, key=row.key)
        else:
            for (key, _, width), cell, before, now in zip(COLUMNS, cells, old.cells(), row.cells()):
                if before != now or old.kind != row.kind:
                    table.update_cell(row.key, key, cell, update_width=width is None)
        self.rows[row.key] = row

    def update_status(self) -> None:
        """The status line (launch, master, counts, notice) and the red problem line."""
        supervisor = self.supervisor
        processes = supervisor.processes
        parts = [self.launch_title] if self.launch_title else []
        if supervisor.embedded is not None:
            parts.append(f"master {supervisor.master_uri} (in this process)")
        else:
            parts.append(f"master {supervisor.master_uri}")
        counts: dict[str, int] = {}
        for process in processes:
            word = "cannot start" if process.state is NodeState.FAILED else process.state.value
            counts[word] = counts.get(word, 0) + 1
        if processes:
            parts.append(" · ".join(f"{n} {word}" for word, n in counts.items()))
        elif not supervisor.finished.is_set():
            parts.append("setting up…")
        if self.notice and self._notice_until is not None and time.monotonic() > self._notice_until:
            self.notice = ""
        if self.notice:
            parts.append(self.notice)
        status = " │ ".join(parts)
        if self.text_hook is not None:
            status = self.text_hook(status)
        self.query_one("#status", Static).update(Text(status))
        banner = self.query_one("#banner", Static)
        problem = ""
        if self.quitting or (supervisor.stopping.is_set() and not supervisor.end_reason):
            problem = "shutting down: SIGINT sent to every node…" if not supervisor.finished.is_set() \
                else "every node has stopped"
        elif supervisor.end_reason:
            problem = supervisor.end_reason + ("; q leaves" if supervisor.finished.is_set() else "")
        banner.update(Text(problem))
        banner.display = bool(problem)

    # -- the log pane -----------------------------------------------------------------------------------
    def _buffer(self) -> OutputBuffer:
        if self.shown is None:
            return self.supervisor.launch_output
        return self._process(self.shown).output

    def _process(self, label: str) -> ManagedProcess:
        return next(p for p in self.supervisor.processes if p.label == label)

    def show_output(self, label: str | None) -> None:
        """Show the output of the node labelled ``label`` (None: the launcher's own) from its first kept line."""
        self.shown = label
        self._shown_seq = 0
        self.log_view.clear()
        self._append_output(limit=PANE_LINES)
        self._update_log_title()

    def _append_output(self, limit: int | None = None) -> None:
        buffer = self._buffer()
        lines = list(buffer.since(self._shown_seq))
        if not lines:
            return
        log = self.log_view
        limit = limit or MAX_LINES_PER_REFRESH
        skipped = buffer.next_seq - self._shown_seq - min(len(lines), limit) if self._shown_seq else 0
        if len(lines) > limit:
            lines = lines[-limit:]
        if skipped > 0:
            log.write(Text(f"… {skipped} lines skipped: more than {limit} arrived between two refreshes …",
                           style="dim"), scroll_end=self.following)
        hook = self.text_hook
        texts = [_line_text(line.text if hook is None else hook(line.text), line.stream) for line in lines]
        log.write(Text("\n").join(texts), scroll_end=self.following)  # one write: rendering is per call
        self._shown_seq = buffer.next_seq

    def _update_log_title(self) -> None:
        who = "the launcher" if self.shown is None else self._process(self.shown).name
        mode = "following" if self.following else "paused (f or End follows)"
        self.query_one("#log-title", Static).update(Text(f"output of {who} — {mode}"))

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        """Moving the cursor to a node shows its output."""
        label = event.row_key.value
        if label is not None and label != self.shown and label in self.rows:
            self.show_output(label)

    # -- actions ------------------------------------------------------------------------------------
    def selected_label(self) -> str | None:
        """The label of the node under the table's cursor."""
        table = self.table
        if not table.row_count:
            return None
        row_key, _ = table.coordinate_to_cell_key(table.cursor_coordinate)
        return row_key.value

    def action_control(self, what: str) -> None:
        """s / k / r: start, stop or restart the selected node (in the background; the table shows progress)."""
        label = self.selected_label()
        if label is None or self.quitting:
            return
        process = self._process(label)
        name = process.name
        if what == "start" and process.running:
            self.set_notice(f"{name} is already running")
            return
        calls = {"start": self.supervisor.start_node, "stop": self.supervisor.stop_node,
                 "restart": self.supervisor.restart_node}
        self.set_notice(f"{what} {name}…", seconds=None)
        self.run_worker(self._control(what, calls[what], name), group=f"control-{label}", exit_on_error=False)

    async def _control(self, what: str, call: Callable[[str], Awaitable[bool | None]], name: str) -> None:
        try:
            result = await call(name)
        except LaunchError as exc:
            self.set_notice(f"cannot {what} {name}: {exc.message}")
        else:
            self.set_notice(f"{what} {name}: cannot run it (see its output)" if result is False else
                            f"{what} {name}: done")
        self.refresh_view()

    def set_notice(self, text: str, seconds: float | None = NOTICE_SECONDS) -> None:
        """Show ``text`` in the status line (for ``seconds``; None: until the next notice)."""
        self.notice = text
        self._notice_until = None if seconds is None else time.monotonic() + seconds
        self.update_status()

    def action_show_launcher(self) -> None:
        """l: the launcher's own output (again: back to the selected node)."""
        if self.shown is None:
            label = self.selected_label()
            if label is not None:
                self.show_output(label)
        else:
            self.show_output(None)

    def set_following(self, following: bool) -> None:
        """Follow new output (scroll to the end on each line), or keep the log pane where it is."""
        self.following = following
        if following:
            self.log_view.scroll_end(animate=False)
        self._update_log_title()

    def action_toggle_follow(self) -> None:
        """f: follow new output, or stop following."""
        self.set_following(not self.following)

    def action_follow(self) -> None:
        """End: follow new output from the end."""
        self.set_following(True)

    def action_switch_focus(self) -> None:
        """Tab: move the keyboard between the node table and the log pane."""
        if self.table.has_focus:
            self.log_view.focus()
        else:
            self.table.focus()

    async def action_quit(self) -> None:
        """q / Ctrl-C: shut the launch down (SIGINT, SIGTERM, SIGKILL after the timeouts), then leave."""
        if self.supervisor.finished.is_set():
            self.exit(self.supervisor.exit_code, return_code=self.supervisor.exit_code)
            return
        if self.quitting:
            return
        self.quitting = True
        self.supervisor.request_stop()
        self.update_status()


def _line_text(line: str, stream: str) -> Text:
    """One output line for the log pane (ANSI colours of the node's own kept, stderr and launcher lines coloured)."""
    text = Text.from_ansi(line) if "\x1b" in line else Text(line)
    style = STREAM_STYLES.get(stream, "")
    if style:
        text.stylize(style)
    return text


def run_app(supervisor: Supervisor, title: str) -> int:
    """Run the monitor in this terminal; returns the launch's exit status (1 when the launch could not start)."""
    app = LaunchMonitorApp(supervisor, title=title)
    try:
        app.run()
    finally:
        supervisor.kill_leftovers()
    if app.launch_error:
        print(f"rostui launch: {app.launch_error}", file=sys.stderr)
        return 1
    return app.return_code if app.return_code is not None else supervisor.exit_code
