"""A file's messages in time order from its chunks, not from an index of every message.

Each chunk's first and last times (:meth:`~rostui.core.bag.files.Reader.chunk_spans`)
say when its entries (:meth:`~rostui.core.bag.files.Reader.chunk_rows`) must be
read, and a heap merges the chunks open at once (several overlap only where a
file was written out of order), so memory follows the chunks in play, whatever
the number of messages.  Order is exact: time, then chunk number, then offset,
which is the file's order for equal times, as rosbag plays them.
"""

from __future__ import annotations

import heapq
from bisect import bisect_left
from collections.abc import Callable, Iterator, Sequence


Row = tuple[int, int, int]
"""``(time, offset, connection id)``: one message of a chunk, as :meth:`~rostui.core.bag.files.Reader.chunk_rows`
gives them."""


def chunk_runs(spans: Sequence[tuple[int, int, int]],
               rows: Callable[[int], list[Row]]) -> Iterator[tuple[int, list[Row], bool]]:
    """``(chunk, rows, last)``: runs of one chunk's messages, whose rows taken in turn are every message of the
    chunks ``spans`` lists (``(first time, last time, number)``) in time order, ties by chunk number, then
    offset; ``last`` is True on a chunk's last run (nothing later needs that chunk).  ``rows(number)`` reads a
    chunk's entries, sorted, when the merge reaches its first time.  A chunk alone in its time comes as one run
    (up to the next chunk's first time); chunks that overlap, a message a run."""
    pending = sorted(spans)
    heap: list[tuple[int, int, int, list[Row]]] = []  # (time, chunk, index of that row, the chunk's rows)
    next_chunk = 0
    while True:
        # a chunk joins before the merge passes its first time (at an equal time too: ties go by chunk number)
        while next_chunk < len(pending) and (not heap or pending[next_chunk][0] <= heap[0][0]):
            number = pending[next_chunk][2]
            next_chunk += 1
            entries = rows(number)
            if entries:
                heapq.heappush(heap, (entries[0][0], number, 0, entries))
        if not heap:
            return
        t, number, at, entries = heap[0]
        if len(heap) == 1 and (next_chunk == len(pending) or pending[next_chunk][0] > t):
            # one chunk open: its entries follow one another until the next chunk's first time
            end = len(entries) if next_chunk == len(pending) else bisect_left(entries, (pending[next_chunk][0],), at)
        else:
            end = at + 1
        last = end == len(entries)
        yield number, entries[at:end], last
        if last:
            heapq.heappop(heap)
        else:
            heapq.heapreplace(heap, (entries[end][0], number, end, entries))


def chunk_order(spans: Sequence[tuple[int, int, int]],
                rows: Callable[[int], list[Row]]) -> Iterator[tuple[int, int, int, int]]:
    """``(time, chunk, offset, connection id)`` of every message of the chunks ``spans`` lists, in time order,
    ties by chunk number, then offset (:func:`chunk_runs`, a message at a time)."""
    for number, run, _last in chunk_runs(spans, rows):
        for t, offset, conn_id in run:
            yield t, number, offset, conn_id
