"""TopicTable: the monitor's one table of topics, repainted in place and asked which topics it shows."""

from __future__ import annotations

from typing import ClassVar, Sequence

from textual.binding import Binding, BindingType
from textual.widgets import DataTable

from rostui.core.monitor.rows import COLUMNS, TopicRow

__all__ = ["TopicTable"]


class TopicTable(DataTable):
    """One row per topic (row key = topic name); :meth:`show` repaints only the cells that changed."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("home", "scroll_top", "first topic", show=False),
        Binding("end", "scroll_bottom", "last topic", show=False),
    ]

    DEFAULT_CSS = """
    TopicTable {
        height: 1fr;
    }
    """

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, cursor_type="row", zebra_stripes=False)
        self.names: list[str] = []
        self._cells: dict[str, tuple[str, ...]] = {}

    def on_mount(self) -> None:
        """Add the columns."""
        for label in COLUMNS:
            self.add_column(label, key=label)

    def show(self, rows: Sequence[TopicRow]) -> None:
        """Show ``rows`` in this order; the cursor stays on its topic when that topic is still shown."""
        names = [r.name for r in rows]
        if names != self.names:
            current = self.current_topic
            self.clear()
            self._cells = {}
            for row in rows:
                cells = row.cells()
                self._cells[row.name] = cells
                self.add_row(*cells, key=row.name)
            self.names = names
            if current in names:
                self.move_cursor(row=names.index(current), animate=False)
            return
        for row in rows:
            cells = row.cells()
            old = self._cells.get(row.name)
            if old == cells:
                continue
            self._cells[row.name] = cells
            for index, (label, value) in enumerate(zip(COLUMNS, cells)):
                if old is None or old[index] != value:
                    self.update_cell(row.name, label, value, update_width=True)

    @property
    def current_topic(self) -> str | None:
        """The topic under the cursor."""
        if not self.names or not 0 <= self.cursor_row < len(self.names):
            return None
        return self.names[self.cursor_row]

    def visible_topics(self) -> list[str]:
        """The topics of the rows on screen now (scrolled into view, below the header)."""
        if not self.names:
            return []
        first = max(0, int(self.scroll_offset.y))
        height = self.scrollable_content_region.height - (self.header_height if self.show_header else 0)
        return self.names[first:first + max(0, height)]

    def select_topic(self, topic: str) -> bool:
        """Put the cursor on ``topic``; False when it is not shown."""
        if topic not in self.names:
            return False
        self.move_cursor(row=self.names.index(topic), animate=False)
        return True
