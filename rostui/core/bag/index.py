"""A bag opened for browsing: its chunks in time order, per-topic counts, and any message found on demand.

``rostui bag view`` needs what a stream cannot give: message density per
topic, the message at any time, and seeking both ways. :func:`load_index`
reads what each file's own index says of each chunk (first and last time,
messages per connection; no payload, and no chunk's entries kept), or, for a
file that has none (not closed, or cut short), reads its chunks once to learn
the same, and says so in :attr:`BagIndex.notices`. A chunk's entries are read
when a seek, a step or a search reaches it and kept in a bounded cache
(:mod:`rostui.core.bag.chunkmerge`); payloads stay on disk and are read through
each reader's cache of decompressed chunks. Memory is bounded by the number of
chunks, not of messages, nor their size.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rostui.core.bag.chunkinfo import ChunkInfos
from rostui.core.bag.chunkmerge import ENTRY_BUDGET, ChunkTable, MergeCursor, MessageRef, chunk_layout, loose_row
from rostui.core.bag.fileindex import ChunkEntries
from rostui.core.bag.files import Reader, open_reader
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.transport import MessageItem

__all__ = ["BagIndex", "EXACT_CHUNKS", "IndexSource", "MessageRef", "TopicTrack", "VIEW_CACHE_BYTES", "load_index",
           "message_yaml"]

VIEW_CACHE_BYTES = int(os.environ.get("ROSTUI_BAG_VIEW_CACHE_BYTES", str(4 * 1024 * 1024)))
"""Bytes of decompressed chunks bag view keeps, shared by its files (at most each reader's own budget; the
chunk read last is always kept): it reads in time order, so chunks left behind are seldom read again. A bag
whose chunks overlap more than that holds (one written topic by topic, with many topics) reads a chunk again
more often: slower to play, never out of order."""

EXACT_CHUNKS = 32
"""Density over a window that at most this many of a topic's chunks reach is counted from their entries;
over a wider one, each chunk's count is spread evenly over its span."""


@dataclass
class TopicTrack:
    """One topic: its message count, the table rows of the chunks that hold it (ascending) with its count in
    each, and its connection ids per file."""

    topic: str
    type: str
    count: int = 0
    rows: Any = None
    row_counts: Any = None
    conn_ids: dict[int, Any] = field(default_factory=dict)

    def mask(self, file: int, entries: ChunkEntries) -> Any:
        """Which of a chunk's ``entries`` (of file ``file``) are this topic's."""
        import numpy as np

        ids = self.conn_ids.get(file)
        if ids is None:
            return np.zeros(len(entries.conn_ids), dtype=bool)
        return np.isin(entries.conn_ids, ids)


