"""The statuses heard on /diagnostics_agg and /diagnostics: each one's last word, its age and its history.

A status is known by its name. The aggregator names its statuses as paths (``/Sensors/Laser/hokuyo: Connection``)
and publishes one for every group above them; the flat topic carries what each driver's updater says. The store
keeps, per name, the last status and when it came, and a short history of what it said: one entry per change of
level or message, with how many updates repeated it. A status not heard for ``stale_after`` seconds counts as
stale, as rqt_robot_monitor shows it, and so does one its sender marks STALE.

Everything is bounded, whatever a publisher sends: at most :data:`MAX_STATUSES` names per topic (the least
recently heard goes first), :data:`MAX_HISTORY` history entries per name, :data:`MAX_VALUES` key/values and
:data:`MAX_TEXT` characters per string kept.
"""

from __future__ import annotations

from collections import OrderedDict, deque
from dataclasses import dataclass, field
from typing import Any, Iterable

from .levels import STALE, severity

__all__ = ["HistoryEntry", "StatusRecord", "StatusTable", "DiagnosticsStore", "MAX_STATUSES", "MAX_HISTORY",
           "MAX_VALUES", "MAX_TEXT", "STALE_AFTER", "AGGREGATED", "FLAT"]

MAX_STATUSES = 5000
MAX_HISTORY = 50
MAX_VALUES = 200
MAX_TEXT = 1000

#: Seconds without news after which a status counts as stale.
STALE_AFTER = 5.0

AGGREGATED = "/diagnostics_agg"
FLAT = "/diagnostics"


def _clip(text: Any) -> str:
    text = text if isinstance(text, str) else str(text)
    return text if len(text) <= MAX_TEXT else text[:MAX_TEXT - 1] + "…"


@dataclass
class HistoryEntry:
    """A level and message a status said from ``since`` on, ``times`` updates in a row (until ``last``)."""

    since: float
    level: int
    message: str
    times: int = 1
    last: float = 0.0


@dataclass
class StatusRecord:
    """The last word of one status: level, message, hardware id, key/values, when it came, and its history."""

    name: str
    level: int
    message: str
    hardware_id: str
    values: tuple[tuple[str, str], ...]
    received: float
    updates: int = 1
    history: deque[HistoryEntry] = field(default_factory=lambda: deque(maxlen=MAX_HISTORY))

    def level_at(self, now: float, stale_after: float = STALE_AFTER) -> int:
        """The level to show at ``now``: STALE when the sender said so or nothing came for ``stale_after`` s."""
        return STALE if now - self.received > stale_after else self.level

    def age(self, now: float) -> float:
        """Seconds since the last update."""
        return max(0.0, now - self.received)


class StatusTable:
    """The statuses of one topic by name, the least recently heard first (so the oldest goes when it is full)."""

    def __init__(self, limit: int = MAX_STATUSES) -> None:
        self.limit = limit
        self.records: OrderedDict[str, StatusRecord] = OrderedDict()
        self.messages = 0
        self.stamp: float | None = None
        """The header stamp of the last message (seconds)."""
        self.dropped = 0
        """Names forgotten to keep within :attr:`limit`."""

    def take(self, statuses: Iterable[Any], received: float, stamp: float | None = None) -> None:
        """Add one DiagnosticArray's statuses (anything with name, level, message, hardware_id and values) and
        its header's ``stamp``."""
        self.messages += 1
        self.stamp = stamp
        for status in statuses:
            name = _clip(status.name)
            level = int(status.level)
            message = _clip(status.message)
            values = tuple((_clip(kv.key), _clip(kv.value)) for kv in list(status.values)[:MAX_VALUES])
            record = self.records.pop(name, None)
            if record is None:
                record = StatusRecord(name, level, message, _clip(status.hardware_id), values, received)
                record.history.append(HistoryEntry(received, level, message, last=received))
            else:
                last = record.history[-1] if record.history else None
                if last is not None and last.level == level and last.message == message \
                        and record.level_at(received) != STALE:
                    last.times += 1
                    last.last = received
                else:
                    record.history.append(HistoryEntry(received, level, message, last=received))
                record.level, record.message, record.values = level, message, values
                record.hardware_id = _clip(status.hardware_id)
                record.received = received
                record.updates += 1
            self.records[name] = record
            while len(self.records) > self.limit:
                self.records.popitem(last=False)
                self.dropped += 1

    def __len__(self) -> int:
        return len(self.records)

    def get(self, name: str) -> StatusRecord | None:
        """The status called ``name``, if heard."""
        return self.records.get(name)


class DiagnosticsStore:
    """The statuses of each topic heard: :attr:`aggregated` (/diagnostics_agg), :attr:`flat` (/diagnostics), and
    any other topic a user names."""

    def __init__(self, limit: int = MAX_STATUSES, stale_after: float = STALE_AFTER) -> None:
        self.limit = limit
        self.tables: dict[str, StatusTable] = {AGGREGATED: StatusTable(limit), FLAT: StatusTable(limit)}
        self.stale_after = stale_after

    @property
    def aggregated(self) -> StatusTable:
        """The aggregator's statuses."""
        return self.tables[AGGREGATED]

    @property
    def flat(self) -> StatusTable:
        """The statuses of /diagnostics."""
        return self.tables[FLAT]

    def table(self, topic: str) -> StatusTable:
        """The table of ``topic`` (made empty when it is new)."""
        if topic not in self.tables:
            self.tables[topic] = StatusTable(self.limit)
        return self.tables[topic]

    def take(self, topic: str, statuses: Iterable[Any], received: float, stamp: float | None = None) -> None:
        """Add one DiagnosticArray heard on ``topic`` (its statuses and header stamp)."""
        self.table(topic).take(statuses, received, stamp)

    @property
    def has_aggregator(self) -> bool:
        """Whether the aggregator's topic has said anything."""
        return self.aggregated.messages > 0

    def worst(self, topic: str, now: float) -> int | None:
        """The worst level of ``topic``'s statuses at ``now`` (None before any)."""
        levels = [record.level_at(now, self.stale_after) for record in self.table(topic).records.values()]
        return max(levels, key=severity) if levels else None
