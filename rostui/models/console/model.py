"""The console's data: a bounded ring of messages and the filtered rows over it.

Messages get a sequence number when they arrive (the ``#`` column is that
number plus one).  The ring keeps the newest ``capacity`` of them; older ones
are dropped and counted.  The rows are the sequence numbers that pass the
filter, in order, so filtering never copies messages and a row is found by
bisection.  While paused, arriving messages wait in a buffer (also bounded)
and the rows stay as they were.  Nothing here knows Textual.

Messages are kept as plain tuples (a RosoutEntry's fields): the garbage
collector stops tracking exact tuples of strings and numbers, so a full ring
adds nothing to its pauses (a NamedTuple would be traversed on every full
collection, costing 100-200 ms at 100 000 messages).
"""

from __future__ import annotations

from bisect import bisect_left
from collections import Counter, deque
from dataclasses import dataclass
from itertools import compress
from typing import Iterable, Iterator

from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry
from rostui.models.console.filters import ALL_LEVELS, LEVEL, NODE, FilterSpec, Selector, compile_selector

__all__ = ["ConsoleModel", "ConsoleOptions"]

#: Messages kept when no --max is given.
DEFAULT_CAPACITY = 100_000

#: Row-list entries skipped at the front before the list is compacted.
_COMPACT_AT = 4096


@dataclass(frozen=True)
class ConsoleOptions:
    """How the console starts: minimum level kept, capacity, and the first filters."""

    min_level: Level = Level.DEBUG
    max_messages: int = DEFAULT_CAPACITY
    include_nodes: tuple[str, ...] = ()
    exclude_nodes: tuple[str, ...] = ()
    search: str = ""
    regex: bool = False

    def filter_spec(self) -> FilterSpec:
        """The filters these options start with."""
        return FilterSpec(include_nodes=frozenset(self.include_nodes), exclude_nodes=frozenset(self.exclude_nodes),
                          search=self.search, regex=self.regex)


