"""LineTable: rows given as finished lines of text, each with a key the cursor stays on and a style class.

Only the lines on screen are rendered, so thousands of rows cost one screenful. A subclass (or its owner) turns
its own rows into :class:`Line`\\ s and calls :meth:`LineTable.show`; the cursor is anchored to a row's key, so it
stays on its row while others come, go or move, and :class:`LineTable.Moved` says when it moves to another.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.message import Message
from textual.strip import Strip

from rostui.apps.widgets.row_table import RowTable
from rostui.apps.widgets.terminal_colors import color_system, readable

__all__ = ["Line", "LineTable"]


@dataclass(frozen=True)
class Line:
    """One row: the ``key`` the cursor follows, its ``text``, and the component class that colours it ("": none)."""

    key: str
    text: str
    style: str = ""


class LineTable(RowTable):
    """A header line and rows of text; :meth:`show` takes the rows in the order to draw them."""

    class Moved(Message):
        """The cursor is on another row."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.lines: list[Line] = []
        self.keys: list[str] = []
        self.header = ""
        self.cursor_key: str | None = None

    @property
    def row_count(self) -> int:
        """How many rows are shown."""
        return len(self.lines)

    @property
    def cursor_row(self) -> int | None:
        """The row of the cursor's key, if shown."""
        try:
            return self.keys.index(self.cursor_key) if self.cursor_key is not None else None
        except ValueError:
            return None

    def show(self, header: str, lines: Sequence[Line]) -> None:
        """Draw ``header`` and ``lines``; the cursor stays on its key (or the nearest row when it left)."""
        old_row = self.cursor_row
        self.header, self.lines = header, list(lines)
        self.keys = [line.key for line in self.lines]
        if self.keys and self.cursor_row is None:
            self.cursor_key = self.keys[0 if old_row is None else min(old_row, len(self.keys) - 1)]
            self.post_message(self.Moved())
        width = max([len(header)] + [len(line.text) for line in self.lines])
        size = Size(width, len(self.lines) + 1)
        if size != self.virtual_size:
            self.virtual_size = size
        self.refresh()

    def select_key(self, key: str) -> bool:
        """Put the cursor on the row of ``key`` and bring it into view; False when it is not shown."""
        if key not in self.keys:
            return False
        if key != self.cursor_key:
            self.cursor_key = key
            self.post_message(self.Moved())
        self.scroll_to_row(self.keys.index(key))
        self.refresh()
        return True

    def select_row(self, row: int) -> None:
        """Put the cursor on ``row``."""
        self.select_key(self.keys[row])

    def render_line(self, y: int) -> Strip:
        """Line ``y`` of the widget: the header, a row, or blank."""
        width = max(self.scrollable_content_region.width, self.virtual_size.width)
        if y == 0:
            text, style = self.header, self.get_component_rich_style("row-table--header")
        else:
            index = self.top_row + y - 1
            if index >= len(self.lines):
                return Strip.blank(self.scrollable_content_region.width, self.rich_style)
            line = self.lines[index]
            text, style = line.text, self.rich_style
            if line.style:
                style += self.get_component_rich_style(line.style)
            if line.key == self.cursor_key:
                cursor = self.get_component_rich_style("row-table--cursor")
                style += Style(bgcolor=cursor.bgcolor, bold=cursor.bold)
            style = readable(style, color_system(self.app.console.color_system))
        scroll_x = int(self.scroll_x)
        strip = Strip([Segment(text.ljust(width), style)], width)
        return strip.crop(scroll_x, scroll_x + self.scrollable_content_region.width)
