"""Notice: one line under a panel saying what it shows, a change made, or (in red) what went wrong, so errors
appear where the user is looking."""

from __future__ import annotations

from rich.text import Text
from textual.widgets import Static

__all__ = ["NOTICE_KINDS", "Notice"]

#: Notice kinds and the CSS class each one sets.
NOTICE_KINDS = ("info", "ok", "error")


class Notice(Static):
    """One line under a panel: what it shows (``info``), a change made (``ok``) or an ``error``."""

    DEFAULT_CSS = """
    Notice {
        height: auto;
        max-height: 4;
        padding: 0 1;
        color: $text-muted;
    }
    Notice.-ok {
        color: $success;
    }
    Notice.-error {
        color: $error;
        text-style: bold;
    }
    """

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__("", id=id, markup=False)
        self.text = ""
        self.kind = "info"

    def say(self, text: str, kind: str = "info") -> None:
        """Show ``text`` styled as ``kind`` (one of :data:`NOTICE_KINDS`)."""
        if kind not in NOTICE_KINDS:
            raise ValueError(f"unknown notice kind {kind!r}")
        self.text, self.kind = text, kind
        for other in NOTICE_KINDS:
            self.set_class(other == kind, f"-{other}")
        self.update(Text(text))
