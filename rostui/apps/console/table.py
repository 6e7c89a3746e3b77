"""LogTable: the console's message table, drawn line by line from the model's rows.

Only the visible lines are rendered (Textual's Line API), so the table costs
the same with ten messages or a hundred thousand.  Line 0 is the column
header; the rest are rows.  The cursor and the view are anchored to message
sequence numbers, so they stay on the same message while old ones are
dropped or the filter changes.  In follow mode the cursor sits on the newest
row; scrolling or moving up leaves it, End (or F in the app) comes back.
"""

from __future__ import annotations

from typing import ClassVar

from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding, BindingType
from textual.geometry import Size
from textual.message import Message
from textual.reactive import reactive
from textual.strip import Strip

from rostui.apps.console.columns import GAP, Layout, cell, layout_for, row_texts
from rostui.apps.widgets.row_table import RowTable
from rostui.apps.widgets.terminal_colors import color_system, readable
from rostui.core.log.levels import Level
from rostui.models.console.filters import HighlightRule, first_highlight
from rostui.models.console.model import ConsoleModel

__all__ = ["HIGHLIGHT_COLOURS", "LogTable"]

#: Highlight rules cycle through this many colours.
HIGHLIGHT_COLOURS = 4

_LEVEL_CLASSES = {int(level): f"log-table--{level.text}" for level in Level}

#: Rendered rows kept between repaints.
_CACHE_ROWS = 2048