@dataclass
class BagIndex:
    """The chunks of the bag(s) in time order (:attr:`table`), per-topic tracks, and the connections in order of
    their first chunk. Holds its files open until :meth:`close`."""

    paths: list[str]
    readers: list[Reader] = field(default_factory=list)
    table: ChunkTable | None = None
    tracks: dict[str, TopicTrack] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    notices: list[str] = field(default_factory=list)
    count: int = 0

    def __len__(self) -> int:
        return self.count

    def close(self) -> None:
        """Close the files."""
        for reader in self.readers:
            reader.close()

    @property
    def file_size(self) -> int:
        """Bytes of the files on disk (what `rosbag info` calls size)."""
        return sum(os.path.getsize(path) for path in self.paths if os.path.exists(path))

    @property
    def start_ns(self) -> int:
        """Time of the first message (0 when empty)."""
        return int(self.table.starts.min()) if self.table is not None and len(self.table) else 0

    @property
    def end_ns(self) -> int:
        """Time of the last message (0 when empty)."""
        return int(self.table.ends.max()) if self.table is not None and len(self.table) else 0

    @property
    def topics(self) -> list[str]:
        """Topic names, sorted."""
        return sorted(self.tracks)

    def _table(self) -> ChunkTable:
        assert self.table is not None
        return self.table

    def cursor(self, t_ns: int) -> MergeCursor:
        """The messages from ``t_ns`` on, in time order."""
        return MergeCursor(self._table(), t_ns)

    def item(self, ref: MessageRef) -> MessageItem:
        """The message ``ref`` points at, its payload read from the file."""
        reader = self.readers[ref.file]
        return reader.connections[ref.conn_id], ref.time, reader.payload(ref.chunk, ref.offset)

    def connection(self, ref: MessageRef) -> Connection:
        """The connection of the message ``ref`` points at."""
        return self.readers[ref.file].connections[ref.conn_id]

    def _topic_rows(self, topic: str) -> tuple[TopicTrack | None, Any]:
        track = self.tracks.get(topic)
        return (track, track.rows) if track is not None and track.count else (None, None)

    def _best_in_rows(self, track: TopicTrack, rows: Any, bounds: Any, pick: Callable[[ChunkEntries, Any], int | None],
                      latest: bool) -> MessageRef | None:
        """The latest (or earliest) of the messages ``pick`` chooses in each row (an index into the row's
        entries, given the topic's mask), visiting rows by their ``bounds`` (the best time a row could give) and
        stopping once no row left could beat the best found."""
        import numpy as np

        table = self._table()
        order = np.argsort(-bounds if latest else bounds, kind="stable")
        best: MessageRef | None = None
        for k in order.tolist():
            bound = int(bounds[k])
            if best is not None and (bound < best.time if latest else bound > best.time):
                break
            row = int(rows[k])
            entries = table.entries(row)
            i = pick(entries, track.mask(int(table.files[row]), entries))
            if i is None:
                continue
            ref = table.ref(row, i, entries)
            if best is None or (ref[:4] > best[:4] if latest else ref[:4] < best[:4]):
                best = ref
        return best

    def message_at(self, topic: str, t_ns: int) -> MessageRef | None:
        """``topic``'s message under a cursor at ``t_ns``: the last one at or before it, else its first; None
        when the topic has no messages."""
        import numpy as np

        track, rows = self._topic_rows(topic)
        if track is None:
            return None
        table = self._table()

        def last_until(entries: ChunkEntries, mask: Any) -> int | None:
            hits = np.flatnonzero(mask[:int(np.searchsorted(entries.times, t_ns, side="right"))])
            return int(hits[-1]) if len(hits) else None

        def first(entries: ChunkEntries, mask: Any) -> int | None:
            hits = np.flatnonzero(mask)
            return int(hits[0]) if len(hits) else None

        before = rows[table.starts[rows] <= t_ns]
        found = self._best_in_rows(track, before, np.minimum(table.ends[before], t_ns), last_until, latest=True)
        return found if found is not None else self._best_in_rows(track, rows, table.starts[rows], first, latest=False)

    def neighbour_time(self, topic: str, t_ns: int, direction: int) -> int | None:
        """Time of ``topic``'s next message after ``t_ns`` (``direction`` > 0) or its last one before it
        (< 0); None when there is none."""
        import numpy as np

        track, rows = self._topic_rows(topic)
        if track is None:
            return None
        table = self._table()
        if direction > 0:
            def after(entries: ChunkEntries, mask: Any) -> int | None:
                lo = int(np.searchsorted(entries.times, t_ns, side="right"))
                hits = np.flatnonzero(mask[lo:])
                return lo + int(hits[0]) if len(hits) else None

            later = rows[table.ends[rows] > t_ns]
            found = self._best_in_rows(track, later, np.maximum(table.starts[later], t_ns + 1), after, latest=False)
        else:
            def before(entries: ChunkEntries, mask: Any) -> int | None:
                hits = np.flatnonzero(mask[:int(np.searchsorted(entries.times, t_ns, side="left"))])
                return int(hits[-1]) if len(hits) else None

            earlier = rows[table.starts[rows] < t_ns]
            found = self._best_in_rows(track, earlier, np.minimum(table.ends[earlier], t_ns - 1), before, latest=True)
        return None if found is None else found.time

    def number_in_track(self, topic: str, ref: MessageRef) -> int:
        """1-based number of the message ``ref`` points at among ``topic``'s messages."""
        import numpy as np

        track, rows = self._topic_rows(topic)
        if track is None:
            return 0
        table = self._table()
        ends, starts = table.ends[rows], table.starts[rows]
        number = int(track.row_counts[ends < ref.time].sum()) + 1
        for k in np.flatnonzero((starts <= ref.time) & (ends >= ref.time)).tolist():
            row = int(rows[k])
            entries = table.entries(row)
            mask = track.mask(int(table.files[row]), entries)
            lo = int(np.searchsorted(entries.times, ref.time, side="left"))
            hi = int(np.searchsorted(entries.times, ref.time, side="right"))
            number += int(mask[:lo].sum())
            place = (int(table.files[row]), int(table.numbers[row]))
            if place < (ref.file, ref.chunk):
                number += int(mask[lo:hi].sum())
            elif place == (ref.file, ref.chunk):
                number += int((mask[lo:hi] & (entries.offsets[lo:hi] < ref.offset)).sum())
        return number

    def density(self, topic: str, bins: int, t0: int | None = None, t1: int | None = None) -> list[int]:
        """How many messages of ``topic`` fall in each of ``bins`` equal slices of ``[t0, t1]``: counted from
        the entries when at most :data:`EXACT_CHUNKS` of its chunks reach the window, else each chunk's count
        spread evenly over its span."""
        import numpy as np

        track, rows = self._topic_rows(topic)
        if track is None or bins <= 0:
            return [0] * max(bins, 0)
        table = self._table()
        t0 = self.start_ns if t0 is None else t0
        t1 = self.end_ns if t1 is None else t1
        span = max(t1 - t0, 1)
        edges = np.array([t0 + span * i // bins for i in range(bins)] + [t1 + 1], dtype=np.int64)
        reach = (table.ends[rows] >= t0) & (table.starts[rows] <= t1)
        near = rows[reach]
        cumulative = None
        if len(near) <= EXACT_CHUNKS and int(track.row_counts[reach].sum()) <= table.budget:
            try:
                times = [entries.times[track.mask(int(table.files[row]), entries)]
                         for row in near.tolist() for entries in [table.entries(row)]]
            except BagError:  # a chunk whose entries cannot be read: its count, spread
                pass
            else:
                joined = np.sort(np.concatenate(times)) if times else np.zeros(0, dtype=np.int64)
                cumulative = np.searchsorted(joined, edges, side="left")
        if cumulative is None:
            cumulative = _spread(table.starts[rows], table.ends[rows], track.row_counts, edges, t0)
        return [max(0, int(n)) for n in np.diff(cumulative)]


def _spread(starts: Any, ends: Any, counts: Any, edges: Any, origin: int) -> Any:
    """How many messages lie before each edge when each chunk's ``counts`` are spread evenly over
    ``[start, end]`` (a chunk of one instant counts at it), rounded to whole messages."""
    import numpy as np

    s = (starts - origin).astype(np.float64)
    e = (ends - origin).astype(np.float64)
    x = (edges - origin).astype(np.float64)
    c = counts.astype(np.float64)
    point = e <= s
    total = np.zeros(len(x))
    if point.any():
        order = np.argsort(s[point])
        cum = np.concatenate(([0.0], np.cumsum(c[point][order])))
        total += cum[np.searchsorted(s[point][order], x, side="left")]
    ramp = ~point
    if ramp.any():
        slope = c[ramp] / (e[ramp] - s[ramp])
        for at, sign in ((s[ramp], 1.0), (e[ramp], -1.0)):
            order = np.argsort(at)
            slopes = np.concatenate(([0.0], np.cumsum(slope[order])))
            moments = np.concatenate(([0.0], np.cumsum(slope[order] * at[order])))
            k = np.searchsorted(at[order], x, side="left")
            total += sign * (x * slopes[k] - moments[k])
    return np.rint(total).astype(np.int64)


def _chunk_infos(reader: Reader, progress: Callable[[str], None] | None, notices: list[str]) -> ChunkInfos:
    """The reader's own index, chunk by chunk, or the same found by reading its chunks (with a notice saying
    why)."""
    infos = reader.chunk_infos()
    if infos is not None:
        return infos
    size = max(os.path.getsize(reader.path), 1)
    name = os.path.basename(reader.path)

    def report(done: int) -> None:
        if progress is not None:
            progress(f"{name} has no index: {100 * done // size}% read")

    infos = reader.scan_chunk_infos(report)
    if reader.truncated:
        notices.append(f"{reader.path} ends early ({reader.truncated}): showing what is readable")
    else:
        notices.append(f"{reader.path} was not closed (recording cut short?): showing what is readable")
    return infos


def load_index(paths: Sequence[str], progress: Callable[[str], None] | None = None,
               budget: int = ENTRY_BUDGET) -> BagIndex:
    """Open ``paths`` and gather their chunks, in time order (ties: earlier file, then file order);
    BagError when a file cannot be opened. ``progress(text)`` tells how reading goes; ``budget`` bounds the
    chunk entries held at once."""
    readers: list[Reader] = []
    try:
        for path in paths:
            readers.append(open_reader(path))
        for reader in readers:
            reader.cache.max_bytes = min(reader.cache.max_bytes, VIEW_CACHE_BYTES // len(readers))
        index = BagIndex(list(paths), readers)
        per_file = []
        for reader in readers:
            if progress is not None:
                progress(f"reading the index of {os.path.basename(reader.path)}")
            per_file.append(_chunk_infos(reader, progress, index.notices))
        _gather(index, per_file, budget)
        return index
    except BaseException:
        for reader in readers:
            reader.close()
        raise


def _gather(index: BagIndex, per_file: list[ChunkInfos], budget: int) -> None:
    """The chunk table, the per-topic tracks and the connections in order of their first chunk."""
    import numpy as np

    layout = chunk_layout(per_file)
    counts = np.zeros(len(layout.starts), dtype=np.int64)
    pinned: dict[int, ChunkEntries] = {}
    firsts: dict[tuple[int, int], int] = {}
    per_topic: dict[str, list[tuple[Any, Any, int, Any]]] = {}
    for i, infos in enumerate(per_file):
        rows = layout.row_of[layout.first_row[i] + infos.pair_rows]
        np.add.at(counts, rows, infos.pair_counts)
        if infos.loose is not None:
            pinned[loose_row(layout, i, infos)] = infos.loose
        conns = index.readers[i].connections
        for conn_id in np.unique(infos.pair_conns).tolist():
            mine = infos.pair_conns == conn_id
            firsts[(i, conn_id)] = int(layout.starts[rows[mine]].min())
            per_topic.setdefault(conns[conn_id].topic, []).append((rows[mine], infos.pair_counts[mine], i, conn_id))
    for (i, conn_id) in sorted(firsts, key=lambda key: (firsts[key], key)):
        index.connections.append(index.readers[i].connections[conn_id])
    for topic, parts in per_topic.items():
        track = index.tracks[topic] = TopicTrack(topic, next(c.type for c in index.connections if c.topic == topic))
        rows_all = np.concatenate([p[0] for p in parts])
        track.rows, inverse = np.unique(rows_all, return_inverse=True)
        track.row_counts = np.zeros(len(track.rows), dtype=np.int64)
        np.add.at(track.row_counts, inverse, np.concatenate([p[1] for p in parts]))
        track.count = int(track.row_counts.sum())
        for _rows, _counts, i, conn_id in parts:
            track.conn_ids[i] = np.append(track.conn_ids.get(i, np.zeros(0, dtype=np.uint32)), np.uint32(conn_id))
    index.count = int(counts.sum())
    readers = index.readers

    def load(file: int, chunk: int) -> ChunkEntries:
        return readers[file].chunk_entries(chunk)

    index.table = ChunkTable(layout.starts, layout.ends, layout.files, layout.numbers, counts, load, budget, pinned)


class IndexSource:
    """A :class:`~rostui.core.bag.transport.MessageSource` over a :class:`BagIndex`: seeks both ways at once.

    A message that cannot be read (a damaged chunk, a record the index misplaces) is passed over, and
    :attr:`problem` keeps the error line of the last one, for the screen to show.
    """

    def __init__(self, index: BagIndex) -> None:
        self.index = index
        self.problem = ""
        """The one-line error of the last message that could not be read ('' while none)."""
        self._cursor = index.cursor(index.start_ns)
        self._read: tuple[MessageRef, MessageItem] | None = None

    def peek(self) -> MessageItem | None:
        """The message at the read position (past any that cannot be read), or None at the end."""
        while (ref := self._cursor.peek()) is not None:
            if self._read is not None and self._read[0] == ref:
                return self._read[1]
            try:
                self._read = (ref, self.index.item(ref))
                return self._read[1]
            except BagError as exc:
                self.problem = str(exc)
                self._cursor.advance()
        if self._cursor.problem:  # a chunk whose entries could not be read
            self.problem = self._cursor.problem
        return None

    def advance(self) -> None:
        """Move past the message at the read position."""
        self._cursor.advance()

    def seek(self, t_ns: int) -> None:
        """Move to the first message at ``t_ns`` or later."""
        self._cursor = self.index.cursor(t_ns)


def message_yaml(conn: Connection, data: bytes, *, noarr: bool = False) -> str:
    """The message as ``rostopic echo`` prints it (``--noarr`` with ``noarr``), decoded with the type
    recorded in the bag (checked: :func:`rostui.core.bag.decode.decode_message`)."""
    from rostui.core.bag.decode import decode_message
    from rostui.core.msg.convert import message_to_yaml

    return message_to_yaml(decode_message(conn, data), noarr=noarr)
