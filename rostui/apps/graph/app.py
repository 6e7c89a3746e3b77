"""GraphApp: rqt_graph in the terminal, live, with filters, search, focus and details.

The app polls the master's ``getSystemState`` every ``period`` seconds,
turns the registrations into the chosen view (:mod:`rostui.models.graph.view`),
lays it out in a thread (:mod:`rostui.models.graph.layout`) and draws it with
:class:`~rostui.apps.graph.widget.GraphView`.  A view whose vertices and edges
did not change keeps its drawing exactly; new and vanished vertices are
marked for a few refreshes.  When the master stops answering the last graph
stays on screen under a red line saying so, and polling goes on until the
master is back.
"""

from __future__ import annotations

import asyncio
from collections import OrderedDict
from pathlib import Path
from typing import Any

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, VerticalScroll
from textual.widgets import Input, Static
from textual.worker import Worker

from rostui.apps.graph.canvas import Canvas, draw, layout_view
from rostui.apps.graph.widget import GraphView
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.bar_text import join_parts
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.core.network import master_uri_from_env
from rostui.models.graph.hidden import explain_empty
from rostui.models.graph.labels import EdgeLabels, LabelStyle, edge_labels
from rostui.models.graph.layout import Layout, LayoutHint
from rostui.models.graph.live import KEEP_REFRESHES, LiveGraph, Mark
from rostui.models.graph.model import RosGraph
from rostui.models.graph.search import fuzzy_rank
from rostui.models.graph.source import GraphSource, RateReport, SourceError
from rostui.models.graph.view import (
    FilterError, GraphOptions, Kind, ViewGraph, ViewMode, book_setup, build_view, focus_view, kind_of, name_of,
    namespace_of,
)
from rostui.tools.node import NodeInfo

__all__ = ["GraphApp", "run_app", "KEYS"]

#: Key help shown under the graph: the book's keys first (b, v, d), where an 80-column line still shows them.
KEYS = key_line("b book  v view  d debug  / search  Tab next  Enter info  s sinks  l leaves  g group  "
                "i/x filter  f focus ±  r rate")
#: On the status line while the drawing does not fit the screen.
SCROLL_HINT = "arrows scroll"
#: Layouts kept for views seen lately (switching back redraws them exactly, at once).
CACHE_SIZE = 8
#: Seconds a topic is listened to when its rate is measured.
RATE_SECONDS = 3.0
#: Prompts of the input line.
PROMPTS = {"search": "search: ", "include": "include regex: ", "exclude": "exclude regex: "}


