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
records in a chunk. A table made ``by_connection`` (rosbag's Python API, which merges one index per
connection) breaks ties by connection id first. :func:`merged_batches` gives the same order a block of
messages at a time, for readers that go through a whole bag (the rosbag API's ``read_messages``).
"""

from __future__ import annotations

import heapq
import os
from collections import OrderedDict
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

from rostui.core.bag.fileindex import NO_CHUNK, ChunkEntries
from rostui.core.bag.model import BagError

if TYPE_CHECKING:
    from rostui.core.bag.chunkinfo import ChunkInfos

ENTRY_BUDGET = int(os.environ.get("ROSTUI_BAG_INDEX_ENTRIES", str(1 << 16)))
"""How many chunk entries (about 20 bytes each) bag view keeps read; the chunk in use is always kept."""

BATCH = 8192
"""How many messages :func:`merged_batches` gives at a time (more when that many share one time)."""


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
    reads a chunk's sorted entries, and :meth:`entries` keeps them within ``budget`` entries.

    ``by_connection``: equal times order by connection id before file, chunk and offset (rosbag's Python API
    merges one index per connection); a chunk's entries are then sorted that way as they are read.
    """

    def __init__(self, starts: Any, ends: Any, files: Any, numbers: Any, counts: Any,
                 load: Callable[[int, int], ChunkEntries], budget: int = ENTRY_BUDGET,
                 pinned: dict[int, ChunkEntries] | None = None, by_connection: bool = False) -> None:
        self.by_connection = by_connection
        if by_connection:
            pinned = {row: connection_ordered(entries) for row, entries in (pinned or {}).items()}
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
        if self.by_connection:
            entries = connection_ordered(entries)
        self.loads += 1
        self._held[row] = entries
        self._held_entries += len(entries.times)
        while self._held_entries > self.budget and len(self._held) > 1:
            _, dropped = self._held.popitem(last=False)
            self._held_entries -= len(dropped.times)
        return entries

    def count_before(self, t_ns: int) -> int:
        """How many messages come before time ``t_ns`` (reads the entries of the chunks that span it)."""
        import numpy as np

        before = int(self.counts[self.ends < t_ns].sum())
        for row in np.flatnonzero((self.starts < t_ns) & (self.ends >= t_ns)).tolist():
            before += int(np.searchsorted(self.entries(row).times, t_ns, side="left"))
        return before

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
        self._heap: list[tuple[int, int, int, int, int, int, int]] = []
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
            rank = int(entries.conn_ids[i]) if table.by_connection else 0
            heapq.heappush(self._heap, (int(entries.times[i]), rank, int(table.files[row]), int(table.numbers[row]),
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
            t, _rank, file, chunk, offset, row, i = self._heap[0]
            entries = self._entries(row)
            if entries is not None:
                return MessageRef(t, file, chunk, offset, int(entries.conn_ids[i]))
            heapq.heappop(self._heap)

    def advance(self) -> None:
        """Move past the next message."""
        self._fill()
        if self._heap:
            _t, _rank, _file, _chunk, _offset, row, i = heapq.heappop(self._heap)
            entries = self._entries(row)
            if entries is not None:
                self._push(row, i + 1, entries)


def connection_ordered(entries: ChunkEntries) -> ChunkEntries:
    """A chunk's entries (sorted by time, then offset) with equal times ordered by connection id, then offset."""
    import numpy as np

    times = entries.times
    if len(times) < 2 or not bool(np.any(times[1:] == times[:-1])):
        return entries
    order = np.lexsort((entries.offsets, entries.conn_ids, times))
    return ChunkEntries(times[order], entries.conn_ids[order], entries.offsets[order], entries.chunk)


class ChunkLayout(NamedTuple):
    """The chunks of several files in a table's order: their first and last times, file and number, sorted by
    (first time, file, number); ``row_of[first_row[file] + i]`` is the row of the i-th chunk of ``file``'s
    :class:`~rostui.core.bag.chunkinfo.ChunkInfos`."""

    starts: Any
    ends: Any
    files: Any
    numbers: Any
    row_of: Any
    first_row: Any


def chunk_layout(per_file: Sequence[ChunkInfos]) -> ChunkLayout:
    """Where each chunk of the files ``per_file`` describes (in the files' order, which breaks ties) sits in a
    :class:`ChunkTable`."""
    import numpy as np

    if not per_file:
        empty = np.zeros(0, dtype=np.int64)
        return ChunkLayout(empty, empty, np.zeros(0, dtype=np.uint16), np.zeros(0, dtype=np.uint32), empty,
                           np.zeros(1, dtype=np.int64))
    starts = np.concatenate([f.starts for f in per_file])
    ends = np.concatenate([f.ends for f in per_file])
    files = np.concatenate([np.full(len(f), i, dtype=np.uint16) for i, f in enumerate(per_file)])
    numbers = np.concatenate([f.numbers for f in per_file])
    order = np.lexsort((numbers, files, starts))
    row_of = np.empty(len(order), dtype=np.int64)
    row_of[order] = np.arange(len(order))
    first_row = np.cumsum([0] + [len(f) for f in per_file])
    return ChunkLayout(starts[order], ends[order], files[order], numbers[order], row_of, first_row)


def table_of(per_file: Sequence[ChunkInfos], load: Callable[[int, int], ChunkEntries], budget: int | None = None,
             by_connection: bool = False) -> ChunkTable:
    """The :class:`ChunkTable` of files whose chunks ``per_file`` describes (in the files' order, which breaks
    ties); ``load(file, chunk)`` reads a chunk's entries, ``budget`` bounds those held (None:
    :data:`ENTRY_BUDGET`). Messages outside chunks are kept whole (pinned)."""
    import numpy as np

    layout = chunk_layout(per_file)
    counts = np.zeros(len(layout.starts), dtype=np.int64)
    pinned: dict[int, ChunkEntries] = {}
    for i, infos in enumerate(per_file):
        rows = layout.row_of[layout.first_row[i] + infos.pair_rows]
        np.add.at(counts, rows, infos.pair_counts)
        if infos.loose is not None:
            pinned[loose_row(layout, i, infos)] = infos.loose
    return ChunkTable(layout.starts, layout.ends, layout.files, layout.numbers, counts, load,
                      ENTRY_BUDGET if budget is None else budget, pinned, by_connection)


def loose_row(layout: ChunkLayout, file: int, infos: ChunkInfos) -> int:
    """The row of ``file``'s messages outside chunks (its pseudo-chunk NO_CHUNK) in ``layout``."""
    import numpy as np

    return int(layout.row_of[layout.first_row[file] + int(np.flatnonzero(infos.numbers == NO_CHUNK)[0])])


class MergedBatch(NamedTuple):
    """Consecutive messages in merge order, as parallel arrays: time, file, chunk number, offset, connection id."""

    times: Any
    files: Any
    chunks: Any
    offsets: Any
    conn_ids: Any


def merged_batches(table: ChunkTable, start_ns: int | None = None, end_ns: int | None = None,
                   batch: int = BATCH) -> Iterator[MergedBatch]:
    """The messages of ``table`` with ``start_ns <= time <= end_ns`` (None: unbounded), in the order
    :class:`MergeCursor` gives them, about ``batch`` at a time.

    Only the chunks that reach ``start_ns`` are read to start with (the others are found from the table's
    first and last times); then each chunk's entries are read when the merge reaches its first time. While
    one chunk is open, a batch is a slice of its entries; chunks that overlap in time are merged a batch at a
    time, at most ``batch`` entries from them together (one a chunk when more than ``batch`` chunks are open;
    every message of one time at once). The chunks open in the merge are kept while their entries fit in the
    table's budget (besides the table's own cache, so at most twice the budget and one batch are held); past
    that (many chunks spanning the same times), their entries are read again through the cache as the merge
    needs them: slower, in the same memory. A chunk whose entries cannot be read raises its BagError.
    """
    import numpy as np

    n = len(table)
    starts, ends = table.starts, table.ends
    ties = ["times", "conn_ids", "files", "chunks", "offsets"] if table.by_connection else \
        ["times", "files", "chunks", "offsets"]
    active: dict[int, int] = {}  # row -> position of its next entry
    kept: dict[int, ChunkEntries] = {}  # the open chunks' entries, while they fit in the budget
    kept_entries = 0

    def entries(row: int) -> ChunkEntries:
        nonlocal kept_entries
        found = kept.get(row)
        if found is None:
            found = table.entries(row)
            if kept_entries + len(found.times) <= table.budget:
                kept[row] = found
                kept_entries += len(found.times)
        return found

    def close(row: int) -> None:
        nonlocal kept_entries
        del active[row]
        dropped = kept.pop(row, None)
        if dropped is not None:
            kept_entries -= len(dropped.times)

    next_row = 0
    if start_ns is not None:
        next_row = int(np.searchsorted(starts, start_ns, side="right"))
        for row in np.flatnonzero(ends[:next_row] >= start_ns).tolist():
            times = entries(row).times
            at = int(np.searchsorted(times, start_ns, side="left"))
            active[row] = at
            if at == len(times):
                close(row)
    while True:
        low = min((int(entries(row).times[at]) for row, at in active.items()), default=None)
        while next_row < n and (low is None or int(starts[next_row]) <= low):
            row = next_row
            next_row += 1
            times = entries(row).times
            active[row] = 0
            if not len(times):
                close(row)
                continue
            low = int(times[0]) if low is None else min(low, int(times[0]))
        if low is None or (end_ns is not None and low > end_ns):
            return
        cut = int(starts[next_row]) if next_row < n else None  # entries before the next chunk's first time
        if end_ns is not None:
            cut = end_ns + 1 if cut is None else min(cut, end_ns + 1)
        share = max(batch // len(active), 1)
        for row, at in active.items():
            times = entries(row).times
            if at + share < len(times):
                limit = int(times[at + share])
                cut = limit if cut is None else min(cut, limit)
        if cut is not None and cut <= low:
            cut = low + 1  # every message of the earliest time at once (ties order across chunks)
        parts: list[MergedBatch] = []
        for row in list(active):
            at = active[row]
            chunk = entries(row)
            times = chunk.times
            end = len(times) if cut is None else at + int(np.searchsorted(times[at:], cut, side="left"))
            if end == at:
                continue
            if end == len(times):
                close(row)
            else:
                active[row] = end
            k = end - at
            parts.append(MergedBatch(times[at:end], np.full(k, table.files[row], dtype=np.uint16),
                                     np.full(k, table.numbers[row], dtype=np.uint32), chunk.offsets[at:end],
                                     chunk.conn_ids[at:end]))
        if len(parts) == 1:
            yield parts[0]
        elif parts:
            joined = MergedBatch(*(np.concatenate(column) for column in zip(*parts)))
            order = np.lexsort(tuple(getattr(joined, name) for name in reversed(ties)))
            yield MergedBatch(*(column[order] for column in joined))
