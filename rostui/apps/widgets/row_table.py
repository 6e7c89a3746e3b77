"""RowTable: a table drawn line by line, its column header on line 0 and one row on each line below.

Only the lines on screen are rendered (Textual's Line API), so a table of a hundred thousand rows costs what
one screenful costs.  Subclasses keep their rows, anchor the cursor to what a row shows (a topic, a message's
sequence number) rather than to its index, and draw the lines; this class knows the geometry they share:
the page, the top row, scrolling a row into view, the keys that move the cursor and the row a click lands on.
"""

from __future__ import annotations

from typing import ClassVar, Sequence

from textual import events
from textual.binding import Binding, BindingType
from textual.scroll_view import ScrollView

__all__ = ["RowTable"]


class RowTable(ScrollView, can_focus=True):
    """Rows under a header line; Up/Down, PageUp/PageDown, Home and End move the cursor, a click selects a row."""

    COMPONENT_CLASSES: ClassVar[set[str]] = {"row-table--header", "row-table--cursor"}

    DEFAULT_CSS = """
    RowTable {
        overflow-y: scroll;
        scrollbar-size-vertical: 1;
    }
    RowTable > .row-table--header { text-style: bold; background: $panel; color: $foreground; }
    RowTable > .row-table--cursor { background: $primary 45%; text-style: bold; }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("up", "move(-1)", "up", show=False),
        Binding("down", "move(1)", "down", show=False),
        Binding("pageup", "page(-1)", "page up", show=False),
        Binding("pagedown", "page(1)", "page down", show=False),
        Binding("home", "first", "first row", show=False),
        Binding("end", "last", "last row", show=False),
    ]

    # -- what subclasses say ----------------------------------------------------------------------
    @property
    def row_count(self) -> int:
        """How many rows there are."""
        raise NotImplementedError

    @property
    def cursor_row(self) -> int | None:
        """The row under the cursor, if it is shown."""
        raise NotImplementedError

    def select_row(self, row: int) -> None:
        """Put the cursor on ``row`` (already clamped to the rows) and bring it into view."""
        raise NotImplementedError

    def row_clicked(self, row: int, event: events.Click) -> None:
        """A click landed on ``row``: select it."""
        self.select_row(row)

    # -- geometry -------------------------------------------------------------------------------------
    @property
    def page_rows(self) -> int:
        """Rows visible below the header."""
        return max(1, self.scrollable_content_region.height - 1)

    @property
    def top_row(self) -> int:
        """The row shown first under the header."""
        return int(self.scroll_y)

    def scroll_to_row(self, row: int, *, center: bool = False) -> int | None:
        """Scroll so that ``row`` shows (in the middle with ``center``); the new top row, or None when it showed."""
        top, page = self.top_row, self.page_rows
        if center:
            target = max(0, row - page // 2)
        elif row < top:
            target = row
        elif row >= top + page:
            target = row - page + 1
        else:
            return None
        self.scroll_to(y=target, animate=False, force=True)
        return target

    def clamped(self, row: int) -> int | None:
        """``row`` within the rows (None when there are none)."""
        return max(0, min(row, self.row_count - 1)) if self.row_count else None

    def _go(self, row: int) -> None:
        target = self.clamped(row)
        if target is not None:
            self.select_row(target)

    # -- keys and mouse ------------------------------------------------------------------------------
    def action_move(self, delta: int) -> None:
        """Up/Down: the row above or below."""
        row = self.cursor_row
        self._go(0 if row is None else row + delta)

    def action_page(self, pages: int) -> None:
        """PageUp/PageDown: a screenful up or down."""
        row = self.cursor_row
        self._go((0 if row is None else row) + pages * self.page_rows)

    def action_first(self) -> None:
        """Home: the first row."""
        self._go(0)

    def action_last(self) -> None:
        """End: the last row."""
        self._go(self.row_count - 1)

    def on_click(self, event: events.Click) -> None:
        """A click on a row (not the header) is :meth:`row_clicked`."""
        offset = event.get_content_offset(self)
        if offset is None or offset.y < 1:
            return
        row = self.top_row + offset.y - 1
        if row < self.row_count:
            self.row_clicked(row, event)

    def visible_texts(self) -> Sequence[str]:
        """The text of every visible line (header first), as drawn."""
        return [self.render_line(y).text for y in range(self.scrollable_content_region.height)]