class GraphApp(ReleasesOnExit, KeysApp):
    """The ROS graph of the master at ``master_uri`` (ROS_MASTER_URI by default), refreshed every ``period`` s.

    A topic's rate is measured over ``rate_seconds``; "new" and "gone" marks
    last ``mark_refreshes`` refreshes.
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui graph"
    KEY_NOTES = (("click", "select a node or topic"),)

    TYPE_AHEAD_ACTIONS = frozenset({"prompt"})
    BINDINGS = [
        Binding("q", "quit", "quit"),
        Binding("v", "next_view", "next view"),
        Binding("1", "set_view('nodes')", "nodes only", show=False),
        Binding("2", "set_view('active')", "nodes/topics (active)", show=False),
        Binding("3", "set_view('all')", "nodes/topics (all)", show=False),
        Binding("d", "toggle_option('hide_debug')", "hide debug"),
        Binding("s", "toggle_option('hide_dead_sinks')", "hide dead sinks"),
        Binding("l", "toggle_option('hide_leaf_topics')", "hide leaf topics"),
        Binding("g", "toggle_option('group_namespaces')", "group namespaces"),
        Binding("b", "book", "book's setup"),
        Binding("i", "prompt('include')", "include regex", priority=True),
        Binding("x", "prompt('exclude')", "exclude regex", priority=True),
        Binding("slash", "prompt('search')", "search", priority=True),
        Binding("f", "focus_mode", "focus on the selection"),
        Binding("plus,equals_sign", "hops(1)", "more hops", show=False),
        Binding("minus", "hops(-1)", "fewer hops", show=False),
        Binding("tab", "step(1)", "select next", priority=True),
        Binding("shift+tab", "step(-1)", "select previous", priority=True),
        Binding("enter", "activate", "details / expand"),
        Binding("space", "expand", "expand/collapse", show=False),
        Binding("r", "rate", "measure the topic's rate"),
        Binding("escape", "escape", "back: close prompt, leave focus, unselect", priority=True),
    ]

    def __init__(self, options: GraphOptions | None = None, *, master_uri: str | None = None,
                 period: float = 1.5, rate_seconds: float = RATE_SECONDS,
                 mark_refreshes: int = KEEP_REFRESHES) -> None:
        super().__init__()
        self.options = options or GraphOptions()
        self.master_uri = master_uri_from_env(master_uri)
        self.period = period
        self.rate_seconds = rate_seconds
        self.source = GraphSource(self.master_uri)
        self.live = LiveGraph(mark_refreshes)
        self.polls = 0
        self.master_ok: bool | None = None
        self.master_error = ""
        self.filter_error = ""
        self.notice = ""
        self._empty_text = ""
        self.focus_center: str | None = None
        self.hops = 1
        self.selected: str | None = None
        self.view_graph: ViewGraph | None = None
        self.shown: ViewGraph | None = None
        self.node_infos: dict[str, NodeInfo | str] = {}
        self.rates: dict[str, RateReport | str] = {}
        self._layouts: OrderedDict[tuple, tuple[Layout, Canvas]] = OrderedDict()
        self._hint: tuple[ViewMode, LayoutHint] | None = None
        self._layout_seq = 0
        self._prompt: str | None = None
        self._prompt_before = ""
        self._polling = False
        self._poll_worker: Worker[None] | None = None

    # -- composition -------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Status line, problem line, graph beside the details pane, prompt, key help."""
        yield Static(id="status")
        yield Static(id="banner")
        with Horizontal(id="main"):
            yield Static(id="empty")
            yield GraphView(id="graph")
            with VerticalScroll(id="details-pane"):
                yield Static(id="details")
        yield LineInput(id="prompt")
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Poll now and every ``period`` seconds; quit cleanly on SIGTERM and SIGHUP."""
        quit_on_signals(self)
        self.query_one("#details-pane").display = False
        self.query_one("#prompt", Input).display = False
        self.query_one("#banner").display = False
        self.query_one("#empty").display = False
        self.graph_view.focus()
        self.update_status()
        self.set_interval(self.period, self.poll)
        self.poll()

    def on_resize(self) -> None:
        """A new width may fit longer (or need shorter) edge labels: draw again."""
        if self.view_graph is not None:
            self.recompute()
        self.call_after_refresh(self.update_status)  # whether the drawing still fits

    @property
    def graph_view(self) -> GraphView:
        """The graph widget."""
        return self.query_one("#graph", GraphView)

    # -- polling -------------------------------------------------------------------------
    def poll(self) -> None:
        """Ask the master for the graph (skipped while the previous poll still runs)."""
        if not self._polling and not self.released:
            self._polling = True
            # the function, not a coroutine object: a worker cancelled before it starts leaves nothing unawaited
            self._poll_worker = self.run_worker(self._poll, group="poll", exit_on_error=False)

    async def _poll(self) -> None:
        try:
            graph = await self.source.fetch()
        except SourceError as exc:
            self.master_ok = False
            self.master_error = f"{exc}; retrying every {self.period:g} s (last graph shown)"
            self.update_status()
            return
        finally:
            self._polling = False
        back = self.master_ok is False
        self.master_ok = True
        self.master_error = ""
        if back:
            self.notice = "master is back"
        self.accept(graph)

    def accept(self, graph: RosGraph) -> None:
        """Take a new snapshot of the registrations and redraw what changed."""
        self.live.update(graph)
        self.polls += 1
        self.recompute()
        if self.selected is not None:
            self.show_details()

    # -- view pipeline ------------------------------------------------------------------------
    def recompute(self) -> None:
        """Apply view, filters and focus to the live graph; lay it out again only when it changed."""
        try:
            view = build_view(self.live.graph, self.options)
        except FilterError as exc:
            self.filter_error = str(exc)
            self.update_status()
            return
        self.filter_error = ""
        if self.focus_center is not None:
            view = focus_view(view, self.focus_center, self.hops)
        self.view_graph = view
        signature = (view.signature(), self.drawing_width())
        cached = self._layouts.get(signature)
        if cached is not None:
            self._layouts.move_to_end(signature)
            self._show_layout(view, *cached)
        else:
            self._layout_seq += 1
            self.run_worker(self._lay_out(view, signature, self._layout_seq), group="layout", exit_on_error=False)
        self.update_status()

    def drawing_width(self) -> int:
        """Columns the drawing has on screen with the details pane closed (edge labels are abbreviated past it)."""
        return max(self.size.width - 1, 20)

    async def _lay_out(self, view: ViewGraph, signature: tuple, seq: int) -> None:
        hint = self._hint[1] if self._hint is not None and self._hint[0] is self.options.view else None
        width = signature[1]
        labelled = self.options.view is ViewMode.NODES

        def compute() -> tuple[Layout, Canvas]:
            return lay_out(view, hint, width, labelled=labelled)

        layout, canvas = await asyncio.to_thread(compute)
        self._layouts[signature] = (layout, canvas)
        while len(self._layouts) > CACHE_SIZE:
            self._layouts.popitem(last=False)
        if seq == self._layout_seq:
            self._show_layout(view, layout, canvas)

    def _show_layout(self, view: ViewGraph, layout: Layout, canvas: Canvas) -> None:
        self._hint = (self.options.view, layout.hint())
        graph = self.graph_view
        if graph.canvas is not canvas:
            graph.show(canvas)
        self.shown = view
        graph.set_marks(self.view_marks(view))
        if self.selected is not None and self.selected not in view.vertices:
            graph.select(None)
        elif graph.selected != self.selected:
            graph.select(self.selected)
        self.update_status()

    def view_marks(self, view: ViewGraph) -> dict[str, Mark]:
        """Live marks of the vertices in ``view`` (a group is new when a member is, gone when all are)."""
        marks = self.live.marks()
        out: dict[str, Mark] = {}
        for vid, vertex in view.vertices.items():
            if vertex.kind is Kind.GROUP:
                inner = [marks.get(m) for m in vertex.members]
                if Mark.NEW in inner:
                    out[vid] = Mark.NEW
                elif inner and all(m is Mark.GONE for m in inner):
                    out[vid] = Mark.GONE
            elif vid in marks:
                out[vid] = marks[vid]
        return out

    @property
    def settled(self) -> bool:
        """True when the drawing shows the current view (no layout pending)."""
        return self.view_graph is not None and self.shown is not None and \
            self.shown.signature() == self.view_graph.signature()

    # -- status ------------------------------------------------------------------------------
    def update_status(self) -> None:
        """The status line (view, options, counts, master) and the red problem line."""
        view = self.view_graph
        counts = ""
        if view is not None:
            kinds = [v.kind for v in view.vertices.values()]
            topics = kinds.count(Kind.TOPIC)
            if self.options.view is ViewMode.NODES:  # the topics written on the edges
                topics = len({t for ts in view.edge_topics.values() for t in ts})
            counts = f"{_count(kinds.count(Kind.NODE), 'node')} · {_count(topics, 'topic')}"
            if Kind.GROUP in kinds:
                counts += f" · {_count(kinds.count(Kind.GROUP), 'group')}"
        parts = [self.options.describe()]
        if self.focus_center is not None:
            parts.append(f"focus {name_of(self.focus_center)} ±{self.hops}")
        if counts:
            parts.append(counts)
        state = {None: "… master", True: "● master", False: "✖ master"}[self.master_ok]
        parts.append(state)
        if self.graph_view.overflows():
            parts.append(SCROLL_HINT)
        if self.notice:
            parts.append(self.notice)
        status = self.query_one("#status", Static)
        status.update(join_parts(parts, status.content_region.width))
        problem = self.master_error or self.filter_error
        banner = self.query_one("#banner", Static)
        banner.update(problem)
        banner.display = bool(problem)
        self.update_empty()

    def update_empty(self) -> None:
        """In place of an empty drawing: what the master has, which filter hides it, and the key that shows it."""
        view = self.view_graph
        empty = self.query_one("#empty", Static)
        explain = bool(self.master_ok) and view is not None and not view.vertices
        if explain:
            lines = explain_empty(self.live.current, self.options).lines()
            if self.focus_center is not None:
                lines.append(f"Focus on {name_of(self.focus_center)} is on: press f to leave it.")
            text = "\n\n".join(lines)
            if text != self._empty_text:
                self._empty_text = text
                shown = Text(text)  # names and patterns are shown as typed, never read as markup
                shown.highlight_regex(r"(?:Press|press) \S+|\([a-z]\)", "bold")
                empty.update(shown)
        else:
            self._empty_text = ""
        if empty.display != explain:
            empty.display = explain
            self.graph_view.display = not explain
            if not explain and self.focused is None:
                self.graph_view.focus()

    # -- selection and details -----------------------------------------------------------
    def select(self, vertex: str | None, *, scroll: bool = True) -> None:
        """Select ``vertex`` (None: clear), show its details and bring it on screen."""
        self.selected = vertex
        self.graph_view.select(vertex)
        pane = self.query_one("#details-pane")
        resized = pane.display != (vertex is not None)
        pane.display = vertex is not None
        if resized:  # the drawing's share of the screen changed: whether it still fits, once laid out again
            self.call_after_refresh(self.update_status)
        if vertex is None:
            return
        if scroll:
            self.graph_view.scroll_to_vertex(vertex)
            if resized:
                self.call_after_refresh(self.graph_view.scroll_to_vertex, vertex)
        if kind_of(vertex) is Kind.NODE:
            self.node_infos.pop(vertex, None)
            self.run_worker(self._fetch_node_info(vertex), group="node-info", exclusive=True, exit_on_error=False)
        self.show_details()

    async def _fetch_node_info(self, vertex: str) -> None:
        self.node_infos[vertex] = "contacting node…"
        self.show_details()
        info = await self.source.node_info(name_of(vertex))
        self.node_infos[vertex] = info
        if self.selected == vertex:
            self.show_details()

    def show_details(self) -> None:
        """Fill the details pane for the selection."""
        if self.selected is None:
            return
        self.query_one("#details", Static).update(self.details_text(self.selected))

    def details_text(self, vertex: str) -> str:
        """What the details pane says about ``vertex``."""
        graph = self.live.current
        name = name_of(vertex)
        kind = kind_of(vertex)
        if kind is Kind.GROUP:
            members = self.view_graph.vertices[vertex].members if self.view_graph and \
                vertex in self.view_graph.vertices else ()
            lines = [f"Namespace {name}", "", "Members:"] + [f" * {name_of(m)}" for m in members]
            return "\n".join(lines + ["", "Enter or space: expand"])
        if kind is Kind.TOPIC:
            gone = name not in graph.publishers and name not in graph.subscribers
            lines = [f"Topic {name}"]
            if gone:
                lines += ["", f"✖ {name} is gone: nobody publishes or subscribes to it any more"]
                return "\n".join(lines)
            lines += [f"Type: {graph.topic_type(name)}", ""]
            lines += _section("Publishers", graph.publishers.get(name, ()))
            lines += _section("Subscribers", graph.subscribers.get(name, ()))
            rate = self.rates.get(vertex)
            if rate is None:
                lines.append("Rate: press r to measure")
            elif isinstance(rate, str):
                lines.append(f"Rate: {rate}")
            else:
                lines.append(f"Rate: {rate.text()}")
            return "\n".join(lines)
        lines = [f"Node {name}"]
        if name not in graph.nodes():
            lines += ["", f"✖ {name} is gone: it is no longer registered with the master"]
            return "\n".join(lines)
        lines.append("")
        lines += _section("Publications", [f"{t} [{graph.topic_type(t)}]" for t in graph.publications_of(name)])
        lines += _section("Subscriptions", [f"{t} [{graph.topic_type(t)}]" for t in graph.subscriptions_of(name)])
        lines += _section("Services", graph.services_of(name))
        info = self.node_infos.get(vertex)
        if isinstance(info, str):
            lines.append(info)
        elif info is not None:
            if info.uri:
                lines.append(f"URI: {info.uri}")
            if info.pid is not None:
                lines.append(f"Pid: {info.pid}")
            if info.error:
                lines.append(f"✖ {info.error.removeprefix('ERROR: ')}")
        return "\n".join(lines)

    # -- actions ---------------------------------------------------------------------------
    def set_options(self, options: GraphOptions) -> None:
        """Use ``options`` and redraw."""
        self.options = options
        self.notice = ""
        self.recompute()

    def action_next_view(self) -> None:
        """v: Nodes only -> Nodes/Topics (active) -> Nodes/Topics (all) -> ..."""
        self.set_options(self.options.with_(view=self.options.view.next()))

    def action_set_view(self, view: str) -> None:
        """1/2/3: a view by name."""
        self.set_options(self.options.with_(view=ViewMode(view)))

    def action_toggle_option(self, flag: str) -> None:
        """Flip one of the hide/group boxes."""
        self.set_options(self.options.with_(**{flag: not getattr(self.options, flag)}))

    def action_book(self) -> None:
        """b: the book's preferred setup (Nodes/Topics (all), only Hide debug checked), filters cleared."""
        self.focus_center = None
        self.set_options(book_setup())
        self.notice = "the book's setup"
        self.update_status()

    def action_focus_mode(self) -> None:
        """f: show only the selection and its neighbours (again: show everything)."""
        if self.focus_center is not None:
            self.focus_center = None
        elif self.selected is not None:
            self.focus_center = self.selected
        else:
            self.notice = "select a node or topic first (Tab, click or /)"
        self.recompute()

    def action_hops(self, delta: int) -> None:
        """+/-: neighbours this many more (or fewer) hops away in focus mode."""
        self.hops = max(1, self.hops + delta)
        if self.focus_center is not None:
            self.recompute()
        else:
            self.update_status()

    def action_step(self, step: int) -> None:
        """Tab/Shift+Tab: select the next/previous box in reading order."""
        if self._prompt is not None:
            return
        order = self.graph_view.vertex_order()
        if not order:
            return
        if self.selected in order:
            index = (order.index(self.selected) + step) % len(order)
        else:
            index = 0 if step > 0 else len(order) - 1
        self.select(order[index])

    def action_activate(self) -> None:
        """Enter: expand a collapsed group, or refresh the details of a node or topic."""
        if self.selected is None:
            return
        if kind_of(self.selected) is Kind.GROUP:
            self.action_expand()
        else:
            self.select(self.selected, scroll=False)

    def action_expand(self) -> None:
        """Space: expand the selected group, or collapse the namespace of the selected member."""
        if self.selected is None or not self.options.group_namespaces:
            return
        name = name_of(self.selected)
        if kind_of(self.selected) is Kind.GROUP:
            self.set_options(self.options.with_(expanded=self.options.expanded | {name}))
            return
        namespace = namespace_of(name)
        if namespace is not None and namespace in self.options.expanded:
            self.selected = f"g:{namespace}"
            self.set_options(self.options.with_(expanded=self.options.expanded - {namespace}))
            self.select(self.selected)

    def action_rate(self) -> None:
        """r: listen to the selected topic for a few seconds and show its rate."""
        if self.selected is None or kind_of(self.selected) is not Kind.TOPIC:
            self.notice = "select a topic to measure its rate"
            self.update_status()
            return
        self.run_worker(self._measure(self.selected), group="rate", exit_on_error=False)

    async def _measure(self, vertex: str) -> None:
        self.rates[vertex] = f"measuring for {self.rate_seconds:g} s…"
        self.show_details()
        try:
            self.rates[vertex] = await self.source.measure_rate(name_of(vertex), self.rate_seconds)
        except SourceError as exc:
            self.rates[vertex] = f"✖ {exc}"
        self.show_details()

    def action_prompt(self, mode: str) -> None:
        """/, i, x: type a search, an include regex or an exclude regex (Enter keeps it, Esc undoes it)."""
        prompt = self.query_one("#prompt", Input)
        self._prompt = mode
        self._prompt_before = {"search": "", "include": self.options.include,
                               "exclude": self.options.exclude}[mode]
        prompt.placeholder = PROMPTS[mode]
        prompt.border_title = PROMPTS[mode]
        prompt.value = self._prompt_before
        prompt.display = True
        focus_now(prompt)

    @on(Input.Changed, "#prompt")
    def _typed(self, event: Input.Changed) -> None:
        self.apply_prompt(event.value)

    def apply_prompt(self, value: str) -> None:
        """Apply what the prompt holds: jump to the best match, or filter."""
        if self._prompt == "search":
            self.search(value)
        elif self._prompt in ("include", "exclude"):
            self.options = self.options.with_(**{self._prompt: value})
            self.recompute()

    def search(self, query: str) -> str | None:
        """Select the vertex whose name best matches ``query`` (fuzzy); returns it."""
        if not query or self.view_graph is None:
            return None
        names = {v.name: vid for vid, v in self.view_graph.vertices.items()}
        best = fuzzy_rank(query, names, limit=1)
        if not best:
            self.notice = f"no match for {query!r}"
            self.update_status()
            return None
        self.notice = ""
        self.select(names[best[0]])
        return names[best[0]]

    @on(Input.Submitted, "#prompt")
    def _submitted(self, event: Input.Submitted) -> None:
        self._close_prompt()

    def _close_prompt(self) -> None:
        self._prompt = None
        prompt = self.query_one("#prompt", Input)
        prompt.display = False
        self.graph_view.focus()

    def action_escape(self) -> None:
        """Esc: undo and close the prompt, else leave focus mode, else clear the selection."""
        if self._prompt is not None:
            if self._prompt in ("include", "exclude"):
                self.options = self.options.with_(**{self._prompt: self._prompt_before})
                self.recompute()
            self._close_prompt()
        elif self.focus_center is not None:
            self.focus_center = None
            self.recompute()
        else:
            self.select(None)

    @on(GraphView.Clicked)
    def _clicked(self, event: GraphView.Clicked) -> None:
        self.select(event.vertex, scroll=False)

    async def release(self) -> None:
        """Close the connection to the master."""
        await self.source.close()


