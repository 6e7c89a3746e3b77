"""The three panels of the loggers app: nodes, the selected node's loggers, and the levels.

Each panel is a list with a one-line :class:`Notice` under it, where the
panel says what it shows or, in red, what went wrong (master away, node gone,
service failed), so errors appear where the user is looking.
"""

from __future__ import annotations

from typing import Iterable, Sequence

from rich.text import Text
from textual.widgets import DataTable, OptionList
from textual.widgets.option_list import Option

from rostui.apps.widgets.name_list import NameList
from rostui.apps.widgets.notice import NOTICE_KINDS, Notice
from rostui.models.loggers import LEVEL_NAMES, LoggerLevel, LoggerNode

__all__ = ["LEVEL_STYLES", "LevelList", "LoggerTable", "NOTICE_KINDS", "NodeList", "Notice", "level_text"]

#: How each level is coloured in the logger table and the level list (rqt_console's hues).
LEVEL_STYLES = {
    "DEBUG": "green",
    "INFO": "",
    "WARN": "yellow",
    "ERROR": "red",
    "FATAL": "bold magenta",
}

#: Marks the current level in the level list; the others get a no-break space (kept at a line start).
CURRENT_MARK = "●"
NOT_CURRENT_MARK = "\u00a0"


def level_text(level: str) -> Text:
    """A level name in its colour."""
    return Text(level, style=LEVEL_STYLES.get(level, ""))


class NodeList(NameList):
    """Nodes that serve ``get_loggers``; the highlighted one is the selected node."""

    @property
    def node_names(self) -> list[str]:
        """The nodes listed."""
        return self.names

    def show_nodes(self, nodes: Sequence[LoggerNode], keep: str | None) -> bool:
        """List ``nodes``, keeping ``keep`` highlighted when it is still there; False when nothing changed."""
        return self.show_names([node.name for node in nodes], keep)


class LoggerTable(DataTable[Text]):
    """The selected node's loggers, one row each: name and level (coloured)."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, cursor_type="row", zebra_stripes=False)
        self.logger_names: list[str] = []

    def on_mount(self) -> None:
        """Two columns: logger and level."""
        self._add_columns([])

    def _add_columns(self, names: list[str]) -> None:
        # The logger column is as wide as the longest name, set here rather than measured by the table: the
        # table measures new rows only when it is next idle, and rows replaced before that kept the old width.
        self.add_column("Logger", key="logger", width=max([len("Logger"), *map(len, names)]))
        self.add_column("Level", key="level", width=5)

    @property
    def highlighted_name(self) -> str | None:
        """The logger under the cursor, if any."""
        if not self.logger_names or not 0 <= self.cursor_row < len(self.logger_names):
            return None
        return self.logger_names[self.cursor_row]

    def show_loggers(self, loggers: Iterable[LoggerLevel], keep: str | None) -> None:
        """Show ``loggers``; the cursor stays on ``keep`` (or goes to the first row)."""
        items = list(loggers)
        names = [item.name for item in items]
        if names == self.logger_names:
            for item in items:
                self.update_cell(item.name, "level", level_text(item.level))
            return
        self.clear(columns=True)
        self._add_columns(names)
        self.logger_names = names
        for item in items:
            self.add_row(Text(item.name), level_text(item.level), key=item.name)
        if keep in names:
            self.move_cursor(row=names.index(keep), animate=False)

    def clear_loggers(self) -> None:
        """Show no loggers."""
        self.clear()
        self.logger_names = []


class LevelList(OptionList):
    """DEBUG ... FATAL; the selected logger's current level is marked and highlighted."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(*(Option(self._prompt(name, False), id=name) for name in LEVEL_NAMES), id=id,
                         markup=False)
        self.current: str | None = None
        self.logger: str | None = None

    @staticmethod
    def _prompt(level: str, current: bool) -> Text:
        # The mark is a span of its own, so SVG screenshots keep the indent of an unmarked, unstyled INFO.
        mark = Text(f"{CURRENT_MARK if current else NOT_CURRENT_MARK}\u00a0", style="bold")
        return Text.assemble(mark, level_text(level))

    def show_current(self, level: str | None, logger: str | None = None) -> None:
        """Mark ``level``, the current level of ``logger`` (None: nothing selected, nothing marked).

        The cursor jumps to the current level only when the logger or its level
        changed, so a periodic refresh never moves it under the user.
        """
        if (level, logger) == (self.current, self.logger):
            return
        self.current, self.logger = level, logger
        for name in LEVEL_NAMES:
            self.replace_option_prompt(name, self._prompt(name, name == level))
        self.highlighted = LEVEL_NAMES.index(level) if level in LEVEL_NAMES else None
