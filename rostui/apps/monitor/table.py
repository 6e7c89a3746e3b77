"""TopicTable: the monitor's table of topics, drawn line by line (only the rows on screen are rendered).

Line 0 is the column header; the rest are rows.  Re-sorting or filtering is
a new list of rows and one refresh, so the cost of a key press does not
grow with the number of topics.  The cursor is anchored to a topic name:
it stays on its topic while rows move.
"""

from __future__ import annotations

from typing import ClassVar, Sequence

from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding, BindingType
from textual.geometry import Size
from textual.message import Message
from textual.strip import Strip

from rostui.apps.widgets.row_table import RowTable
from rostui.apps.widgets.terminal_colors import color_system, readable
from rostui.models.monitor.rows import COLUMNS, Liveness, TopicRow

__all__ = ["TopicTable"]

#: Spaces between columns.
GAP = 2
#: Narrowest width of each column (the figures' columns never change width as values change).
MIN_WIDTHS = (10, 8, 4, 4, 9, 11, 7, 10)

_LIVENESS_CLASSES = {Liveness.LIVE: "topic-table--live", Liveness.STALE: "topic-table--stale",
                     Liveness.WAITING: "topic-table--quiet", Liveness.NO_PUBLISHERS: "topic-table--quiet",
                     Liveness.OFF: "topic-table--quiet"}


class TopicTable(RowTable):
    """One row per topic; :meth:`show` takes the rows in the order to draw them."""

    COMPONENT_CLASSES: ClassVar[set[str]] = {"topic-table--live", "topic-table--stale", "topic-table--quiet"}

    DEFAULT_CSS = """
    TopicTable {
        overflow-x: auto;
    }
    TopicTable > .topic-table--live { color: $text-success; }
    TopicTable > .topic-table--stale { color: $text-error; text-style: bold; }
    TopicTable > .topic-table--quiet { color: $text-muted; }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("home", "first", "first topic", show=False),
        Binding("end", "last", "last topic", show=False),
        Binding("enter", "choose", "expand", show=False),
    ]

    class Chosen(Message):
        """Enter (or a double click) on a topic's row."""

        def __init__(self, topic: str) -> None:
            super().__init__()
            self.topic = topic

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.rows: list[TopicRow] = []
        self.names: list[str] = []
        self.cursor_topic: str | None = None
        self.widths: list[int] = list(MIN_WIDTHS)

    # -- geometry ------------------------------------------------------------------------------
    @property
    def row_count(self) -> int:
        """How many topics are shown."""
        return len(self.names)

    @property
    def cursor_row(self) -> int | None:
        """The row of the cursor's topic, if shown."""
        if self.cursor_topic is None:
            return None
        try:
            return self.names.index(self.cursor_topic)
        except ValueError:
            return None

    @property
    def current_topic(self) -> str | None:
        """The topic under the cursor."""
        return self.cursor_topic if self.cursor_row is not None else None

    # -- updates from the app --------------------------------------------------------------------
    def show(self, rows: Sequence[TopicRow]) -> None:
        """Draw ``rows`` in this order; the cursor stays on its topic (or the nearest row when it left)."""
        old_row = self.cursor_row
        self.rows = list(rows)
        self.names = [r.name for r in self.rows]
        cells = [r.cells() for r in self.rows]
        self.widths = [max([MIN_WIDTHS[i], len(COLUMNS[i])] + [len(c[i]) for c in cells])
                       for i in range(len(COLUMNS))]
        if self.names and self.cursor_row is None:
            index = 0 if old_row is None else min(old_row, len(self.names) - 1)
            self.cursor_topic = self.names[index]
        width = sum(self.widths) + GAP * (len(self.widths) - 1)
        size = Size(width, len(self.rows) + 1)
        if size != self.virtual_size:
            self.virtual_size = size
        self.refresh()

    def visible_topics(self) -> list[str]:
        """The topics of the rows on screen now."""
        return self.names[self.top_row:self.top_row + self.page_rows]

    def select_topic(self, topic: str) -> bool:
        """Put the cursor on ``topic`` and bring it into view; False when it is not shown."""
        if topic not in self.names:
            return False
        self.cursor_topic = topic
        self.scroll_to_row(self.names.index(topic))
        self.refresh()
        return True

    def select_row(self, row: int) -> None:
        """Put the cursor on the topic of ``row``."""
        self.select_topic(self.names[row])

    # -- keys and mouse -------------------------------------------------------------------------
    def action_choose(self) -> None:
        """Enter: tell the app the cursor's topic was chosen."""
        if self.current_topic is not None:
            self.post_message(self.Chosen(self.current_topic))

    def row_clicked(self, row: int, event: events.Click) -> None:
        """A click selects the row; a double click chooses it."""
        self.select_row(row)
        if event.chain >= 2:
            self.action_choose()

    # -- drawing -----------------------------------------------------------------------------------
    def _line(self, texts: Sequence[str]) -> str:
        parts = [t.ljust(w) if i < 2 or i == len(texts) - 1 else t.rjust(w) if i < 7 else t.ljust(w)
                 for i, (t, w) in enumerate(zip(texts, self.widths))]
        return (" " * GAP).join(parts)

    def render_line(self, y: int) -> Strip:
        """Line ``y`` of the widget: the header, a topic's row, or blank."""
        width = max(self.scrollable_content_region.width, self.virtual_size.width)
        scroll_x = int(self.scroll_x)
        if y == 0:
            text = self._line(COLUMNS)
            style = self.get_component_rich_style("row-table--header")
        else:
            row = self.top_row + y - 1
            if row >= len(self.rows):
                return Strip.blank(self.scrollable_content_region.width, self.rich_style)
            topic = self.rows[row]
            text = self._line(topic.cells())
            style = self.rich_style + self.get_component_rich_style(_LIVENESS_CLASSES[topic.liveness])
            if topic.name == self.cursor_topic:
                cursor = self.get_component_rich_style("row-table--cursor")
                style += Style(bgcolor=cursor.bgcolor, bold=cursor.bold)
            style = readable(style, color_system(self.app.console.color_system))
        strip = Strip([Segment(text.ljust(width), style)], width)
        return strip.crop(scroll_x, scroll_x + self.scrollable_content_region.width)
