"""StatusTree: the diagnostics as a table drawn line by line: level, the status in its tree, its message.

The cursor is anchored to a status's full name: it stays on its status while others come, go or change level.
"""

from __future__ import annotations

from typing import ClassVar, Sequence

from rostui.apps.widgets.line_table import Line, LineTable
from rostui.models.diagnostics.levels import ERROR, OK, STALE, WARN, level_name
from rostui.models.diagnostics.tree import DiagRow

__all__ = ["StatusTree", "HEADER"]

HEADER = ("level", "status", "message")
#: Spaces between columns.
GAP = 2
LEVEL_WIDTH = 5

_LEVEL_CLASSES = {OK: "status-tree--ok", WARN: "status-tree--warn", ERROR: "status-tree--error",
                  STALE: "status-tree--stale"}


class StatusTree(LineTable):
    """One row per status (and per group of the aggregator's tree); :meth:`show_rows` takes the rows in order."""

    COMPONENT_CLASSES: ClassVar[set[str]] = set(_LEVEL_CLASSES.values())

    DEFAULT_CSS = """
    StatusTree { overflow-x: auto; }
    StatusTree > .status-tree--ok { color: $text-success; }
    StatusTree > .status-tree--warn { color: $text-warning; }
    StatusTree > .status-tree--error { color: $text-error; text-style: bold; }
    StatusTree > .status-tree--stale { color: $text-primary; text-style: italic; }
    """

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.rows: list[DiagRow] = []

    @property
    def names(self) -> list[str]:
        """The full names of the rows shown."""
        return self.keys

    @property
    def cursor_name(self) -> str | None:
        """The status under the cursor (its full name)."""
        return self.cursor_key

    @cursor_name.setter
    def cursor_name(self, name: str | None) -> None:
        self.cursor_key = name

    @property
    def current(self) -> DiagRow | None:
        """The row under the cursor."""
        row = self.cursor_row
        return self.rows[row] if row is not None else None

    def show_rows(self, rows: Sequence[DiagRow]) -> None:
        """Draw ``rows`` in this order; the cursor stays on its status (or the nearest row when it left)."""
        self.rows = list(rows)
        width = max([len(HEADER[1])] + [len(row.label) for row in self.rows])

        def line(level: str, label: str, message: str) -> str:
            return f"{level:<{LEVEL_WIDTH}}{' ' * GAP}{label:<{width}}{' ' * GAP}{message}"

        self.show(line(*HEADER), [Line(row.name, line(level_name(row.level), row.label, row.message),
                                       _LEVEL_CLASSES.get(row.level, _LEVEL_CLASSES[ERROR])) for row in self.rows])
