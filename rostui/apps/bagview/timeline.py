"""The timeline: one row per topic with its message density over the bag, a time ruler and the cursor.

Rows show whether the topic is published (``●``) or only browsed (``○``), its
name, its message count and a density strip (block glyphs scaled to the
topic's busiest slice). The cursor is a highlighted column through every
strip; the ruler marks it with ``▼``. A click in the strips seeks there; a
click on a name selects that topic.
"""

from __future__ import annotations

from typing import ClassVar

from rich.text import Text
from textual import events
from textual.message import Message
from textual.widget import Widget

from rostui.apps.widgets.terminal_colors import color_system, readable
from rostui.core.bag.index import BagIndex

GLYPHS = " ▁▂▃▄▅▆▇█"
COUNT_WIDTH = 7
MARK_WIDTH = 2
TICK_SPACING = 14


def density_glyphs(counts: list[int]) -> str:
    """Block glyphs for ``counts``, scaled to their largest (a slice with any message shows at least ``▁``)."""
    top = max(counts, default=0)
    if top <= 0:
        return " " * len(counts)
    steps = len(GLYPHS) - 1
    return "".join(GLYPHS[0 if n <= 0 else max(1, round(n * steps / top))] for n in counts)


def seconds_label(seconds: float, step: float = 1.0) -> str:
    """A short ruler label: ``0s``, ``1.5s``, ``12s``, ``2m05s``; with ticks ``step`` seconds apart under a
    tenth of a second, ``35ms`` or ``120µs`` (a 50 ms bag read ``0.0s 0.0s 0.0s``)."""
    if 0 < step < 0.001:
        return f"{seconds * 1e6:.0f}µs"
    if 0 < step < 0.1:
        return f"{seconds * 1e3:.0f}ms"
    if seconds >= 120:
        return f"{int(seconds // 60)}m{int(seconds % 60):02d}s"
    if seconds >= 10 or seconds == int(seconds):
        return f"{seconds:.0f}s"
    return f"{seconds:.1f}s"


