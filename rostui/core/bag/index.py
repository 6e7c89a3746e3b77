"""A bag opened for browsing: where every message lies, in time order, with per-topic times and random access.

``rostui bag view`` needs what a stream cannot give: message density per
topic, the message at any time, and seeking both ways. :func:`load_index`
reads each file's own index (no payload is read), or, for a file that has none
(not closed, or cut short), reads its chunks once to find its messages, and
says so in :attr:`BagIndex.notices`. Payloads stay on disk and are read
through each reader's cache of decompressed chunks when a message is shown or
published, so memory is bounded by the number of messages, not their size.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rostui.core.bag.files import Reader, open_reader
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.transport import MessageItem


@dataclass
class TopicTrack:
    """One topic's messages: their times and their positions in the whole bag (both sorted)."""

    topic: str
    type: str
    times: Any = None
    positions: Any = None

    @property
    def count(self) -> int:
        """Messages on this topic."""
        return 0 if self.times is None else int(self.times.shape[0])


@dataclass
class BagIndex:
    """Every message of the bag(s) in time order (columns: time, file, connection id, chunk, offset), with
    per-topic tracks and the connections in order of their first message. Holds its files open until
    :meth:`close`."""

    paths: list[str]
    readers: list[Reader] = field(default_factory=list)
    times: Any = None
    files: Any = None
    conn_ids: Any = None
    chunks: Any = None
    offsets: Any = None
    tracks: dict[str, TopicTrack] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    notices: list[str] = field(default_factory=list)

    def __len__(self) -> int:
        return 0 if self.times is None else int(self.times.shape[0])

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
        return int(self.times[0]) if len(self) else 0

    @property
    def end_ns(self) -> int:
        """Time of the last message (0 when empty)."""
        return int(self.times[-1]) if len(self) else 0

    @property
    def topics(self) -> list[str]:
        """Topic names, sorted."""
        return sorted(self.tracks)

    def connection(self, position: int) -> Connection:
        """The connection of the message at ``position``."""
        return self.readers[int(self.files[position])].connections[int(self.conn_ids[position])]

    def item(self, position: int) -> MessageItem:
        """The message at ``position`` (0-based, time order), its payload read from the file."""
        reader = self.readers[int(self.files[position])]
        data = reader.payload(int(self.chunks[position]), int(self.offsets[position]))
        return reader.connections[int(self.conn_ids[position])], int(self.times[position]), data

    def position_at(self, t_ns: int) -> int:
        """Position of the first message at ``t_ns`` or later (``len`` when none)."""
        return int(self.times.searchsorted(t_ns, side="left")) if len(self) else 0

    def number_in_track(self, topic: str, position: int) -> int:
        """1-based number of the message at ``position`` among ``topic``'s messages."""
        return int(self.tracks[topic].positions.searchsorted(position, side="left")) + 1

    def density(self, topic: str, bins: int, t0: int | None = None, t1: int | None = None) -> list[int]:
        """How many messages of ``topic`` fall in each of ``bins`` equal slices of ``[t0, t1]``."""
        track = self.tracks.get(topic)
        if track is None or bins <= 0:
            return [0] * max(bins, 0)
        import numpy as np

        t0 = self.start_ns if t0 is None else t0
        t1 = self.end_ns if t1 is None else t1
        span = max(t1 - t0, 1)
        bounds = [t0 + span * i // bins for i in range(bins)]
        edges = np.append(track.times.searchsorted(bounds, side="left"), track.times.searchsorted(t1, side="right"))
        return [max(0, int(n)) for n in np.diff(edges)]

    def neighbour_time(self, topic: str, t_ns: int, direction: int) -> int | None:
        """Time of ``topic``'s next message after ``t_ns`` (``direction`` > 0) or its last one before it
        (< 0); None when there is none."""
        track = self.tracks.get(topic)
        if track is None or not track.count:
            return None
        if direction > 0:
            i = int(track.times.searchsorted(t_ns, side="right"))
            return int(track.times[i]) if i < track.count else None
        i = int(track.times.searchsorted(t_ns, side="left")) - 1
        return int(track.times[i]) if i >= 0 else None

    def message_at(self, topic: str, t_ns: int) -> int | None:
        """Position of ``topic``'s message under a cursor at ``t_ns``: the last one at or before it,
        else its first; None when the topic has no messages."""
        track = self.tracks.get(topic)
        if track is None or not track.count:
            return None
        i = int(track.times.searchsorted(t_ns, side="right")) - 1
        return int(track.positions[max(i, 0)])


def _file_index(reader: Reader, progress: Callable[[str], None] | None, notices: list[str]) -> Any:
    """The reader's own index, or one found by reading its chunks (with a notice saying why)."""
    index = reader.file_index()
    if index is not None:
        return index
    size = max(os.path.getsize(reader.path), 1)
    name = os.path.basename(reader.path)

    def report(done: int) -> None:
        if progress is not None:
            progress(f"{name} has no index: {100 * done // size}% read")

    index = reader.scan_index(report)
    if reader.truncated:
        notices.append(f"{reader.path} ends early ({reader.truncated}): showing what is readable")
    else:
        notices.append(f"{reader.path} was not closed (recording cut short?): showing what is readable")
    return index


def load_index(paths: Sequence[str], progress: Callable[[str], None] | None = None) -> BagIndex:
    """Open ``paths`` and gather where each message lies, merged in time order (ties: earlier file, then
    file order); BagError when a file cannot be opened. ``progress(text)`` tells how reading goes."""
    import numpy as np

    readers: list[Reader] = []
    try:
        for path in paths:
            readers.append(open_reader(path))
        index = BagIndex(list(paths), readers)
        per_file = []
        for reader in readers:
            if progress is not None:
                progress(f"reading the index of {os.path.basename(reader.path)}")
            per_file.append(_file_index(reader, progress, index.notices))
        if len(per_file) == 1:  # already in time order: share the reader's columns instead of copying them
            only = per_file[0]
            index.times, index.conn_ids, index.chunks, index.offsets = (only.times, only.conn_ids, only.chunks,
                                                                        only.offsets)
            index.files = np.zeros(len(only), dtype=np.uint16)
        else:
            times = np.concatenate([f.times for f in per_file])
            order = np.argsort(times, kind="stable")
            index.times = times[order]
            del times
            index.files = np.concatenate([np.full(len(f), i, dtype=np.uint16) for i, f in enumerate(per_file)])[order]
            index.conn_ids = np.concatenate([f.conn_ids for f in per_file])[order]
            index.chunks = np.concatenate([f.chunks for f in per_file])[order]
            index.offsets = np.concatenate([f.offsets for f in per_file])[order]
        _gather_tracks(index)
        return index
    except BaseException:
        for reader in readers:
            reader.close()
        raise


def _gather_tracks(index: BagIndex) -> None:
    """Per-topic tracks and the connections in order of their first message."""
    import numpy as np

    # one key per (file, connection): where its first message is, and which topic it belongs to (one file:
    # the connection ids themselves, with no 8-byte copy of them)
    if len(index.readers) == 1:
        keys = index.conn_ids
    else:
        keys = index.files.astype(np.uint64) << np.uint64(32) | index.conn_ids.astype(np.uint64)
    unique, first = np.unique(keys, return_index=True)
    topic_of_key: dict[int, str] = {}
    for key, at in sorted(zip(unique.tolist(), first.tolist()), key=lambda pair: pair[1]):
        conn = index.readers[key >> 32].connections[key & 0xFFFFFFFF]
        index.connections.append(conn)
        topic_of_key[key] = conn.topic
        if conn.topic not in index.tracks:
            index.tracks[conn.topic] = TopicTrack(conn.topic, conn.type)
    small = np.uint32 if len(index) < 1 << 32 else np.int64
    for topic, track in index.tracks.items():
        wanted = [k for k, t in topic_of_key.items() if t == topic]
        found = keys == keys.dtype.type(wanted[0]) if len(wanted) == 1 else np.isin(keys, np.array(wanted, keys.dtype))
        track.positions = np.flatnonzero(found).astype(small)
        del found
        track.times = index.times[track.positions]


class IndexSource:
    """A :class:`~rostui.core.bag.transport.MessageSource` over a :class:`BagIndex`: seeks both ways at once.

    A message that cannot be read (a damaged chunk, a record the index misplaces) is passed over, and
    :attr:`problem` keeps the error line of the last one, for the screen to show.
    """

    def __init__(self, index: BagIndex) -> None:
        self.index = index
        self.position = 0
        self.problem = ""
        """The one-line error of the last message that could not be read ('' while none)."""
        self._read: tuple[int, MessageItem] | None = None

    def peek(self) -> MessageItem | None:
        """The message at the read position (past any that cannot be read), or None at the end."""
        while self.position < len(self.index):
            if self._read is not None and self._read[0] == self.position:
                return self._read[1]
            try:
                self._read = (self.position, self.index.item(self.position))
            except BagError as exc:
                self.problem = str(exc)
                self.position += 1
        return None

    def advance(self) -> None:
        """Move past the message at the read position."""
        if self.position < len(self.index):
            self.position += 1

    def seek(self, t_ns: int) -> None:
        """Move to the first message at ``t_ns`` or later."""
        self.position = self.index.position_at(t_ns)


def message_yaml(conn: Connection, data: bytes, *, noarr: bool = False) -> str:
    """The message as ``rostopic echo`` prints it (``--noarr`` with ``noarr``), decoded with the type
    recorded in the bag (checked: :func:`rostui.core.bag.decode.decode_message`)."""
    from rostui.core.bag.decode import decode_message
    from rostui.core.msg.convert import message_to_yaml

    return message_to_yaml(decode_message(conn, data), noarr=noarr)
