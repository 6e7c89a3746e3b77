"""A bag's messages in time order as TCPROS frames, ready for a socket: what a player publishes.

A ``.bag`` chunk stores each message's data right after its 4-byte length, which
is exactly how TCPROS frames a message, so a frame is a view of the chunk the
reader holds (:meth:`~rostui.core.bag.files.Reader.framer`): nothing is copied
between the file and the socket.  An uncompressed chunk without a CRC is not
even read: its frames are regions of the file
(:class:`~rostui.core.file_region.FileRegion`) the kernel sends itself.  Other
formats add the prefix.

Time order comes from the chunks (:func:`~rostui.core.bag.chunkorder.chunk_runs`):
memory follows the chunks in play, whatever the number of messages, and a
``.bag`` is read without numpy.
"""

from __future__ import annotations

import heapq
from collections.abc import Iterator, Sequence
from typing import Any

from rostui.core.bag.chunkorder import chunk_runs
from rostui.core.bag.files import Reader
from rostui.core.bag.model import Connection, Frame, frame_of

#: ``(connection, time_ns, frame)``: one message, its bytes framed as TCPROS sends them.
FramedMessage = tuple[Connection, int, Frame]


def framed_messages(reader: Reader) -> Iterator[FramedMessage]:
    """One file's messages in time order (ties in file order, as rosbag plays them), framed; in file order when
    the file has no index (:func:`~rostui.core.bag.files.unordered_notice` says so).  A chunk is released from
    the reader's cache once its last frame is out (a frame still held keeps its bytes)."""
    spans = reader.chunk_spans()
    if spans is None:
        for conn, t, data in reader.messages():
            yield conn, t, frame_of(data)
        return
    conns = reader.connections
    for chunk, run, last in chunk_runs(spans, reader.chunk_rows):
        frame_at = reader.framer(chunk)  # what every frame needs of its chunk, looked up once a run
        for t, offset, conn_id in run:
            yield conns[conn_id], t, frame_at(offset)
        if last:
            reader.release(chunk)  # played: the next chunk takes its place in memory and in the CPU's caches


def merged_framed_messages(readers: Sequence[Reader]) -> Iterator[FramedMessage]:
    """Several files' messages in time order, framed; equal times in the order the files are given."""
    if len(readers) == 1:
        return framed_messages(readers[0])  # itself: a generator around it would add a resumption a message
    return _merged(readers)


def _merged(readers: Sequence[Reader]) -> Iterator[FramedMessage]:
    streams: list[Iterator[Any]] = [_tagged(framed_messages(r), i) for i, r in enumerate(readers)]
    for t, _i, conn, data in heapq.merge(*streams, key=lambda item: (item[0], item[1])):
        yield conn, t, data


def _tagged(messages: Iterator[FramedMessage], i: int) -> Iterator[tuple[int, int, Connection, Any]]:
    for conn, t, data in messages:
        yield t, i, conn, data
