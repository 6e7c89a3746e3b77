"""What a page may send up its websocket, read strictly, and the terminal sizes it may ask for.

The page (textual-serve's textual.js) sends JSON arrays: ``["stdin", text]``, ``["resize",
{"width": W, "height": H}]``, ``["ping", text]``, ``["focus"]`` and ``["blur"]``.  Anything else
is :class:`BadMessage`, and a size is clamped to :data:`MAX_COLUMNS` x :data:`MAX_ROWS`: the app
allocates for every cell, so a tab asking for 100000 x 100000 gets the largest sane screen instead.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Union

#: The widest terminal an app is given (a 4K screen at 6 px a column is 640 columns).
MAX_COLUMNS = 640

#: The tallest terminal an app is given (a 4K screen at 12 px a row is 180 rows).
MAX_ROWS = 240

#: The size an app gets when the page does not say (or says nonsense) when it connects.
DEFAULT_SIZE = (80, 24)


class BadMessage(ValueError):
    """A websocket message the page never sends."""


@dataclass(frozen=True)
class Stdin:
    """Keys and pastes, as the terminal encodes them."""

    text: str


@dataclass(frozen=True)
class Resize:
    """The page's terminal has a new size (already clamped)."""

    width: int
    height: int


@dataclass(frozen=True)
class Ping:
    """The page measures its round trip; the text comes back in a ``pong``."""

    text: str


@dataclass(frozen=True)
class Focus:
    """The page gained (``True``) or lost the focus."""

    focused: bool


Message = Union[Stdin, Resize, Ping, Focus]


def _cells(value: object, most: int) -> int:
    """A count of cells between 1 and ``most``, or :class:`BadMessage`."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise BadMessage(f"a terminal size must be a whole number, not {str(value)[:20]!r}")
    return max(1, min(value, most))


def clamp_size(width: object, height: object) -> tuple[int, int]:
    """``(columns, rows)`` within 1..:data:`MAX_COLUMNS` and 1..:data:`MAX_ROWS`, or :class:`BadMessage`."""
    return _cells(width, MAX_COLUMNS), _cells(height, MAX_ROWS)


def size_from_query(width: str | None, height: str | None) -> tuple[int, int]:
    """The first size, from the websocket URL's ``width`` and ``height`` (text): clamped, or the default."""
    try:
        return clamp_size(int(width or ""), int(height or ""))
    except ValueError:  # BadMessage included
        return DEFAULT_SIZE


def parse(text: str) -> Message:
    """One text frame from the page, or :class:`BadMessage` saying what was wrong with it."""
    try:
        envelope = json.loads(text)
    except (ValueError, RecursionError):
        raise BadMessage("a message that is not JSON") from None
    if not isinstance(envelope, list) or not envelope or not isinstance(envelope[0], str):
        raise BadMessage("a message that is not [kind, ...]")
    kind, arguments = envelope[0], envelope[1:]
    if kind in ("focus", "blur") and not arguments:
        return Focus(kind == "focus")
    if len(arguments) != 1:
        raise BadMessage(f"a {kind[:20]!r} message with {len(arguments)} arguments")
    argument = arguments[0]
    if kind == "stdin" and isinstance(argument, str):
        return Stdin(argument)
    if kind == "ping" and isinstance(argument, str):
        return Ping(argument[:64])
    if kind == "resize" and isinstance(argument, dict):
        return Resize(*clamp_size(argument.get("width"), argument.get("height")))
    raise BadMessage(f"a {kind[:20]!r} message the page does not send")
