"""A bag read into memory for browsing: every message in time order, per-topic times, random access.

``rostui bag view`` needs what a stream cannot give: message density per
topic, the message at any time, and seeking both ways. :func:`load_index`
reads every readable message of one or more files once (a file cut short is
read up to its last complete record, and says so in :attr:`BagIndex.notices`).
"""

from __future__ import annotations

import os
from bisect import bisect_left, bisect_right
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from rostui.core.bag.files import merged_messages, open_reader
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.transport import MessageItem


@dataclass
class TopicTrack:
    """One topic's messages: their times and their positions in the whole bag."""

    topic: str
    type: str
    times: list[int] = field(default_factory=list)
    positions: list[int] = field(default_factory=list)
    size: int = 0

    @property
    def count(self) -> int:
        """Messages on this topic."""
        return len(self.times)


@dataclass
class BagIndex:
    """Every message of the bag(s) in time order, with per-topic tracks and the connections in order of
    their first message."""

    paths: list[str]
    times: list[int] = field(default_factory=list)
    conns: list[Connection] = field(default_factory=list)
    datas: list[bytes] = field(default_factory=list)
    tracks: dict[str, TopicTrack] = field(default_factory=dict)
    connections: list[Connection] = field(default_factory=list)
    notices: list[str] = field(default_factory=list)
    size: int = 0

    def __len__(self) -> int:
        return len(self.times)

    @property
    def file_size(self) -> int:
        """Bytes of the files on disk (what `rosbag info` calls size); ``size`` counts message bytes only."""
        return sum(os.path.getsize(path) for path in self.paths if os.path.exists(path))

    @property
    def start_ns(self) -> int:
        """Time of the first message (0 when empty)."""
        return self.times[0] if self.times else 0

    @property
    def end_ns(self) -> int:
        """Time of the last message (0 when empty)."""
        return self.times[-1] if self.times else 0

    @property
    def topics(self) -> list[str]:
        """Topic names, sorted."""
        return sorted(self.tracks)

    def item(self, position: int) -> MessageItem:
        """The message at ``position`` (0-based, time order)."""
        return self.conns[position], self.times[position], self.datas[position]

    def position_at(self, t_ns: int) -> int:
        """Position of the first message at ``t_ns`` or later (``len`` when none)."""
        return bisect_left(self.times, t_ns)

    def density(self, topic: str, bins: int, t0: int | None = None, t1: int | None = None) -> list[int]:
        """How many messages of ``topic`` fall in each of ``bins`` equal slices of ``[t0, t1]``."""
        track = self.tracks.get(topic)
        if track is None or bins <= 0:
            return [0] * max(bins, 0)
        t0 = self.start_ns if t0 is None else t0
        t1 = self.end_ns if t1 is None else t1
        span = max(t1 - t0, 1)
        edges = [bisect_left(track.times, t0 + span * i // bins) for i in range(bins)]
        edges.append(bisect_right(track.times, t1))
        return [max(0, edges[i + 1] - edges[i]) for i in range(bins)]

    def neighbour_time(self, topic: str, t_ns: int, direction: int) -> int | None:
        """Time of ``topic``'s next message after ``t_ns`` (``direction`` > 0) or its last one before it
        (< 0); None when there is none."""
        track = self.tracks.get(topic)
        if track is None:
            return None
        if direction > 0:
            i = bisect_right(track.times, t_ns)
            return track.times[i] if i < len(track.times) else None
        i = bisect_left(track.times, t_ns) - 1
        return track.times[i] if i >= 0 else None

    def message_at(self, topic: str, t_ns: int) -> int | None:
        """Position of ``topic``'s message under a cursor at ``t_ns``: the last one at or before it,
        else its first; None when the topic has no messages."""
        track = self.tracks.get(topic)
        if track is None or not track.times:
            return None
        i = bisect_right(track.times, t_ns) - 1
        return track.positions[max(i, 0)]


def load_index(paths: Sequence[str], progress: Callable[[int], None] | None = None) -> BagIndex:
    """Read every readable message of ``paths`` (merged in time order); BagError when a file cannot be opened.

    ``progress(count)`` is called every few thousand messages.
    """
    readers = []
    try:
        for path in paths:
            readers.append(open_reader(path))
        index = BagIndex(list(paths))
        seen: set[Connection] = set()
        for conn, t, data, _i in merged_messages(readers):
            position = len(index.times)
            index.times.append(t)
            index.conns.append(conn)
            index.datas.append(data)
            if conn not in seen:
                seen.add(conn)
                index.connections.append(conn)
            track = index.tracks.get(conn.topic)
            if track is None:
                track = index.tracks[conn.topic] = TopicTrack(conn.topic, conn.type)
            track.times.append(t)
            track.positions.append(position)
            track.size += len(data)
            index.size += len(data)
            if progress is not None and position % 5000 == 4999:
                progress(position + 1)
        for reader in readers:
            if reader.truncated:
                index.notices.append(f"{reader.path} ends early ({reader.truncated}): showing what is readable")
            elif not reader.closed_properly:
                index.notices.append(f"{reader.path} was not closed (recording cut short?): showing what is readable")
        return index
    finally:
        for reader in readers:
            reader.close()


class IndexSource:
    """A :class:`~rostui.core.bag.transport.MessageSource` over a :class:`BagIndex`: seeks both ways at once."""

    def __init__(self, index: BagIndex) -> None:
        self.index = index
        self.position = 0

    def peek(self) -> MessageItem | None:
        """The message at the read position, or None at the end."""
        return self.index.item(self.position) if self.position < len(self.index) else None

    def advance(self) -> None:
        """Move past the message at the read position."""
        if self.position < len(self.index):
            self.position += 1

    def seek(self, t_ns: int) -> None:
        """Move to the first message at ``t_ns`` or later."""
        self.position = self.index.position_at(t_ns)


def message_yaml(conn: Connection, data: bytes, *, noarr: bool = False) -> str:
    """The message as ``rostopic echo`` prints it (``--noarr`` with ``noarr``), decoded with the type
    recorded in the bag."""
    from rostui.core.msg import register_types_from_definition
    from rostui.core.msg.convert import message_to_yaml

    try:
        cls = register_types_from_definition(conn.type, conn.definition)
        msg = cls().deserialize(data)
    except Exception as exc:  # a bad definition, or the generated deserializer's errors on damaged data
        raise BagError(f"cannot decode this {conn.type or 'message'}: {exc}") from None
    return message_to_yaml(msg, noarr=noarr)
