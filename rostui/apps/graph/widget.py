"""GraphView: a scrollable Line API widget that shows a :class:`~rostui.apps.graph.canvas.Canvas`.

Only the visible rows are built and styled.  Colours come from component
classes (see ``app.tcss``): nodes, topics, groups, edges, edge labels, the selection,
its neighbours and edges, and the "new" / "gone" marks of live changes.  A
new vertex gets a ``+`` in its top border, a vanished one an ``×``.
"""

from __future__ import annotations

from typing import Mapping

from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.actions import SkipAction
from textual.geometry import Region, Size
from textual.message import Message
from textual.scroll_view import ScrollView
from textual.strip import Strip

from rostui.apps.graph.canvas import EMPTY, Canvas
from rostui.apps.widgets.terminal_colors import color_system, readable
from rostui.models.graph.live import Mark
from rostui.models.graph.view import Kind, kind_of

__all__ = ["GraphView"]

_MARKERS = {Mark.NEW: "+", Mark.GONE: "×"}

#: Columns and lines an arrow key scrolls the graph.
SCROLL_COLUMNS = 8
SCROLL_LINES = 3


class GraphView(ScrollView, can_focus=True):
    """The graph: boxes and arrows on a canvas larger than the screen; click a box to select it."""

    COMPONENT_CLASSES = {
        "graph--node", "graph--topic", "graph--group", "graph--edge", "graph--edge-hot", "graph--label",
        "graph--selected", "graph--neighbour", "graph--new", "graph--gone",
    }

    DEFAULT_CSS = """
    GraphView { background: $surface; }
    """

    class Clicked(Message):
        """A box (or empty space: ``vertex`` None) was clicked."""

        def __init__(self, vertex: str | None) -> None:
            self.vertex = vertex
            super().__init__()

    # -- keys: arrows scroll a few cells at a time (one column a press took 45 presses across the book's graph)
    def action_scroll_left(self) -> None:
        """← scrolls :data:`SCROLL_COLUMNS` columns left."""
        if not self.allow_horizontal_scroll:
            raise SkipAction()
        self.scroll_relative(x=-SCROLL_COLUMNS, animate=False)

    def action_scroll_right(self) -> None:
        """→ scrolls :data:`SCROLL_COLUMNS` columns right."""
        if not self.allow_horizontal_scroll:
            raise SkipAction()
        self.scroll_relative(x=SCROLL_COLUMNS, animate=False)

    def action_scroll_up(self) -> None:
        """↑ scrolls :data:`SCROLL_LINES` lines up."""
        if not self.allow_vertical_scroll:
            raise SkipAction()
        self.scroll_relative(y=-SCROLL_LINES, animate=False)

    def action_scroll_down(self) -> None:
        """↓ scrolls :data:`SCROLL_LINES` lines down."""
        if not self.allow_vertical_scroll:
            raise SkipAction()
        self.scroll_relative(y=SCROLL_LINES, animate=False)

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.canvas: Canvas | None = None
        self.marks: Mapping[str, Mark] = {}
        self.selected: str | None = None
        self._hot: set[str] = set()
        self._box_tops: dict[int, list[tuple[int, str]]] = {}

    # -- content ------------------------------------------------------------------
    def show(self, canvas: Canvas | None) -> None:
        """Display ``canvas`` (None: nothing)."""
        self.canvas = canvas
        self._box_tops = {}
        if canvas is not None:
            for vid, box in canvas.boxes.items():
                self._box_tops.setdefault(box.y, []).append((box.x, vid))
        self._update_hot()
        self.virtual_size = Size(canvas.width, canvas.height) if canvas else Size(0, 0)
        self.refresh()

    def overflows(self) -> bool:
        """True when the drawing is wider or taller than the widget shows (the arrow keys scroll it)."""
        shown = self.scrollable_content_region
        if self.canvas is None or not self.display or not shown.area:
            return False
        return self.canvas.width > shown.width or self.canvas.height > shown.height

    def set_marks(self, marks: Mapping[str, Mark]) -> None:
        """Which vertices show as new or gone."""
        if dict(marks) != dict(self.marks):
            self.marks = dict(marks)
            self.refresh()

    def select(self, vertex: str | None) -> None:
        """Highlight ``vertex`` with its edges and neighbours (None: no selection)."""
        self.selected = vertex
        self._update_hot()
        self.refresh()

    def _update_hot(self) -> None:
        self._hot = set()
        if self.canvas is None or self.selected is None:
            return
        for a, b in self.canvas.edges:
            if self.selected in (a, b):
                self._hot.update((a, b))

    def scroll_to_vertex(self, vertex: str, *, animate: bool = False) -> None:
        """Scroll so that ``vertex``'s box is on screen (centred when it was not)."""
        if self.canvas is None or vertex not in self.canvas.boxes:
            return
        box = self.canvas.boxes[vertex]
        self.scroll_to_region(Region(box.x, box.y, box.w, box.h), animate=animate, center=True, force=True)

    def vertex_order(self) -> list[str]:
        """Vertices in reading order: by layer column, then top to bottom."""
        if self.canvas is None:
            return []
        boxes = self.canvas.boxes
        return sorted(boxes, key=lambda v: (boxes[v].x, boxes[v].y, v))

    # -- drawing --------------------------------------------------------------------
    def render_line(self, y: int) -> Strip:
        """One screen row: the canvas row at the scroll position, styled cell run by cell run."""
        scroll_x, scroll_y = self.scroll_offset
        width = self.scrollable_content_region.width
        row_y = y + scroll_y
        base = self.rich_style
        canvas = self.canvas
        if canvas is None or row_y >= canvas.height:
            return Strip.blank(width, base)
        chars, owners = canvas.row(row_y)
        chars = list(chars)
        for x, vid in self._box_tops.get(row_y, ()):
            mark = self.marks.get(vid)
            if mark is not None and canvas.boxes[vid].w > 2:
                chars[x + 1] = _MARKERS[mark]
        end = min(scroll_x + width, canvas.width)
        styles = self._styles(base)
        segments: list[Segment] = []
        x = scroll_x
        while x < end:
            key = self._style_key(owners[x])
            start = x
            x += 1
            while x < end and self._style_key(owners[x]) == key:
                x += 1
            segments.append(Segment("".join(chars[start:x]), styles[key]))
        strip = Strip(segments, end - scroll_x if end > scroll_x else 0)
        return strip.extend_cell_length(width, base)

    def _style_key(self, owner: int) -> str:
        canvas = self.canvas
        assert canvas is not None
        if owner == EMPTY:
            return "blank"
        found = canvas.edge_of(owner)
        if found is not None:
            a, b = canvas.edges[found[0]]
            if self.selected is not None and self.selected in (a, b):
                return "edge-hot"
            if self.marks.get(a) is Mark.GONE or self.marks.get(b) is Mark.GONE:
                return "gone"
            return "label" if found[1] else "edge"
        vid = canvas.vertex_ids[owner]
        if vid == self.selected:
            return "selected"
        mark = self.marks.get(vid)
        if mark is not None:
            return mark.value
        if vid in self._hot:
            return "neighbour"
        return {Kind.NODE: "node", Kind.TOPIC: "topic", Kind.GROUP: "group"}[kind_of(vid)]

    def _styles(self, base: Style) -> dict[str, Style]:
        names = ("node", "topic", "group", "edge", "edge-hot", "label", "selected", "neighbour", "new", "gone")
        system = color_system(self.app.console.color_system)
        styles = {name: readable(base + self.get_component_rich_style(f"graph--{name}", partial=True), system)
                  for name in names}
        styles["blank"] = base
        return styles

    # -- input ----------------------------------------------------------------------
    def on_click(self, event: events.Click) -> None:
        """Select the box under the pointer (or nothing)."""
        if self.canvas is None:
            return
        scroll_x, scroll_y = self.scroll_offset
        self.post_message(self.Clicked(self.canvas.owner_at(event.x + scroll_x, event.y + scroll_y)))
