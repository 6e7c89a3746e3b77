"""What a bag file's index says of each chunk: its first and last message time and its messages per connection.

This is what rqt_bag reads of a bag (rosbag's chunk info records; MCAP's chunk
indexes and message indexes give the same): enough for the timeline and the
counts, with memory bounded by the number of chunks, not of messages.  The
times and counts are gathered from the entries themselves as the index is read
(each chunk's entries are dropped once counted), so they agree exactly with
the entries :meth:`~rostui.core.bag.fileindex.ChunkedFile.chunk_entries` reads
later.  Messages outside any chunk (an MCAP file may hold some) have no chunk
to re-read them from: they are kept whole, as one pseudo-chunk numbered
:data:`~rostui.core.bag.fileindex.NO_CHUNK`.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from rostui.core.bag.fileindex import NO_CHUNK, ChunkEntries
from rostui.core.records import Record


class ChunkInfos(Record):
    """Per chunk of one file with messages (in order of chunk number): number, first and last message time, and
    ``(row, connection id, count)`` triples, one per connection the chunk holds; ``loose``: the messages outside
    any chunk, sorted (their row's number is NO_CHUNK). A record: see :mod:`rostui.core.records`."""

    _fields = ("numbers", "starts", "ends", "pair_rows", "pair_conns", "pair_counts", "loose", "from_file_index")

    def __init__(self, numbers: Any, starts: Any, ends: Any, pair_rows: Any, pair_conns: Any, pair_counts: Any,
                 loose: ChunkEntries | None = None, from_file_index: bool = True) -> None:
        self.numbers = numbers
        self.starts = starts
        self.ends = ends
        self.pair_rows = pair_rows
        self.pair_conns = pair_conns
        self.pair_counts = pair_counts
        self.loose = loose
        self.from_file_index = from_file_index

    def __len__(self) -> int:
        return int(self.numbers.shape[0])

    @property
    def message_count(self) -> int:
        """Messages in the file."""
        return int(self.pair_counts.sum())

    @classmethod
    def gather(cls, parts: Iterable[ChunkEntries], *, from_file_index: bool = True) -> ChunkInfos:
        """Count ``parts`` (several may share a chunk) without keeping their entries, except those of messages
        outside chunks."""
        import numpy as np

        spans: dict[int, list[int]] = {}
        counts: dict[int, dict[int, int]] = {}
        loose: list[ChunkEntries] = []
        for part in parts:
            times = np.asarray(part.times, dtype=np.int64)
            if not times.shape[0]:
                continue
            if part.chunk == NO_CHUNK:
                loose.append(part)
            lo, hi = int(times.min()), int(times.max())
            span = spans.get(part.chunk)
            if span is None:
                spans[part.chunk] = [lo, hi]
            else:
                span[0], span[1] = min(span[0], lo), max(span[1], hi)
            held = counts.setdefault(part.chunk, {})
            conn_ids = np.asarray(part.conn_ids, dtype=np.uint32)
            first = int(conn_ids[0])
            if bool((conn_ids == first).all()):  # a rosbag index data record: one connection
                held[first] = held.get(first, 0) + int(conn_ids.shape[0])
                continue
            ids, per_id = np.unique(conn_ids, return_counts=True)
            for conn_id, n in zip(ids.tolist(), per_id.tolist()):
                held[conn_id] = held.get(conn_id, 0) + n
        numbers = sorted(spans)
        pairs = [(row, conn_id, n) for row, number in enumerate(numbers) for conn_id, n in counts[number].items()]
        return cls(np.array(numbers, dtype=np.uint32),
                   np.array([spans[n][0] for n in numbers], dtype=np.int64),
                   np.array([spans[n][1] for n in numbers], dtype=np.int64),
                   np.array([p[0] for p in pairs], dtype=np.int32),
                   np.array([p[1] for p in pairs], dtype=np.uint32),
                   np.array([p[2] for p in pairs], dtype=np.int64),
                   sorted_entries(loose, NO_CHUNK) if loose else None, from_file_index)


def sorted_entries(parts: Sequence[ChunkEntries], chunk: int) -> ChunkEntries:
    """One chunk's entries joined from ``parts`` and sorted by time, then by offset (the file's order)."""
    import numpy as np

    if not parts:
        return ChunkEntries(np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.uint32), np.zeros(0, dtype=np.uint64),
                            chunk)
    times = np.concatenate([np.asarray(p.times, dtype=np.int64) for p in parts])
    conn_ids = np.concatenate([np.asarray(p.conn_ids, dtype=np.uint32) for p in parts])
    offsets = np.concatenate([np.asarray(p.offsets, dtype=np.uint64) for p in parts])
    order = np.lexsort((offsets, times))
    return ChunkEntries(times[order], conn_ids[order], offsets[order], chunk)
