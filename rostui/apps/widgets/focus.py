"""Give a widget the keyboard before the next key is handled.

Textual's ``Widget.focus()`` moves the focus in a callback queued behind the
events already waiting.  Keys that arrive in the same burst as the key that
opened a prompt (fast typing, a paste, an SSH connection delivering a batch)
then reach the old widget: "/cmd" became "/" plus the table's c, m, d.
"""

from __future__ import annotations

from textual.widget import Widget

__all__ = ["focus_now"]


def focus_now(widget: Widget) -> None:
    """Focus ``widget`` at once, so every key handled after this call goes to it."""
    widget.screen.set_focus(widget)
