"""ConfirmScreen: a question over the app that only ``y`` answers yes to; ``n``, Escape or ``q`` say no."""

from __future__ import annotations

from typing import ClassVar

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.screen import ModalScreen
from textual.widgets import Static

__all__ = ["ConfirmScreen"]


class ConfirmScreen(ModalScreen[bool]):
    """Asks ``question`` (plain text); dismissed with True on ``y``, False on ``n``, Escape or ``q``."""

    DEFAULT_CSS = """
    ConfirmScreen {
        align: center middle;
    }
    ConfirmScreen > #question {
        width: auto;
        max-width: 90%;
        height: auto;
        border: round $warning;
        border-title-color: $warning;
        padding: 0 1;
        background: $surface;
    }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("y", "answer(True)", "yes"),
        Binding("n", "answer(False)", "no"),
        Binding("escape", "answer(False)", "no"),
        Binding("q", "answer(False)", "no"),
    ]

    def __init__(self, question: str, title: str = "confirm · y yes · n or Esc no") -> None:
        super().__init__()
        self.question = question
        self.title_text = title

    def compose(self) -> ComposeResult:
        """The question in a box."""
        yield Static(Text(self.question), id="question")

    def on_mount(self) -> None:
        """Title the box with the keys."""
        self.query_one("#question").border_title = self.title_text

    def action_answer(self, yes: bool) -> None:
        """y: True; n, Escape, q: False."""
        self.dismiss(yes)
