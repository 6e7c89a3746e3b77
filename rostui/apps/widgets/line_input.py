"""LineInput: Textual's one-line Input whose editing keys act in the order they were typed.

Textual's Input inserts a printable key as soon as it gets it, but its editing keys (ctrl+u, backspace,
arrows, Enter) are bindings: the key travels up through each parent's queue and runs at the app.  Keys that
come in one burst (a paste, tmux's send-keys, a fast typist over SSH) then overtake each other: ctrl+u then
``True`` and Enter left the field empty, because the letters were in before ctrl+u cleared the line (a
form's expression lost in CI).  Here the field runs its own bindings as it meets their keys, so every key
acts in turn.  Keys the field has no binding for still go up to the screen and the app (Escape, ctrl+s).
"""

from __future__ import annotations

from textual import events
from textual.widgets import Input

__all__ = ["LineInput"]


class LineInput(Input):
    """An Input whose own key bindings run at once, in the order of the keys (see the module's docstring)."""

    async def _on_key(self, event: events.Key) -> None:
        if not event.is_printable:
            bindings = self._bindings.key_to_bindings.get(event.key, ())
            if bindings:
                event.stop()
                event.prevent_default()
                await self.run_action(bindings[0].action)
                return
        await super()._on_key(event)
