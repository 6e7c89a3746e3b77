"""Keys that reach an app in one burst, as a fast typist, a paste or an SSH connection delivers them.

Textual's ``pilot.press`` lets the app go idle after every key, so it never
shows what happens when the next key is already waiting while the first one
is handled.  ``press_in_one_burst`` queues all keys at once.
"""

from __future__ import annotations

import unicodedata

from textual import events
from textual.app import App
from textual.keys import REPLACED_KEYS, _character_to_key, _get_unicode_name_from_key

__all__ = ["press_in_one_burst"]


def key_event(key: str) -> events.Key:
    """The Key event Textual's driver makes for ``key`` (a name such as "slash" or one character)."""
    if len(key) == 1 and not key.isalnum():
        key = _character_to_key(key)
    try:
        character: str | None = unicodedata.lookup(_get_unicode_name_from_key(REPLACED_KEYS.get(key, key)))
    except KeyError:
        character = key if len(key) == 1 else None
    return events.Key(key, character)


def press_in_one_burst(app: App[object], *keys: str) -> None:
    """Queue every key on ``app`` before it handles the first; the caller waits for what they should do."""
    for key in keys:
        event = key_event(key)
        event.set_sender(app)
        app.post_message(event)
