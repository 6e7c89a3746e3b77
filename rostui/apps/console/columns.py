"""The console table's columns: which fit in a width, and each message's cell texts.

rqt_console's columns, in its order: ``#``, message, severity, node, stamp,
topics, location.  The message column takes what the others leave; on a
narrow terminal location, topics and stamp give way first (the detail pane
still shows them).  Stamps are local wall-clock times (``HH:MM:SS.mmm``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

from rich.cells import cell_len, set_cell_size

from rostui.core.log.rosout_read import RosoutEntry

__all__ = ["Column", "Layout", "cell", "clock_text", "layout_for", "printable", "row_texts"]

#: Narrowest message column before optional columns are dropped.
MIN_MESSAGE = 40

#: Space between two columns.
GAP = 1


@dataclass(frozen=True)
class Column:
    """One column: key (``seq``, ``message``...), title and width in cells."""

    key: str
    title: str
    width: int


@dataclass(frozen=True)
class Layout:
    """The columns shown at one width, left to right."""

    columns: tuple[Column, ...]
    width: int

    @property
    def keys(self) -> tuple[str, ...]:
        """The column keys, in order."""
        return tuple(c.key for c in self.columns)


#: Optional columns in the order they are dropped when space runs out.
_DROP_ORDER = ("location", "topics", "stamp")


def layout_for(width: int, seq_digits: int, node_width: int) -> Layout:
    """The columns for a table ``width`` cells wide.

    ``seq_digits`` is the width of the largest ``#``; ``node_width`` the
    longest node name shown (clamped to 8..28).
    """
    widths = {
        "seq": max(3, seq_digits),
        "message": 0,
        "severity": 5,
        "node": min(max(node_width, 8), 28),
        "stamp": 12,
        "topics": 16,
        "location": 24,
    }
    titles = {"seq": "#", "message": "Message", "severity": "Sev", "node": "Node", "stamp": "Stamp",
              "topics": "Topics", "location": "Location"}
    keys = ["seq", "message", "severity", "node", "stamp", "topics", "location"]

    def others(ks: list[str]) -> int:
        return sum(widths[k] for k in ks if k != "message") + GAP * (len(ks) - 1)

    for key in _DROP_ORDER:
        if width - others(keys) >= MIN_MESSAGE:
            break
        keys.remove(key)
    if width - others(keys) < MIN_MESSAGE:  # very narrow: give the node column what is left over
        widths["node"] = max(4, min(widths["node"], width - MIN_MESSAGE - others([k for k in keys if k != "node"])
                                    - GAP))
    widths["message"] = max(1, width - others(keys))
    return Layout(tuple(Column(k, titles[k], widths[k]) for k in keys), width)


@lru_cache(maxsize=4096)
def clock_text(secs: int) -> str:
    """``HH:MM:SS`` of a stamp's whole seconds in local time."""
    return time.strftime("%H:%M:%S", time.localtime(secs))


def stamp_cell(stamp: int) -> str:
    """A stamp as ``HH:MM:SS.mmm`` local time."""
    secs, nsecs = divmod(stamp, 1_000_000_000)
    return f"{clock_text(secs)}.{nsecs // 1_000_000:03d}"


def one_line(text: str) -> str:
    """The first line of a message, with ``⏎`` when more lines follow."""
    first, newline, _ = text.partition("\n")
    return f"{first} ⏎" if newline else first


#: Control characters shown as their Unicode pictures (tab as a space), so none reaches the terminal.
_VISIBLE_CONTROLS = {code: chr(0x2400 + code) for code in range(32)} | {9: " ", 0x7F: "\u2421"}


def printable(text: str, keep_newlines: bool = False) -> str:
    """``text`` with control characters (and tabs) replaced by visible ones; newlines kept if asked."""
    if text.isprintable():
        return text
    table = _VISIBLE_CONTROLS if not keep_newlines else {**_VISIBLE_CONTROLS, 10: "\n"}
    return text.translate(table)


def cell(text: str, width: int) -> str:
    """``text`` padded or cut to exactly ``width`` cells (``…`` marks a cut); control characters made visible."""
    if width <= 0:
        return ""
    if len(text) <= width and text.isascii() and text.isprintable():
        return text.ljust(width)
    text = text.translate(_VISIBLE_CONTROLS)
    if cell_len(text) <= width:
        return set_cell_size(text, width)
    return set_cell_size(text, width - 1) + "…"


def row_texts(seq: int, entry: RosoutEntry) -> dict[str, str]:
    """Each column's text for one message (before padding)."""
    return {
        "seq": str(seq + 1),
        "message": one_line(entry.message),
        "severity": entry.level_name,
        "node": entry.node,
        "stamp": stamp_cell(entry.stamp),
        "topics": ",".join(entry.topics),
        "location": entry.location,
    }
