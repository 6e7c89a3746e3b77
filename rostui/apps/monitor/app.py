"""MonitorApp: every topic live in one table, expanded topics as message trees, a plot of fields, publishing.

A :class:`~rostui.models.monitor.source.MonitorSource` runs on Textual's loop:
it polls the master and subscribes only to the topics whose rows are on
screen (plus the expanded and plotted ones).  Fields named on the command
line as rqt_plot takes them (``/turtle1/pose/x``, ``/turtle1/pose/x:y``) are
told apart from topics once the master lists the topics.  A timer repaints the table,
the trees and the charts a few times a second; a second timer samples rates
and bandwidths once a second (the sparklines' step).  Keys act at once:
sorting, filtering, expanding and publishing repaint in the same handler.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable, ClassVar, Sequence

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Horizontal
from textual.markup import escape
from textual.widgets import Input, Static

from rostui.apps.monitor.detail import Charts, Line, MessageTree
from rostui.apps.monitor.editor import PublishEditor
from rostui.apps.monitor.plot import FieldChooser, PlotPanel
from rostui.apps.monitor.table import TopicTable
from rostui.apps.terminal import terminal_missing
from rostui.apps.view.app import ViewScreen
from rostui.apps.view.registry import viewable
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.core.msg import Message
from rostui.core.network import master_uri_from_env
from rostui.models.master_link import MasterState, SourceState
from rostui.models.monitor.plot import PlotFieldError, check_numeric, expand_spec, numeric_fields, split_spec
from rostui.models.monitor.publish import (
    PublishError, Repeater, check_topic, message_from_text, message_template, parse_rate,
)
from rostui.models.monitor.rows import Column, Liveness, TopicRow, filter_rows, sort_rows
from rostui.models.monitor.source import MonitorSource
from rostui.models.monitor.tree import message_tree

__all__ = ["MonitorApp", "run_app", "KEYS"]

#: Key help at the bottom.
KEYS = key_line("s sort  S rev  Enter expand  Tab tree  f plot  p publish")
#: What the filter line says while it waits for "/", and while it has the keyboard.
FILTER_IDLE = "/ filter"
FILTER_TYPING = "name or type; Enter keeps, Esc clears"
#: Actions of the plot's keys.
PLOT_ACTIONS = frozenset({"plot", "toggle_plot", "window_longer", "window_shorter", "pause_plot"})
#: Seconds between repaints of the table, trees and charts.
REFRESH = 0.25
#: Seconds between rate/bandwidth samples (one sparkline step).
SAMPLE = 1.0


class FilterInput(LineInput):
    """The filter line (always on screen, so opening it repaints one line); Escape clears it."""

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "clear filter", show=False)]

    def action_cancel(self) -> None:
        """Clear the filter and give the keyboard back to the table."""
        app = self.app
        assert isinstance(app, MonitorApp)
        app.close_filter(clear=True)

    def on_focus(self) -> None:
        """Say how the line works while typing."""
        self.placeholder = FILTER_TYPING

    def on_blur(self) -> None:
        """Back to the short hint."""
        self.placeholder = FILTER_IDLE


class MonitorApp(ReleasesOnExit, KeysApp):
    """The topics of the master at ``master_uri`` (ROS_MASTER_URI by default); ``topics`` start expanded.

    An entry of ``topics`` that turns out to be a field of a topic the master
    knows (``/turtle1/pose/x``), or that holds rqt_plot's ``:`` shorthand
    (``/turtle1/pose/x:y:theta``), is plotted instead.

    The master is polled every ``period`` seconds; the screen is repainted
    every ``refresh`` seconds and rates are sampled every ``sample_every``
    seconds, on ``clock`` (wall time; tests step their own).
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui monitor"

    TYPE_AHEAD_ACTIONS = frozenset({"open_filter"})
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("slash", "open_filter", "filter", priority=True),
        Binding("s", "sort_next", "sort"),
        Binding("S", "sort_reverse", "reverse sort"),
        Binding("f", "plot", "plot field"),
        Binding("v", "toggle_plot", "show/hide plot"),
        Binding("plus,equals_sign", "window_longer", "longer plot window"),
        Binding("minus", "window_shorter", "shorter plot window"),
        Binding("space", "pause_plot", "pause/resume plot"),
        Binding("p", "publish", "publish"),
        Binding("x", "collapse", "collapse topic", show=False),
    ]

    def __init__(self, topics: Sequence[str] = (), *, master_uri: str | None = None, period: float = 1.0,
                 refresh: float = REFRESH, sample_every: float = SAMPLE,
                 clock: Callable[[], float] = time.time) -> None:
        super().__init__()
        self.master_uri = master_uri_from_env(master_uri)
        self.clock = clock
        self.source = MonitorSource(self.master_uri, period=period, on_state=self._on_state, clock=clock)
        self.refresh_period = refresh
        self.sample_period = sample_every
        names = list(dict.fromkeys(topics))
        self.expanded: list[str] = [name for name in names if ":" not in name]
        #: Command-line names not yet known as a topic or as a field of one.
        self.pending: list[str] = names
        self.plot_open = any(":" in name for name in names)
        self.sort_column = Column.TOPIC
        self.sort_reverse = False
        self.filter_text = ""
        self.notice = ""
        self.rows: list[TopicRow] = []
        self.shown: list[TopicRow] = []
        self.repeaters: dict[str, Repeater] = {}
        self.repaints = 0
        self._problem: str | None = None

    # -- composition -------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Status, problem line, the table, the expanded view (trees | charts), filter line, keys."""
        yield Line(id="status")
        yield Static(id="banner")
        yield TopicTable(id="topics")
        yield PlotPanel(id="plot")
        with Horizontal(id="detail"):
            yield MessageTree(id="tree")
            yield Charts(id="charts")
        with Horizontal(id="bottom"):
            yield FilterInput(placeholder=FILTER_IDLE, id="filter")
            yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Start the source and the timers; the table has the focus."""
        quit_on_signals(self)
        self.query_one("#banner").display = False
        self.table.focus()
        self.query_one("#plot").display = self.plot_open
        self.message_trees.set_topics(self.expanded)
        self.run_worker(self.source.run(), group="source", exit_on_error=False)
        self.set_interval(self.refresh_period, self.repaint)
        self.set_interval(self.sample_period, self.sample)
        self.repaint()

    @property
    def table(self) -> TopicTable:
        """The topic table."""
        return self.query_one("#topics", TopicTable)

    @property
    def message_trees(self) -> MessageTree:
        """The message trees of the expanded topics."""
        return self.query_one("#tree", MessageTree)

    # -- the live picture ----------------------------------------------------------------
    def _on_state(self, state: SourceState) -> None:
        if not self.released:
            self.repaint()

    def sample(self) -> None:
        """Take this second's rates and bandwidths."""
        self.source.sample()

    def repaint(self) -> None:
        """Rows filtered and sorted into the table, subscriptions to what is shown, trees, charts, status."""
        if self.released:
            return
        self.rows = self.source.rows(self.clock())
        if self.pending:
            self.resolve_pending()
        self.shown = sort_rows(filter_rows(self.rows, self.filter_text), self.sort_column, self.sort_reverse)
        table = self.table
        table.show(self.shown)
        self.source.want(self.wanted_topics())
        self.paint_plot()
        self.paint_detail()
        self.update_status()
        self.repaints += 1

    def wanted_topics(self) -> set[str]:
        """What the monitor subscribes to: the rows on screen, the expanded topics and the plotted ones."""
        return set(self.table.visible_topics()) | set(self.expanded) | self.source.plot.topics

    def resolve_pending(self) -> None:
        """Command-line names the master's topics now explain: a topic stays expanded, a field is plotted."""
        known = set(self.source.topics)
        for name in list(self.pending):
            if name in known:
                self.pending.remove(name)
                continue
            specs = expand_spec(name)
            fields = [split_spec(spec, known) for spec in specs]
            if any(f is None for f in fields):
                continue
            self.pending.remove(name)
            if name in self.expanded:
                self.expanded.remove(name)
                self.message_trees.set_topics(self.expanded)
            for topic, path in (f for f in fields if f is not None):
                try:
                    self.source.plot_field(topic, path)
                except PlotFieldError as exc:
                    self.say(str(exc))
            self.show_plot(True)

    def show_plot(self, show: bool) -> None:
        """Show or hide the plot panel."""
        self.plot_open = show
        panel = self.query_one("#plot", PlotPanel)
        if panel.display != show:
            panel.display = show
        self.paint_plot()

    def paint_plot(self) -> None:
        """Draw the plotted fields (when the panel is shown)."""
        if self.plot_open:
            self.query_one("#plot", PlotPanel).show(self.source.plot, self.clock())

    def row_of(self, topic: str) -> TopicRow | None:
        """The latest row of ``topic``."""
        return next((r for r in self.rows if r.name == topic), None)

    def topic_type(self, topic: str) -> str | None:
        """The type the master knows for ``topic``."""
        info = self.source.topics.get(topic)
        return info.type if info is not None else None

    def paint_detail(self) -> None:
        """The message trees of the expanded topics and the charts of the topic in focus."""
        detail = self.query_one("#detail")
        if detail.display != bool(self.expanded):
            detail.display = bool(self.expanded)
        if not self.expanded:
            return
        tree = self.message_trees
        for topic in self.expanded:
            row = self.row_of(topic)
            heading = f"{topic} [{row.type}]" if row is not None else f"{topic} (not published)"
            msg = None
            note = ""
            try:
                msg = self.source.latest(topic)
            except Exception as exc:  # a message we cannot decode is a note on its branch
                note = f"cannot decode: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}"
            if msg is None and not note:
                note = "(waiting for a message)" if row is None or row.liveness is not Liveness.NO_PUBLISHERS \
                    else "(no publishers)"
            elif row is not None and row.liveness is Liveness.STALE:
                note = "✖ stale: no messages lately"
            refused = self.source.refusals(topic)
            if refused and not note.startswith("cannot decode"):  # a publisher whose header gives no class
                said = f"✖ refused {refused[-1]}"
                note = said if msg is None else f"{note}  {said}".strip()
            tree.show_message(topic, heading, message_tree(msg) if msg is not None else None, note)
        focus = self.focus_topic()
        rates, bandwidths = self.source.history(focus) if focus else ([], [])
        self.query_one("#charts", Charts).show(focus, rates, bandwidths)

    def focus_topic(self) -> str | None:
        """The topic the charts are about: the tree's under its cursor when the tree has focus, else the table's."""
        if self.focused is self.message_trees:
            where = self.message_trees.cursor_topic_and_path()
            if where is not None:
                return where[0]
        return self.table.current_topic or (self.expanded[0] if self.expanded else None)

    def update_status(self) -> None:
        """The status line and the red problem line."""
        parts = [f"{len(self.rows)} topics", f"{len(self.shown)} shown", f"{len(self.source.subscribed)} subscribed",
                 f"sort {self.sort_column.value} {'↑' if self.sort_reverse else '↓'}"]
        if self.filter_text:
            parts.append(f"filter {self.filter_text!r}")
        running = [f"{r.topic} {r.rate:g} Hz" for r in self.repeaters.values() if r.running]
        if running:
            parts.append("publishing " + ", ".join(running))
        parts.append(self.source.state.text(marks=True))
        if self.notice:
            parts.append(self.notice)
        self.query_one("#status", Line).set(escape(" │ ".join(parts)))
        problem = ""
        if self.source.state.status is not MasterState.CONNECTED:
            problem = self.source.state.text()
            if self.source.state.status is MasterState.WAITING:
                problem += "; start one with `rostui core` (retrying)"
        elif self.rows and not self.shown:
            problem = f"no topic matches {self.filter_text!r}"
        banner = self.query_one("#banner", Static)
        if self._problem != problem:
            self._problem = problem
            banner.update(escape(problem))
            banner.display = bool(problem)

    def say(self, text: str) -> None:
        """A notice in the status line (until the next one)."""
        self.notice = text
        self.update_status()

    def refuse(self, text: str) -> None:
        """Why a key did nothing: in the status line, and whole in a toast (a long line is cut in the status)."""
        self.say(text)
        self.notify(text, severity="warning", timeout=6)

    # -- keys ------------------------------------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """The plot's keys act on the main screen only (in the field chooser, letters are not the app's).

        "/" is a type-ahead key (:attr:`KeysApp.TYPE_AHEAD_ACTIONS`): it is the app's only on the main screen,
        and never while the filter has the keyboard ("/" is part of topic names).

        Over a topic's view (Enter on an image) only help, quit and the palette are the app's.
        """
        if action in PLOT_ACTIONS and len(self.screen_stack) > 1:
            return False
        if action == "open_filter" and len(self.screen_stack) > 1 or self.typing_in_a_field(action):
            return False
        if action not in ("help", "quit", "command_palette") and isinstance(self.screen, ViewScreen):
            return False
        return True

    def action_sort_next(self) -> None:
        """s: sort by the next column."""
        self.sort_column = self.sort_column.next()
        self.repaint()

    def action_sort_reverse(self) -> None:
        """S: reverse the order."""
        self.sort_reverse = not self.sort_reverse
        self.repaint()

    def action_open_filter(self) -> None:
        """/: type a filter (name or type contains it); the table follows each keystroke."""
        focus_now(self.query_one("#filter", FilterInput))

    @on(Input.Changed, "#filter")
    def _filter_typed(self, event: Input.Changed) -> None:
        self.filter_text = event.value
        self.repaint()

    @on(Input.Submitted, "#filter")
    def _filter_done(self) -> None:
        self.close_filter(clear=False)

    def close_filter(self, *, clear: bool) -> None:
        """Leave the filter line (``clear``: and drop the filter)."""
        line = self.query_one("#filter", FilterInput)
        if clear:
            self.filter_text = ""
            line.value = ""
        self.table.focus()
        self.repaint()

    @on(TopicTable.Chosen)
    def _row_chosen(self, event: TopicTable.Chosen) -> None:
        if self.open_view(event.topic):
            return
        self.toggle_expanded(event.topic)

    def open_view(self, topic: str) -> bool:
        """Enter on a topic whose type has a view (an image...): show it over the table; False when none has."""
        msg_type = self.topic_type(topic)
        if msg_type is None or not viewable(msg_type):
            return False
        self.push_screen(ViewScreen([topic], lambda: self.source.node, self.topic_type))
        return True

    def toggle_expanded(self, topic: str) -> None:
        """Enter: show ``topic``'s newest message as a tree below the table (again: hide it)."""
        if topic in self.expanded:
            self.expanded.remove(topic)
        else:
            self.expanded.append(topic)
        self.message_trees.set_topics(self.expanded)
        self.repaint()

    def action_collapse(self) -> None:
        """x: hide the tree of the topic in focus."""
        topic = self.focus_topic()
        if topic in self.expanded:
            self.toggle_expanded(topic)

    def action_plot(self) -> None:
        """f: on a number in the tree, plot it (again: stop); elsewhere choose the topic's numeric fields."""
        where = self.message_trees.cursor_topic_and_path() if self.focused is self.message_trees else None
        if where is not None and where[1]:
            self.toggle_field(*where)
            return
        topic = where[0] if where is not None else self.table.current_topic
        if topic is None:
            self.say("f plots a field: select a topic first")
            return
        self.choose_fields(topic)

    def toggle_field(self, topic: str, path: str) -> None:
        """Plot ``topic``'s field ``path``, or stop plotting it when it is plotted."""
        if self.source.plot.remove_field(topic, path):
            self.say(f"stopped plotting {topic}/{path}")
        else:
            try:
                self.source.plot_field(topic, path)
            except PlotFieldError as exc:
                self.refuse(str(exc))
                return
            self.say(f"plotting {topic}/{path}")
            self.plot_open = True
        self.show_plot(self.plot_open)
        self.repaint()

    def choose_fields(self, topic: str) -> None:
        """Open the chooser of ``topic``'s numeric fields (known from its newest message)."""
        try:
            msg = self.source.latest(topic)
        except Exception as exc:  # an undecodable message has no fields to offer
            self.say(f"cannot decode {topic}: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}")
            return
        if msg is None:
            self.refuse(f"no message on {topic} yet: its fields are read from one (is it published?)")
            self.source.want(self.wanted_topics() | {topic})
            return
        fields = [(path, f"{check_numeric(msg, topic, path):.6g}") for path in numeric_fields(msg)]
        if not fields:
            self.refuse(f"{topic} ({getattr(msg, '_type', '?')}) has no numeric fields to plot")
            return
        plotted = [s.path for s in self.source.plot.series if s.topic == topic]

        def chosen(paths: list[str] | None) -> None:
            if paths is None:
                return
            plot = self.source.plot
            for series in [s for s in plot.series if s.topic == topic and s.path not in paths]:
                plot.remove_field(topic, series.path)
            for path in paths:
                try:
                    self.source.plot_field(topic, path)
                except PlotFieldError as exc:  # a newer message with a shorter array
                    self.say(str(exc))
                    return
            self.say(f"plotting {len(paths)} field{'s' if len(paths) != 1 else ''} of {topic}")
            self.show_plot(self.plot_open or bool(paths))
            self.repaint()

        self.push_screen(FieldChooser(topic, fields, plotted), chosen)

    def action_toggle_plot(self) -> None:
        """v: show or hide the plot panel."""
        self.show_plot(not self.plot_open)

    def action_window_longer(self) -> None:
        """+: show a longer time window."""
        self.say(f"plot window {self.source.plot.longer():g} s")
        self.show_plot(True)

    def action_window_shorter(self) -> None:
        """-: show a shorter time window."""
        self.say(f"plot window {self.source.plot.shorter():g} s")
        self.show_plot(True)

    def action_pause_plot(self) -> None:
        """space: freeze the plot (points keep being received and counted), or follow them again."""
        paused = self.source.plot.toggle_pause(self.clock())
        self.say("plot paused (space resumes)" if paused else "plot resumed")
        self.show_plot(True)

    def action_publish(self) -> None:
        """p: open the publish editor for the topic in focus."""
        topic = self.focus_topic() or ""
        self.push_screen(PublishEditor(self, topic, self.topic_type(topic) or "" if topic else ""))

    # -- publishing (called by the editor) -------------------------------------------------
    def _message(self, editor: PublishEditor) -> tuple[str, type[Message], Message]:
        topic = check_topic(editor.topic)
        cls = editor.msg_class
        if cls is None or cls._type != editor.type_name:
            cls, _ = message_template(editor.type_name)
            editor.msg_class = cls
        known = self.topic_type(topic)
        if known and known != "*" and known != cls._type:
            raise PublishError(f"{topic} is published as {known}, not {cls._type}")
        return topic, cls, message_from_text(cls, editor.yaml_text)

    def send_once(self, editor: PublishEditor) -> None:
        """Publish the editor's message once, latched (as ``rostopic pub -1`` does)."""
        try:
            topic, cls, msg = self._message(editor)
        except PublishError as exc:
            editor.say(str(exc), error=True)
            return

        async def send() -> None:
            try:
                await self.source.publish(topic, cls, msg, latch=True)
            except Exception as exc:  # no master, or the master refused: said in the editor
                editor.say(f"not sent: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}", error=True)
                return
            editor.say(f"sent 1 message on {topic}")
            self.say(f"sent 1 message on {topic}")

        self.run_worker(send(), group="publish", exit_on_error=False)

    def toggle_repeat(self, editor: PublishEditor) -> None:
        """Publish the editor's message at its rate, or stop the topic's repeating publisher."""
        try:
            topic = check_topic(editor.topic)
        except PublishError as exc:
            editor.say(str(exc), error=True)
            return
        running = self.repeaters.get(topic)
        if running is not None and running.running:
            running.stop()
            editor.say(f"stopped publishing {topic} ({running.sent} sent)")
            self.say(f"stopped publishing {topic}")
            return
        try:
            rate = parse_rate(editor.rate_text)
            if rate is None:
                raise PublishError("type a rate in Hz to publish repeatedly (ctrl+s sends once)")
            topic, cls, msg = self._message(editor)
        except PublishError as exc:
            editor.say(str(exc), error=True)
            return
        repeater = Repeater(topic, rate, lambda: self.source.publish(topic, cls, msg, latch=False))
        repeater.start()
        self.repeaters[topic] = repeater
        editor.say(f"publishing {topic} at {rate:g} Hz (ctrl+r stops)")
        self.update_status()

    # -- the end ----------------------------------------------------------------------
    async def release(self) -> None:
        """Stop publishing, unsubscribe, leave the master."""
        for repeater in self.repeaters.values():
            repeater.stop()
        await self.source.stop()


def run_app(topics: Sequence[str], *, period: float = 1.0) -> int:
    """Run :class:`MonitorApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui monitor", "use `rostui topic hz/bw/echo` without one"):
        return 1
    app = MonitorApp(topics, period=period)
    app.run()
    return app.return_code or 0
