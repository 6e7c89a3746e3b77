"""The monitor's table as data: one row per topic, its columns as text, sorting and filtering.

A row joins what the master says (type, publishers, subscribers) with what
the monitor measured (:class:`~rostui.models.monitor.stats.Sample`) and the
topic's liveness (:class:`Liveness`).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Iterable, Sequence

from rostui.tools.topic.rates import bandwidth_unit

__all__ = ["Liveness", "TopicRow", "Column", "COLUMNS", "sort_rows", "filter_rows", "rate_text",
           "bandwidth_text", "age_text"]


class Liveness(str, Enum):
    """Whether a topic's messages are arriving, as the live column shows it."""

    LIVE = "live"
    """Subscribed, messages arriving."""
    WAITING = "waiting"
    """Subscribed, publishers registered, no message yet."""
    STALE = "stale"
    """Messages came, then stopped (the publishers died or went quiet)."""
    NO_PUBLISHERS = "no publishers"
    """Nobody publishes the topic."""
    OFF = "off"
    """Not subscribed (not on screen), so not measured."""

    @property
    def mark(self) -> str:
        """The symbol and word shown in the live column."""
        return {"live": "● live", "waiting": "… waiting", "stale": "✖ stale", "no publishers": "· no pubs",
                "off": ""}[self.value]


@dataclass(frozen=True)
class TopicRow:
    """One topic as the table shows it."""

    name: str
    type: str
    publishers: tuple[str, ...]
    subscribers: tuple[str, ...]
    rate: float | None = None
    bandwidth: float | None = None
    age: float | None = None
    liveness: Liveness = Liveness.OFF

    def cells(self) -> tuple[str, ...]:
        """The row's text, column by column (in :data:`COLUMNS` order)."""
        return (self.name, self.type, str(len(self.publishers)), str(len(self.subscribers)), rate_text(self.rate),
                bandwidth_text(self.bandwidth), age_text(self.age), self.liveness.mark)


class Column(str, Enum):
    """The table's columns, in order; the sort key cycles through them."""

    TOPIC = "topic"
    TYPE = "type"
    PUBS = "pubs"
    SUBS = "subs"
    RATE = "rate"
    BANDWIDTH = "bandwidth"
    AGE = "age"
    LIVE = "live"

    def next(self) -> "Column":
        """The column after this one (the last wraps to the first)."""
        members = list(Column)
        return members[(members.index(self) + 1) % len(members)]


#: Column headers as shown.
COLUMNS: tuple[str, ...] = ("topic", "type", "pubs", "subs", "rate (Hz)", "bandwidth", "age", "live")

_LIVENESS_ORDER = {Liveness.LIVE: 0, Liveness.WAITING: 1, Liveness.STALE: 2, Liveness.NO_PUBLISHERS: 3,
                   Liveness.OFF: 4}


def _sort_key(row: TopicRow, column: Column) -> tuple:
    """Numbers sort biggest first; rows without a figure go last; ties by name."""
    if column is Column.TOPIC:
        return (row.name,)
    if column is Column.TYPE:
        return (row.type, row.name)
    if column is Column.PUBS:
        return (-len(row.publishers), row.name)
    if column is Column.SUBS:
        return (-len(row.subscribers), row.name)
    if column is Column.LIVE:
        return (_LIVENESS_ORDER[row.liveness], row.name)
    value = {Column.RATE: row.rate, Column.BANDWIDTH: row.bandwidth, Column.AGE: row.age}[column]
    if value is None:
        return (1, 0.0, row.name)
    return (0, value if column is Column.AGE else -value, row.name)


def sort_rows(rows: Iterable[TopicRow], column: Column, reverse: bool = False) -> list[TopicRow]:
    """Rows sorted by ``column`` (names A-Z, numbers biggest first, ages youngest first); ``reverse`` flips."""
    out = sorted(rows, key=lambda r: _sort_key(r, column))
    return out[::-1] if reverse else out


def filter_rows(rows: Iterable[TopicRow], text: str) -> list[TopicRow]:
    """Rows whose topic name or type contains ``text`` (any case); all rows for empty text."""
    needle = text.strip().lower()
    if not needle:
        return list(rows)
    return [r for r in rows if needle in r.name.lower() or needle in r.type.lower()]


def rate_text(rate: float | None) -> str:
    """``100.0`` (Hz, to four significant figures), or ``-`` without a rate."""
    if rate is None:
        return "-"
    if rate >= 1000:
        return f"{rate:.0f}"
    if rate >= 100:
        return f"{rate:.1f}"
    if rate >= 10:
        return f"{rate:.2f}"
    return f"{rate:.3f}"


def bandwidth_text(bps: float | None) -> str:
    """Bytes per second as rostopic bw scales them: ``512.00B/s``, ``3.20KB/s``, ``1.05MB/s``."""
    if bps is None:
        return "-"
    divisor, unit = bandwidth_unit(bps)
    return f"{bps / divisor:.2f}{unit}/s"


def age_text(age: float | None) -> str:
    """Seconds since the last message: ``0.01s``, ``12.3s``, ``4m05s``; ``-`` before any."""
    if age is None:
        return "-"
    if age < 10:
        return f"{age:.2f}s"
    if age < 60:
        return f"{age:.1f}s"
    minutes, seconds = divmod(int(age), 60)
    if minutes < 60:
        return f"{minutes}m{seconds:02d}s"
    return f"{minutes // 60}h{minutes % 60:02d}m"


def topic_names(rows: Sequence[TopicRow]) -> list[str]:
    """The topic names of ``rows``, in order."""
    return [r.name for r in rows]