class LogTable(RowTable):
    """The messages of a :class:`ConsoleModel`, one row each, newest at the bottom."""

    COMPONENT_CLASSES: ClassVar[set[str]] = {
        *_LEVEL_CLASSES.values(),
        *(f"log-table--highlight-{n}" for n in range(HIGHLIGHT_COLOURS)),
    }

    DEFAULT_CSS = """
    LogTable {
        overflow-x: hidden;
    }
    LogTable > .log-table--debug { color: $text-success; }
    LogTable > .log-table--info { color: $foreground; }
    LogTable > .log-table--warn { color: $text-warning; }
    LogTable > .log-table--error { color: $text-error; }
    LogTable > .log-table--fatal { color: $text; background: $error 45%; text-style: bold; }
    LogTable > .log-table--highlight-0 { background: $accent 30%; }
    LogTable > .log-table--highlight-1 { background: $success 30%; }
    LogTable > .log-table--highlight-2 { background: $secondary 80%; }
    LogTable > .log-table--highlight-3 { background: $error 25%; }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("home", "first", "first", show=False),
        Binding("end", "last", "follow", show=False),
    ]

    follow: reactive[bool] = reactive(True)
    """Keep the cursor on the newest row and the view at the bottom."""

    class CursorMoved(Message):
        """The selected message changed (``seq`` is None when no row is selected)."""

        def __init__(self, seq: int | None) -> None:
            super().__init__()
            self.seq = seq

    def __init__(self, model: ConsoleModel, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.model = model
        self.highlights: list[HighlightRule] = []
        self.cursor_seq: int | None = None
        self._top_seq: int | None = None
        self._layout: Layout | None = None
        self._layout_key: tuple[int, int, int] = (0, 0, 0)
        self._cache: dict[tuple[int, bool], Strip] = {}
        self._syncing = False

    # -- geometry ------------------------------------------------------------------------------
    @property
    def row_count(self) -> int:
        """How many messages the filter shows."""
        return len(self.model)

    @property
    def column_layout(self) -> Layout:
        """The columns at the current width (recomputed when width, ``#`` digits or node width change)."""
        key = (self.scrollable_content_region.width, len(str(self.model.end)), self.model.longest_node)
        if self._layout is None or key != self._layout_key:
            self._layout = layout_for(*key)
            self._layout_key = key
            self._cache.clear()
        return self._layout

    @property
    def cursor_row(self) -> int | None:
        """The row of the selected message, if it is shown."""
        if self.cursor_seq is None or not len(self.model):
            return None
        row = self.model.row_of(self.cursor_seq)
        if row >= len(self.model) or self.model.seq_at(row) != self.cursor_seq:
            return None
        return row

    # -- updates from the app --------------------------------------------------------------------
    def sync(self) -> None:
        """Show the model's current rows: follow the newest, or keep the same messages in view."""
        rows = len(self.model)
        self._syncing = True
        try:
            self._set_virtual_height(rows + 1)
            if self.follow:
                self._set_cursor(self.model.seq_at(rows - 1) if rows else None)
                self.scroll_to(y=max(0, rows + 1 - self.scrollable_content_region.height), animate=False,
                               force=True)
            else:
                if self.cursor_seq is not None and rows and self.cursor_row is None:
                    self._set_cursor(self.model.seq_at(min(self.model.row_of(self.cursor_seq), rows - 1)))
                elif not rows:
                    self._set_cursor(None)
                if self._top_seq is not None:
                    self.scroll_to(y=self.model.row_of(self._top_seq), animate=False, force=True)
        finally:
            self._syncing = False
        self.refresh()

    def _set_virtual_height(self, height: int) -> None:
        """Change the scroll range without a layout.

        Setting ``virtual_size`` lays out the whole screen; at 20 batches a
        second that is most of the app's time.  The table's box does not
        depend on its row count (its scrollbar is always shown), so updating
        the scroll range, the scrollbar's range and a scroll position past
        the new end is all a new row count needs.
        """
        size = Size(self.scrollable_content_region.width, height)
        if size != self.virtual_size:
            self.set_reactive(LogTable.virtual_size, size)
            if self.show_vertical_scrollbar:
                self.vertical_scrollbar.window_virtual_size = height
            self.scroll_y = min(self.scroll_y, self.max_scroll_y)

    def refilter(self) -> None:
        """The filter changed: keep the selected message in view if it is still shown."""
        self._cache.clear()
        if self.follow or self.cursor_seq is None:
            self.sync()
            return
        rows = len(self.model)
        row = min(self.model.row_of(self.cursor_seq), max(rows - 1, 0))
        self._set_cursor(self.model.seq_at(row) if rows else None)
        self._top_seq = None
        self.sync()
        self.scroll_to_row(row, center=True)

    def restyle(self) -> None:
        """Highlight rules (or colours) changed: draw every row again."""
        self._cache.clear()
        self.refresh()

    def set_follow(self, follow: bool) -> None:
        """Enter or leave follow mode."""
        self.follow = follow
        if follow:
            self.sync()

    def on_resize(self, _event: events.Resize) -> None:
        """A new size: new columns, and in follow mode the newest row at the bottom again."""
        self._cache.clear()
        self.sync()

    # -- cursor ------------------------------------------------------------------------------------
    def _set_cursor(self, seq: int | None) -> None:
        if seq != self.cursor_seq:
            self.cursor_seq = seq
            self.post_message(self.CursorMoved(seq))

    def select_row(self, row: int) -> None:
        """Select ``row`` (clamped) and scroll it into view; leaves follow mode unless it is the newest row."""
        rows = len(self.model)
        if not rows:
            return
        row = max(0, min(row, rows - 1))
        if row < rows - 1 or not self.follow:
            self.follow = False
        self._set_cursor(self.model.seq_at(row))
        self.scroll_to_row(row)
        self.refresh()

    def scroll_to_row(self, row: int, *, center: bool = False) -> int | None:
        """Scroll ``row`` into view (a scroll that stays in follow mode); the view is anchored to its top message."""
        self._syncing = True
        try:
            target = super().scroll_to_row(row, center=center)
        finally:
            self._syncing = False
        if target is not None:
            self._top_seq = self.model.seq_at(target) if target < len(self.model) else None
        return target

    def _move(self, delta: int) -> None:
        row = self.cursor_row
        if row is None:
            row = len(self.model) - 1 if delta < 0 else 0
        self.follow = False
        self.select_row(row + delta)

    def action_move(self, delta: int) -> None:
        """Up/Down: the message above or below (leaves follow mode)."""
        self._move(delta)

    def action_page(self, pages: int) -> None:
        """PageUp/PageDown: a page up or down (leaves follow mode)."""
        self._move(pages * self.page_rows)

    def action_first(self) -> None:
        """Home: the oldest message shown (leaves follow mode)."""
        self.follow = False
        self.select_row(0)

    def action_last(self) -> None:
        """End: back to follow mode, the newest message and the ones after it as they arrive."""
        self.set_follow(True)

    def watch_scroll_y(self, old: float, new: float) -> None:
        """Scrolling up by hand leaves follow mode; the view stays anchored to its top message."""
        super().watch_scroll_y(old, new)
        row = int(new)
        self._top_seq = self.model.seq_at(row) if row < len(self.model) else None
        if not self._syncing and self.follow and new < old and new < self.max_scroll_y:
            self.follow = False

    def row_clicked(self, row: int, event: events.Click) -> None:
        """Clicking a row selects it (leaves follow mode)."""
        self.follow = False
        self.select_row(row)

    # -- drawing -----------------------------------------------------------------------------------
    def _style(self, *names: str) -> Style:
        return self.get_component_rich_style(*names)

    def _overlay(self, name: str) -> Style:
        """A component class's background (and boldness), so the level's colour shows through."""
        full = self.get_component_rich_style(name)
        return Style(bgcolor=full.bgcolor, bold=full.bold)

    def render_line(self, y: int) -> Strip:
        """Line ``y`` of the widget: the header, a message row, or blank."""
        layout = self.column_layout
        if y == 0:
            return self._header(layout)
        row = self.top_row + y - 1
        if row >= len(self.model):
            return Strip.blank(layout.width, self.rich_style)
        seq = self.model.seq_at(row)
        key = (seq, seq == self.cursor_seq)
        strip = self._cache.get(key)
        if strip is None:
            if len(self._cache) > _CACHE_ROWS:
                self._cache.clear()
            strip = self._cache[key] = self._row(layout, seq, key[1])
        return strip

    def _header(self, layout: Layout) -> Strip:
        style = self._style("row-table--header")
        text = (" " * GAP).join(cell(c.title, c.width) for c in layout.columns)
        return Strip([Segment(text.ljust(layout.width), style)], layout.width)

    def _row(self, layout: Layout, seq: int, selected: bool) -> Strip:
        entry = self.model.entry(seq)
        style = self.rich_style + self._style(_LEVEL_CLASSES.get(entry.level, "log-table--info"))
        mark = first_highlight(self.highlights, entry)
        if mark >= 0:
            style += self._overlay(f"log-table--highlight-{mark % HIGHLIGHT_COLOURS}")
        if selected:
            style += self._overlay("row-table--cursor")
        style = readable(style, color_system(self.app.console.color_system))
        texts = row_texts(seq, entry)
        gap = " " * GAP
        text = gap.join(cell(texts[c.key], c.width) for c in layout.columns)
        return Strip([Segment(text, style)], layout.width)