def lay_out(view: ViewGraph, hint: LayoutHint | None, width: int, *,
            labelled: bool = True) -> tuple[Layout, Canvas]:
    """Lay ``view`` out and draw it; ``labelled`` (the nodes-only view): with topic names on its edges.

    The widest labels that fit in ``width`` columns: full topic names
    first, then abbreviations, then numbered keys; when none fits, the
    narrowest drawing (the graph scrolls).  A graph too wide without any
    label (a big one) goes straight to numbered keys: one layout, not three.
    """
    if not labelled or not view.edge_topics:
        layout = layout_view(view, hint)
        return layout, draw(view, layout)
    styles = list(LabelStyle)
    if layout_view(view, hint).width > width:  # too wide even bare: only the narrowest labels can help
        styles = [LabelStyle.KEYS]
    best: tuple[Layout, EdgeLabels] | None = None
    for style in styles:
        labels = edge_labels(view, style)
        layout = layout_view(view, hint, labels.lines)
        if best is None or layout.width < best[0].width:
            best = (layout, labels)
        if layout.width <= width:
            break
    assert best is not None
    return best[0], draw(view, best[0], best[1])


def _count(number: int, noun: str) -> str:
    """``1 node``, ``2 nodes``."""
    return f"{number} {noun}" if number == 1 else f"{number} {noun}s"


def _section(title: str, items: Any) -> list[str]:
    items = list(items)
    if not items:
        return [f"{title}: None", ""]
    return [f"{title}:"] + [f" * {item}" for item in items] + [""]


def run_app(options: GraphOptions, *, period: float = 1.5) -> int:
    """Run :class:`GraphApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui graph", "use `rostui graph --dot` without one"):
        return 1
    app = GraphApp(options, period=period)
    app.run()
    return app.return_code or 0