class ConsoleModel:
    """Messages kept, the rows shown, and the counters the status line reports.

    ``min_level``: messages below it are not kept at all (counted in
    ``below_level``), so a flood of DEBUG cannot push warnings out; a level
    outside DEBUG..FATAL cannot be ranked and is always kept.
    ``received`` counts every message kept or buffered; ``dropped`` the oldest
    ones pushed out by ``capacity`` (in the ring or the pause buffer);
    ``version`` changes whenever the rows do.
    """

    def __init__(self, capacity: int = DEFAULT_CAPACITY, *, min_level: int = Level.DEBUG,
                 spec: FilterSpec | None = None) -> None:
        if capacity < 1:
            raise ValueError(f"capacity must be at least 1, got {capacity}")
        self.capacity = capacity
        self.min_level = int(min_level)
        self.spec = spec or FilterSpec()
        self._select: Selector | None = compile_selector(self.spec)
        self._slots: list[tuple] = []  # slot seq % capacity; only those of first..end-1 are read
        self.first = 0
        self.end = 0
        self._rows: list[int] = []
        self._head = 0
        self.paused = False
        self._pending: deque[tuple] = deque()
        self.received = 0
        self.below_level = 0
        self.dropped = 0
        self.level_counts: Counter[int] = Counter()
        self.node_names: set[str] = set()
        self.longest_node = 0
        self.version = 0

    # -- messages ------------------------------------------------------------------------------
    def __len__(self) -> int:
        """Rows shown."""
        return len(self._rows) - self._head

    @property
    def kept(self) -> int:
        """Messages in the ring (shown or not)."""
        return self.end - self.first

    @property
    def pending(self) -> int:
        """Messages that arrived while paused and are not shown yet."""
        return len(self._pending)

    def entry(self, seq: int) -> RosoutEntry:
        """The message with sequence number ``seq`` (must still be kept)."""
        if not self.first <= seq < self.end:
            raise IndexError(f"message {seq} is not kept (kept: {self.first}..{self.end - 1})")
        return RosoutEntry._make(self._slots[seq % self.capacity])

    def seq_at(self, row: int) -> int:
        """The sequence number shown in ``row`` (0 = oldest shown)."""
        if not 0 <= row < len(self):
            raise IndexError(f"row {row} out of range (0..{len(self) - 1})")
        return self._rows[self._head + row]

    def row_of(self, seq: int) -> int:
        """The row showing ``seq``, or the row of the next newer message shown (``len`` if none)."""
        return bisect_left(self._rows, seq, self._head) - self._head

    def shown(self) -> Iterator[tuple[int, RosoutEntry]]:
        """(sequence number, message) of every row, oldest first."""
        slots, capacity = self._slots, self.capacity
        for index in range(self._head, len(self._rows)):
            seq = self._rows[index]
            yield seq, RosoutEntry._make(slots[seq % capacity])

    def ingest(self, entries: Iterable[tuple]) -> int:
        """Take one batch of arriving messages (RosoutEntry or its plain tuple); returns how many were kept."""
        min_level = self.min_level
        taken = 0
        if self.paused:
            pending = self._pending
            for entry in entries:
                if entry[LEVEL] < min_level and entry[LEVEL] in ALL_LEVELS:
                    self.below_level += 1
                    continue
                pending.append(tuple(entry))
                taken += 1
            overflow = len(pending) - self.capacity
            for _ in range(max(0, overflow)):
                pending.popleft()
            self.dropped += max(0, overflow)
            self.received += taken
            return taken
        slots, capacity = self._slots, self.capacity
        counts, node_names = self.level_counts, self.node_names
        first, end = self.first, self.end
        start = end
        batch: list[tuple] = []
        dropped = below = 0
        for entry in entries:
            level = entry[LEVEL]
            if level < min_level and level in ALL_LEVELS:
                below += 1
                continue
            fields = tuple(entry)
            slot = end % capacity
            if end - first >= capacity:
                counts[slots[slot][LEVEL]] -= 1
                slots[slot] = fields
                first += 1
                dropped += 1
            elif slot < len(slots):
                slots[slot] = fields
            else:
                slots.append(fields)
            counts[level] += 1
            node = fields[NODE]
            if node not in node_names:
                node_names.add(node)
                self.longest_node = max(self.longest_node, len(node))
            batch.append(fields)
            end += 1
            taken += 1
        self.first, self.end = first, end
        new_seqs = range(start, end)
        self._rows.extend(new_seqs if self._select is None else compress(new_seqs, self._select(batch)))
        self.below_level += below
        self.received += taken
        if dropped:
            self.dropped += dropped
            self._trim()
        if taken:
            self.version += 1
        return taken

    def _trim(self) -> None:
        head = bisect_left(self._rows, self.first, self._head)
        if head >= _COMPACT_AT and head * 2 > len(self._rows):
            del self._rows[:head]
            head = 0
        self._head = head

    # -- pause, clear, filters -----------------------------------------------------------------
    def pause(self) -> None:
        """Freeze the rows; arriving messages wait in the buffer."""
        self.paused = True

    def resume(self) -> int:
        """Show what arrived while paused; returns how many messages that was."""
        if not self.paused:
            return 0
        self.paused = False
        waiting, self._pending = self._pending, deque()
        self.received -= len(waiting)  # counted when they arrived
        return self.ingest(waiting)

    def clear(self) -> None:
        """Forget every kept message (numbering goes on; the pause buffer stays)."""
        self._slots = [()] * len(self._slots)  # frees the messages, keeps slot = seq % capacity
        self.first = self.end
        self._rows = []
        self._head = 0
        self.level_counts.clear()
        self.node_names.clear()
        self.longest_node = 0
        self.version += 1

    def set_filter(self, spec: FilterSpec) -> None:
        """Show the messages passing ``spec``; raises FilterError (and changes nothing) for a bad regex."""
        select = compile_selector(spec)
        self.spec = spec
        self._select = select
        kept = range(self.first, self.end)
        self._rows = list(kept if select is None else compress(kept, select(self._kept_fields())))
        self._head = 0
        self.version += 1

    def _kept_fields(self) -> list[tuple]:
        """The kept messages' tuples, oldest first."""
        start, count = self.first % self.capacity, self.end - self.first
        slots = self._slots
        if start + count <= len(slots):
            return slots[start:start + count]
        return slots[start:] + slots[:start + count - len(slots)]

    def set_min_level(self, level: int) -> None:
        """Keep messages at or above ``level`` from now on (kept ones stay)."""
        self.min_level = int(level)

    def nodes(self) -> list[str]:
        """Every node a kept message came from since the start (or the last clear), sorted."""
        return sorted(self.node_names)
