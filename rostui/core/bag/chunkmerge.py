"""The chunks of one or more bag files in time order, their entries read on demand, and an exact merge over them.

A :class:`ChunkTable` holds one row per chunk of every file (first and last
message time, file, chunk number, message count), sorted by first time. A
chunk's entries (time, connection, offset of each message) are read from its
file's index when a seek, a step or a search needs them and kept in a
least-recently-used cache of at most :data:`ENTRY_BUDGET` entries (the chunk
in use is always kept), so memory follows the number of chunks, not of
messages.

Chunks may overlap in time (a file written out of order, several files
recorded together): :class:`MergeCursor` merges the entries of the chunks
whose spans reach the cursor, bringing each later chunk in just before the
merge could pass its first time, so messages come in exact time order; equal
times keep the order of the files given, then of chunks in a file, then of
records in a chunk.
"""

from __future__ import annotations

import heapq
import os
from collections import OrderedDict
from collections.abc import Callable
from typing import Any, NamedTuple

from rostui.core.bag.fileindex import ChunkEntries
from rostui.core.bag.model import BagError

ENTRY_BUDGET = int(os.environ.get("ROSTUI_BAG_INDEX_ENTRIES", str(1 << 16)))
"""How many chunk entries (about 20 bytes each) bag view keeps read; the chunk in use is always kept."""


class MessageRef(NamedTuple):
    """Where one message lies: its time, file (position in the files given), chunk number, offset, connection id.

    The first four order messages: time, then file, chunk and offset break ties.
    """

    time: int
    file: int
    chunk: int
    offset: int
    conn_id: int


class ChunkTable:
    """Every chunk of the files, one row each, sorted by (first time, file, chunk number); ``load(file, chunk)``
    reads a chunk's sorted entries, and :meth:`entries` keeps them within ``budget`` entries."""

    def __init__(self, starts: Any, ends: Any, files: Any, numbers: Any, counts: Any,
                 load: Callable[[int, int], ChunkEntries], budget: int = ENTRY_BUDGET,
                 pinned: dict[int, ChunkEntries] | None = None) -> None:
        self.starts = starts
        self.ends = ends
        self.files = files
        self.numbers = numbers
        self.counts = counts
        self.budget = budget
        self._load = load
        self._pinned = pinned or {}
        self._held: OrderedDict[int, ChunkEntries] = OrderedDict()
        self._held_entries = 0
        self.loads = 0
        """How many times a chunk's entries were read (a test's measure of the cache)."""

    def __len__(self) -> int:
        return int(self.starts.shape[0])

    @property
    def held_entries(self) -> int:
        """Entries held in the cache now (messages outside chunks, always held, not counted)."""
        return self._held_entries

    @property
    def held_chunks(self) -> int:
        """Chunks whose entries the cache holds now."""
        return len(self._held)

    def entries(self, row: int) -> ChunkEntries:
        """Row ``row``'s entries sorted by time, then offset; BagError when they cannot be read."""
        pinned = self._pinned.get(row)
        if pinned is not None:
            return pinned
        held = self._held.get(row)
        if held is not None:
            self._held.move_to_end(row)
            return held
        entries = self._load(int(self.files[row]), int(self.numbers[row]))
        self.loads += 1
        self._held[row] = entries
        self._held_entries += len(entries.times)
        while self._held_entries > self.budget and len(self._held) > 1:
            _, dropped = self._held.popitem(last=False)
            self._held_entries -= len(dropped.times)
        return entries

    def ref(self, row: int, i: int, entries: ChunkEntries) -> MessageRef:
        """The reference of entry ``i`` of row ``row``."""
        return MessageRef(int(entries.times[i]), int(self.files[row]), int(self.numbers[row]),
                          int(entries.offsets[i]), int(entries.conn_ids[i]))


class MergeCursor:
    """The messages of a :class:`ChunkTable` from a time on, one at a time, in exact time order.

    Holds only a position per chunk in the merge; entries come from the table's cache. A chunk whose entries
    cannot be read is passed over, and :attr:`problem` keeps its error line.
    """

    def __init__(self, table: ChunkTable, t_ns: int) -> None:
        import numpy as np

        self.table = table
        self.problem = ""
        """The one-line error of the last chunk whose entries could not be read ('' while none)."""
        self._heap: list[tuple[int, int, int, int, int, int]] = []
        self._next_row = int(np.searchsorted(table.starts, t_ns, side="right"))
        reaching = np.flatnonzero(table.ends[:self._next_row] >= t_ns)
        for row in reaching.tolist():
            entries = self._entries(row)
            if entries is not None:
                self._push(row, int(np.searchsorted(entries.times, t_ns, side="left")), entries)

    def _entries(self, row: int) -> ChunkEntries | None:
        try:
            return self.table.entries(row)
        except BagError as exc:
            self.problem = str(exc)
            return None

    def _push(self, row: int, i: int, entries: ChunkEntries) -> None:
        if i < len(entries.times):
            table = self.table
            heapq.heappush(self._heap, (int(entries.times[i]), int(table.files[row]), int(table.numbers[row]),
                                        int(entries.offsets[i]), row, i))

    def _fill(self) -> None:
        """Bring in every chunk that starts no later than the earliest message held (ties may sort before it)."""
        table, heap = self.table, self._heap
        while self._next_row < len(table) and (not heap or int(table.starts[self._next_row]) <= heap[0][0]):
            row = self._next_row
            self._next_row += 1
            entries = self._entries(row)
            if entries is not None:
                self._push(row, 0, entries)

    def peek(self) -> MessageRef | None:
        """The next message, or None at the end."""
        while True:
            self._fill()
            if not self._heap:
                return None
            t, file, chunk, offset, row, i = self._heap[0]
            entries = self._entries(row)
            if entries is not None:
                return MessageRef(t, file, chunk, offset, int(entries.conn_ids[i]))
            heapq.heappop(self._heap)

    def advance(self) -> None:
        """Move past the next message."""
        self._fill()
        if self._heap:
            _t, _file, _chunk, _offset, row, i = heapq.heappop(self._heap)
            entries = self._entries(row)
            if entries is not None:
                self._push(row, i + 1, entries)
