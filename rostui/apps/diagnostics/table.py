"""StatusTree: the diagnostics as a table drawn line by line: level, the status in its tree, its message.

Only the lines on screen are rendered, so a robot with thousands of statuses costs one screenful. The cursor is
anchored to a status's full name: it stays on its status while others come, go or change level.
"""

from __future__ import annotations

from typing import ClassVar, Sequence

from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.message import Message
from textual.strip import Strip

from rostui.apps.widgets.row_table import RowTable
from rostui.apps.widgets.terminal_colors import color_system, readable
from rostui.models.diagnostics.levels import ERROR, OK, STALE, WARN, level_name
from rostui.models.diagnostics.tree import DiagRow

__all__ = ["StatusTree", "HEADER"]

HEADER = ("level", "status", "message")
#: Spaces between columns.
GAP = 2
LEVEL_WIDTH = 5

_LEVEL_CLASSES = {OK: "status-tree--ok", WARN: "status-tree--warn", ERROR: "status-tree--error",
                  STALE: "status-tree--stale"}


class StatusTree(RowTable):
    """One row per status (and per group of the aggregator's tree); :meth:`show` takes the rows in order."""

    COMPONENT_CLASSES: ClassVar[set[str]] = set(_LEVEL_CLASSES.values())

    DEFAULT_CSS = """
    StatusTree { overflow-x: auto; }
    StatusTree > .status-tree--ok { color: $text-success; }
    StatusTree > .status-tree--warn { color: $text-warning; }
    StatusTree > .status-tree--error { color: $text-error; text-style: bold; }
    StatusTree > .status-tree--stale { color: $text-primary; text-style: italic; }
    """

    class Moved(Message):
        """The cursor is on another status."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.rows: list[DiagRow] = []
        self.names: list[str] = []
        self.cursor_name: str | None = None
        self.label_width = len(HEADER[1])

    @property
    def row_count(self) -> int:
        """How many rows are shown."""
        return len(self.rows)

    @property
    def cursor_row(self) -> int | None:
        """The row of the cursor's status, if shown."""
        try:
            return self.names.index(self.cursor_name) if self.cursor_name is not None else None
        except ValueError:
            return None

    @property
    def current(self) -> DiagRow | None:
        """The row under the cursor."""
        row = self.cursor_row
        return self.rows[row] if row is not None else None

    def show(self, rows: Sequence[DiagRow]) -> None:
        """Draw ``rows`` in this order; the cursor stays on its status (or the nearest row when it left)."""
        old_row = self.cursor_row
        self.rows = list(rows)
        self.names = [row.name for row in self.rows]
        self.label_width = max([len(HEADER[1])] + [len(row.label) for row in self.rows])
        if self.names and self.cursor_row is None:
            self.cursor_name = self.names[0 if old_row is None else min(old_row, len(self.names) - 1)]
            self.post_message(self.Moved())
        longest = max((len(row.message) for row in self.rows), default=0)
        size = Size(LEVEL_WIDTH + GAP + self.label_width + GAP + max(longest, len(HEADER[2])), len(self.rows) + 1)
        if size != self.virtual_size:
            self.virtual_size = size
        self.refresh()

    def select_name(self, name: str) -> bool:
        """Put the cursor on status ``name`` and bring it into view; False when it is not shown."""
        if name not in self.names:
            return False
        if name != self.cursor_name:
            self.cursor_name = name
            self.post_message(self.Moved())
        self.scroll_to_row(self.names.index(name))
        self.refresh()
        return True

    def select_row(self, row: int) -> None:
        """Put the cursor on the status of ``row``."""
        self.select_name(self.names[row])

    def _line(self, level: str, label: str, message: str) -> str:
        return f"{level:<{LEVEL_WIDTH}}{' ' * GAP}{label:<{self.label_width}}{' ' * GAP}{message}"

    def render_line(self, y: int) -> Strip:
        """Line ``y`` of the widget: the header, a status's row, or blank."""
        width = max(self.scrollable_content_region.width, self.virtual_size.width)
        if y == 0:
            text = self._line(*HEADER)
            style = self.get_component_rich_style("row-table--header")
        else:
            index = self.top_row + y - 1
            if index >= len(self.rows):
                return Strip.blank(self.scrollable_content_region.width, self.rich_style)
            row = self.rows[index]
            text = self._line(level_name(row.level), row.label, row.message)
            style = self.rich_style + self.get_component_rich_style(_LEVEL_CLASSES.get(row.level,
                                                                                       _LEVEL_CLASSES[ERROR]))
            if row.name == self.cursor_name:
                cursor = self.get_component_rich_style("row-table--cursor")
                style += Style(bgcolor=cursor.bgcolor, bold=cursor.bold)
            style = readable(style, color_system(self.app.console.color_system))
        scroll_x = int(self.scroll_x)
        strip = Strip([Segment(text.ljust(width), style)], width)
        return strip.crop(scroll_x, scroll_x + self.scrollable_content_region.width)
