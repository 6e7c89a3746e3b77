"""HelpScreen: every key the app answers to, with what it does, over the app; Escape, ``?``, F1 or q closes it."""

from __future__ import annotations

from typing import ClassVar

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

from rostui.apps.widgets.keys import KeySection

__all__ = ["HelpScreen", "help_table"]

#: The help panel's title line.
HELP_TITLE = "keys · Esc, ? or q closes · ctrl+p finds an action by name"


def help_table(sections: list[KeySection]) -> Table:
    """The sections as one two-column table: a bold heading per section, then key and description rows."""
    table = Table.grid(padding=(0, 2))
    table.add_column(no_wrap=True, style="bold")
    table.add_column()
    for index, section in enumerate(sections):
        if index:
            table.add_row("", "")
        table.add_row(Text(section.title, style="bold underline"), "")
        for row in section.rows:
            table.add_row(Text(row.keys), Text(row.description))
    return table


class HelpScreen(ModalScreen[None]):
    """The keys of ``sections`` in a scrollable panel (arrows and PgUp/PgDn scroll it)."""

    DEFAULT_CSS = """
    HelpScreen {
        align: center middle;
    }
    HelpScreen > #help {
        width: 90%;
        max-width: 100;
        height: auto;
        max-height: 90%;
        border: round $accent;
        border-title-color: $accent;
        padding: 0 1;
        background: $surface;
    }
    HelpScreen #help-text {
        width: 100%;
    }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape", "close", "close help"),
        Binding("q", "close", "close help"),
        Binding("question_mark", "close", "close help"),
        Binding("f1", "close", "close help"),
    ]

    def __init__(self, sections: list[KeySection]) -> None:
        super().__init__()
        self.sections = sections

    def compose(self) -> ComposeResult:
        """The table of keys in a scrolling box."""
        with VerticalScroll(id="help"):
            yield Static(help_table(self.sections), id="help-text")

    def on_mount(self) -> None:
        """Title the box; the keyboard scrolls it."""
        box = self.query_one("#help", VerticalScroll)
        box.border_title = HELP_TITLE
        box.focus()

    @property
    def text(self) -> str:
        """Every key and description shown, as plain lines (for tests and screen readers)."""
        lines = []
        for section in self.sections:
            lines.append(section.title)
            lines += [f"{row.keys}  {row.description}" for row in section.rows]
        return "\n".join(lines)

    def action_close(self) -> None:
        """Back to the app."""
        self.dismiss(None)
