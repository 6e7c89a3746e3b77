"""A DataTable whose self-sizing columns narrow on screen too, when their widest cell becomes shorter."""

from __future__ import annotations

from typing import Any

from textual.widgets import DataTable


class FittedTable(DataTable[Any]):
    """DataTable that redraws its rows when a column narrows.

    Textual's DataTable measures a column again once its updated cells have been drawn and narrows it, but the
    rows it has already drawn stay in its line caches: the screen keeps the old width until some later update
    (a node's state "starting" then "running" left the launch monitor's State column one cell too wide until
    its next CPU reading, so what a screenshot showed depended on the machine's load).
    """

    def _update_column_widths(self, updated_cells: set[Any]) -> None:
        before = {key: column.content_width for key, column in self.columns.items()}
        super()._update_column_widths(updated_cells)
        if any(column.content_width < before.get(key, column.content_width) for key, column in self.columns.items()):
            self._clear_caches()
            self.refresh()