class TimelineView(Widget, can_focus=True):
    """Per-topic density strips over the whole bag, with the cursor at :attr:`cursor_ns`."""

    COMPONENT_CLASSES: ClassVar[set[str]] = {
        "timeline--ruler", "timeline--name", "timeline--count", "timeline--strip", "timeline--cursor",
        "timeline--selected", "timeline--publishing",
    }

    class Seek(Message):
        """The user clicked in the strips: seek to ``fraction`` of the bag."""

        def __init__(self, fraction: float) -> None:
            super().__init__()
            self.fraction = fraction

    class Selected(Message):
        """The user clicked a topic's name."""

        def __init__(self, row: int) -> None:
            super().__init__()
            self.row = row

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.index: BagIndex | None = None
        self.topics: list[str] = []
        self.cursor_ns = 0
        self.selected = 0
        self.publishing: set[str] = set()
        self._top = 0
        self._strips: dict[str, str] = {}
        self._strip_width = -1
        self._drawn: tuple[object, ...] = ()

    # -- state from the app ----------------------------------------------------------------------
    def set_index(self, index: BagIndex) -> None:
        """Show ``index``."""
        self.index = index
        self.topics = index.topics
        self._strip_width = -1
        self.refresh(layout=True)

    def show(self, cursor_ns: int, selected: int, publishing: set[str]) -> None:
        """Move the cursor and the selection, mark the ``publishing`` topics; repaints only when what is drawn
        changes."""
        self.cursor_ns = cursor_ns
        self.selected = selected
        self.publishing = set(publishing)
        key = (self._cursor_column(), selected, frozenset(publishing), self.size)
        if key != self._drawn:
            self._drawn = key
            self.refresh()

    @property
    def selected_topic(self) -> str | None:
        """The topic on the selected row."""
        return self.topics[self.selected] if 0 <= self.selected < len(self.topics) else None

    # -- geometry --------------------------------------------------------------------------------
    def get_content_height(self, container: object, viewport: object, width: int) -> int:
        """The ruler plus one row per topic (a placeholder line while loading)."""
        return 1 + max(1, len(self.topics))

    def _name_width(self) -> int:
        longest = max((len(t) for t in self.topics), default=10)
        return max(10, min(longest + 1, self.size.width // 3))

    def _strip_x(self) -> int:
        return MARK_WIDTH + self._name_width() + COUNT_WIDTH + 1

    def _strip_width_now(self) -> int:
        return max(1, self.size.width - self._strip_x() - 1)

    def _cursor_column(self) -> int:
        index = self.index
        if index is None:
            return 0
        span = index.end_ns - index.start_ns
        frac = 0.0 if span <= 0 else (self.cursor_ns - index.start_ns) / span
        return min(self._strip_width_now() - 1, max(0, int(frac * self._strip_width_now())))

    def _rows_shown(self) -> int:
        return max(1, self.size.height - 1)

    def _scroll_to_selection(self) -> None:
        rows = self._rows_shown()
        if self.selected < self._top:
            self._top = self.selected
        elif self.selected >= self._top + rows:
            self._top = self.selected - rows + 1
        self._top = max(0, min(self._top, max(0, len(self.topics) - rows)))

    # -- drawing ---------------------------------------------------------------------------------
    def _strip(self, topic: str, width: int) -> str:
        if width != self._strip_width:
            self._strips.clear()
            self._strip_width = width
        strip = self._strips.get(topic)
        if strip is None:
            assert self.index is not None
            strip = self._strips[topic] = density_glyphs(self.index.density(topic, width))
        return strip

    def _ruler(self, width: int, column: int) -> Text:
        assert self.index is not None
        line = Text(" " * MARK_WIDTH + "topic".ljust(self._name_width()) + "msgs".rjust(COUNT_WIDTH) + " ",
                    style=self.get_component_rich_style("timeline--ruler"))
        span_s = (self.index.end_ns - self.index.start_ns) / 1e9
        cells = [" "] * width
        step = span_s * TICK_SPACING / width if width else 0.0
        for x in range(0, width, TICK_SPACING):
            label = "┊" + seconds_label(span_s * x / width, step)
            if x + len(label) <= width and not x - 1 <= column <= x + len(label):  # labels give way to ▼
                cells[x:x + len(label)] = list(label)
        cells[column] = "▼"
        line.append("".join(cells), style=self.get_component_rich_style("timeline--ruler"))
        return line

    def render(self) -> Text:
        """The ruler and the visible topic rows."""
        if self.index is None:
            return Text(" reading the bag…", style=self.get_component_rich_style("timeline--ruler"))
        width = self._strip_width_now()
        column = self._cursor_column()
        self._scroll_to_selection()
        name_width = self._name_width()
        system = color_system(self.app.console.color_system)
        cursor_style = readable(self.get_component_rich_style("timeline--cursor"), system)
        lines = [self._ruler(width, column)]
        for row in range(self._top, min(len(self.topics), self._top + self._rows_shown())):
            topic = self.topics[row]
            line = Text()
            name = topic if len(topic) < name_width else topic[:name_width - 2] + "…"
            if topic in self.publishing:
                line.append("● ", style=self.get_component_rich_style("timeline--publishing"))
            else:
                line.append("○ ")
            line.append(name.ljust(name_width), style=self.get_component_rich_style("timeline--name"))
            line.append(str(self.index.tracks[topic].count).rjust(COUNT_WIDTH),
                        style=self.get_component_rich_style("timeline--count"))
            line.append(" ")
            strip = self._strip(topic, width)
            strip_style = self.get_component_rich_style("timeline--strip")
            line.append(strip[:column], style=strip_style)
            line.append(strip[column] if strip[column] != " " else "│", style=cursor_style)
            line.append(strip[column + 1:], style=strip_style)
            if row == self.selected:
                line.stylize(readable(self.get_component_rich_style("timeline--selected"), system),
                             0, MARK_WIDTH + name_width)
            lines.append(line)
        return Text("\n").join(lines)

    # -- mouse -------------------------------------------------------------------------------------
    def on_click(self, event: events.Click) -> None:
        """Click in a strip: seek there; on a name: select that topic."""
        if self.index is None:
            return
        x0 = self._strip_x()
        if event.x >= x0:
            self.post_message(self.Seek(min(1.0, max(0.0, (event.x - x0) / self._strip_width_now()))))
        elif event.y >= 1:
            row = self._top + event.y - 1
            if row < len(self.topics):
                self.post_message(self.Selected(row))
