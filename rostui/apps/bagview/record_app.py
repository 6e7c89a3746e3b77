"""BagRecordApp: ``rostui bag view --record``: record with live per-topic counts, sizes and rates.

Recording starts at once (as ``rostui bag record`` does); ``r`` stops and
starts again (into the next file), ``n`` splits into the next file without
losing a message, ``q`` finishes the file and leaves. Files are named like
``rosbag record --split``: ``NAME_0.mcap``, ``NAME_1.mcap``, ...
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any, ClassVar

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.widgets import Static

from rostui.apps.bagview.bars import RECORD_KEYS
from rostui.tools.bag.info import status_size
from rostui.apps.bagview.recording import RecordSession
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core.bag.model import BagError
from rostui.tools.bag.recorder import RecordOptions

__all__ = ["BagRecordApp", "record_header", "record_status", "run_record_app", "topics_table"]

#: Screen refreshes (and rate samples) per second.
REFRESH_RATE = 4.0


def topics_table(session: RecordSession) -> Table:
    """One row per topic: messages in this file and in all, size, rate and bandwidth."""
    table = Table(expand=True, box=None, header_style="bold", pad_edge=False)
    table.add_column("topic", ratio=1, no_wrap=True, overflow="ellipsis")
    for name in ("msgs (file)", "msgs (all)", "size (all)", "rate", "bandwidth"):
        table.add_column(name, justify="right", no_wrap=True)
    subscribed = session.subscribed
    for topic in sorted(set(session.meters) | subscribed):
        meter = session.meters.get(topic)
        if meter is None:
            table.add_row(topic, "0", "0", "0 B", "-", "-")
            continue
        rate, bandwidth = meter.rates()
        style = "" if topic in subscribed or not session.recording else "dim"
        table.add_row(topic, str(meter.file_count), str(meter.count), status_size(meter.size), f"{rate:.1f} Hz",
                      f"{status_size(bandwidth)}/s", style=style)
    return table


def record_status(session: RecordSession, problem: str) -> Text:
    """``● REC 'name_0.mcap' │ 123 msgs │ 1.2 MB │ 3 topics │ 1 file`` (or STOPPED, and which limit stopped
    it), then a problem."""
    text = Text(" ● REC " if session.recording else " ■ STOPPED ", style="bold reverse")
    if session.file:
        text.append(f" '{session.file}'")
    nfiles = len(session.files)
    text.append(f" │ {session.messages} msgs │ {status_size(session.total_bytes)} │ {len(session.subscribed)} topics"
                f" │ {nfiles} file{'s' if nfiles != 1 else ''}")
    if session.dropped:
        text.append(f" │ {session.dropped} dropped", style="bold")
    if session.notice and not session.recording:
        text.append(f" │ {session.notice}", style="bold yellow")
    if problem:
        text.append(f" │ {problem}", style="bold red")
    return text


def record_header(session: RecordSession) -> Text:
    """``recording /a, topics matching /cam.*, not /cam/raw into rec_<n>.mcap · stops at 30 s · next file rec_0.mcap``."""
    opts = session.opts
    parts = []
    if opts.all_topics:
        parts.append("all topics")
    if opts.topics:
        parts.append(("topics matching " if opts.regex else "") + ", ".join(opts.topics))
    what = " and ".join(parts)
    if opts.exclude:
        what += f" except those matching {opts.exclude}"
    limits = [f"{opts.size_mb:g} MB" if opts.size_mb is not None else "",
              f"{opts.duration_s:g} s" if opts.duration_s is not None else ""]
    limit = " or ".join(x for x in limits if x)
    until = (f" · {'splits every' if opts.split else 'stops at'} {limit}") if limit else ""
    root, ext = os.path.splitext(session.base)
    return Text(f"recording {what} into {root}_<n>{ext}{until} · next file {session.next_name()}")


class BagRecordApp(ReleasesOnExit, KeysApp):
    """Record topics with a live table of what arrives; start, stop and split from the keyboard."""

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui bag view --record"

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("r", "toggle_record", "start/stop"),
        Binding("n", "split", "split"),
    ]

    def __init__(self, opts: RecordOptions, *, master_uri: str | None = None, start: bool = True) -> None:
        super().__init__()
        self.session = RecordSession(opts, master_uri=master_uri, report=self._report)
        self.start_at_once = start
        self.problem = ""
        self.log_lines: list[str] = []
        self.header = Static(id="header")
        self.table = Static(id="record-table-text")
        self.status = Static(id="status")

    def compose(self) -> ComposeResult:
        """Header, topics table, status line and key help."""
        yield self.header
        with VerticalScroll(id="record-table"):
            yield self.table
        yield self.status
        yield Static(RECORD_KEYS, id="keys")

    def on_mount(self) -> None:
        """Start recording and the refresh timer."""
        quit_on_signals(self)
        self.set_interval(1.0 / REFRESH_RATE, self.refresh_view)
        if self.start_at_once:
            self.run_worker(self._start(), name="start", exclusive=True, exit_on_error=False)
        self.refresh_view()

    def _report(self, line: str) -> None:
        self.log_lines.append(line)

    async def _start(self) -> None:
        try:
            await self.session.start()
            self.problem = ""
        except BagError as exc:
            self.problem = str(exc)
        self.refresh_view()

    def refresh_view(self) -> None:
        """Timer: sample the rates and redraw."""
        self.session.sample()
        problem = self.problem or (self.session.errors[-1] if self.session.errors else "")
        self.header.update(record_header(self.session))
        self.table.update(topics_table(self.session))
        self.status.update(record_status(self.session, problem))

    def action_toggle_record(self) -> None:
        """Stop, or start again into the next file (in a worker: closing a file may take a moment)."""
        self.run_worker(self._toggle(), group="control", exit_on_error=False)

    async def _toggle(self) -> None:
        if self.session.recording:
            await self.session.stop()
        else:
            await self._start()
        self.refresh_view()

    def action_split(self) -> None:
        """Go on in the next file (in a worker: the next recorder connects first)."""
        self.run_worker(self._split(), group="control", exit_on_error=False)

    async def _split(self) -> None:
        try:
            await self.session.split()
        except BagError as exc:
            self.problem = str(exc)
        self.refresh_view()

    async def release(self) -> None:
        """Finish the file."""
        await self.session.close()


def run_record_app(opts: RecordOptions, **options: Any) -> int:
    """Run :class:`BagRecordApp` in this terminal; then print what was recorded."""
    if terminal_missing("rostui bag view", "use `rostui bag record` without one"):
        return 1
    app = BagRecordApp(opts, **options)
    app.run()
    session = app.session
    if session.files:
        print(f"Recorded {session.messages} messages to {', '.join(session.files)}", flush=True)
    for problem in session.errors:
        print(f"rostui bag view: {problem}", file=sys.stderr)
    return 1 if session.errors else (app.return_code or 0)
