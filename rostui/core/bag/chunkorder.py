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
from collections.abc import Callable, Iterator, Sequence


def chunk_order(spans: Sequence[tuple[int, int, int]],
                rows: Callable[[int], list[tuple[int, int, int]]]) -> Iterator[tuple[int, int, int, int]]:
    """``(time, chunk, offset, connection id)`` of every message of the chunks ``spans`` lists (``(first time,
    last time, number)``), in time order, ties by chunk number, then offset; ``rows(number)`` reads a chunk's
    entries, sorted, when the merge reaches its first time."""
    pending = sorted(spans)
    heap: list[tuple[int, int, int, int, Iterator[tuple[int, int, int]]]] = []
    next_chunk = 0
    while True:
        # a chunk joins before the merge passes its first time (at an equal time too: ties go by chunk number)
        while next_chunk < len(pending) and (not heap or pending[next_chunk][0] <= heap[0][0]):
            number = pending[next_chunk][2]
            next_chunk += 1
            entries = iter(rows(number))
            first = next(entries, None)
            if first is not None:
                heapq.heappush(heap, (first[0], number, first[1], first[2], entries))
        if not heap:
            return
        t, number, offset, conn_id, entries = heap[0]
        if len(heap) == 1 and (next_chunk == len(pending) or pending[next_chunk][0] > t):
            # one chunk open: its entries follow one another until the next chunk's first time
            limit = pending[next_chunk][0] if next_chunk < len(pending) else None
            yield t, number, offset, conn_id
            for t, offset, conn_id in entries:
                if limit is not None and t >= limit:
                    heap[0] = (t, number, offset, conn_id, entries)
                    break
                yield t, number, offset, conn_id
            else:
                heap.pop()
            continue
        yield t, number, offset, conn_id
        following = next(entries, None)
        if following is None:
            heapq.heappop(heap)
        else:
            heapq.heapreplace(heap, (following[0], number, following[1], following[2], entries))
