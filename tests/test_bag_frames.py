"""A player's frames: each message of a bag as TCPROS sends it, a view of the chunk in a compressed ``.bag``, the
region of the file in an uncompressed one.

Every frame must be the message's 4-byte little-endian length and then exactly the bytes :meth:`payload` reads,
in the order the player plays (time order, ties in file order; file order without an index), for both formats;
a view queued for a slow subscriber must not keep its chunk alive; a region reaches a real socket whole, however
little the socket takes at once, and a file cut short under it is the chunk's one-line error.
"""

from __future__ import annotations

import os
import socket
import struct
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag.files import merged_messages, open_reader, open_writer
from rostui.core.bag.frames import framed_messages, merged_framed_messages
from rostui.core.bag.model import Connection, Frame, MalformedRecord, frame_of
from rostui.core.file_region import FileRegion

from bag_view_helpers import STEP_NS, T0, Int32, write_counts


def _plain(frame: Frame) -> bytes:
    whole = bytes(frame)
    (length,) = struct.unpack_from("<I", whole)
    assert length == len(whole) - 4 == len(frame) - 4
    return whole[4:]


@pytest.mark.parametrize("name,compression,kind", [("c.bag", "none", FileRegion), ("c.bag", "lz4", memoryview),
                                                   ("c.bag", "bz2", memoryview), ("c.mcap", "lz4", bytes)])
def test_frames_are_the_payloads_with_their_length_in_play_order(tmp_path: Path, name: str, compression: str,
                                                                  kind: type) -> None:
    """A ``.bag`` frame is the record's own length field and data: in the file when the chunk is plain, in the
    decompressed chunk otherwise; MCAP's are copies with a length added."""
    path = str(write_counts(tmp_path / name, count=120, flush_every=25, compression=compression))
    reader = open_reader(path)
    expected = [(c.topic, t, d) for c, t, d, _i in merged_messages([reader])]
    frames = list(framed_messages(reader))
    assert [(c.topic, t, _plain(f)) for c, t, f in frames] == expected
    assert {type(f) for _c, _t, f in frames} <= {kind, *kind.__subclasses__()}
    reader.close()


@pytest.mark.parametrize("name", ["c.bag", "c.mcap"])
def test_a_chunk_leaves_the_cache_once_its_frames_are_out(tmp_path: Path, name: str) -> None:
    """A player reads in time order and never goes back: each chunk's decompressed bytes leave the reader's
    cache after its last frame, so it holds the chunk in play and no more, however large its bound."""
    path = str(write_counts(tmp_path / name, count=120, flush_every=25, compression="lz4"))
    reader = open_reader(path)
    chunks = reader.chunk_spans()
    assert chunks is not None and len(chunks) == 5
    held = []
    for _c, _t, frame in framed_messages(reader):
        held.append(reader.cache.held_bytes)
        _plain(frame)  # still whole after its chunk left the cache
    assert 0 < max(held) <= max(place.plain_size for place in reader.chunk_table)
    assert reader.cache.held_bytes == 0
    reader.close()


def test_two_files_merge_in_time_order_ties_by_file(tmp_path: Path) -> None:
    a = str(write_counts(tmp_path / "a.bag", count=40, flush_every=7))
    b = str(write_counts(tmp_path / "b.mcap", count=30, flush_every=11))
    readers = [open_reader(a), open_reader(b)]
    expected = [(c.topic, t, d, i) for c, t, d, i in merged_messages(readers)]
    got = [(c.topic, t, _plain(f)) for c, t, f in merged_framed_messages(readers)]
    assert got == [(topic, t, d) for topic, t, d, _i in expected]
    # equal times: the first file's message first
    assert [i for *_x, i in expected][:4] == [0, 1, 0, 0]
    for reader in readers:
        reader.close()


def test_a_bag_never_closed_plays_its_complete_chunks_in_file_order(tmp_path: Path) -> None:
    path = tmp_path / "open.bag"
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/c"))
    for i in range(60):
        writer.write(0, T0 + (59 - i) * STEP_NS, Int32(data=i).serialize())  # written backwards in time
        if i % 20 == 19:
            writer.flush()
    os.close(writer.fd) if hasattr(writer, "fd") else writer.out.close()  # killed: no index written
    reader = open_reader(str(path))
    assert reader.chunk_spans() is None
    values = [Int32().deserialize(_plain(f)).data for _c, _t, f in framed_messages(reader)]
    assert values == list(range(60))
    reader.close()


def test_a_view_queued_for_a_slow_subscriber_is_copied(tmp_path: Path) -> None:
    """While a subscriber does not keep up, its queue keeps bytes of its own, not views pinning whole chunks."""
    from rostui.core.node.topics import OutgoingLink

    class Pub:
        queue_limit = 2

    link = OutgoingLink.__new__(OutgoingLink)
    link.pub = Pub()  # type: ignore[assignment]
    link.gone = False
    link.backlog = __import__("collections").deque()
    link.backlog_bytes = 0
    link.dropped = 0
    chunk = bytes(range(256)) * 4
    for start in (0, 100, 200):
        link._queue(memoryview(chunk)[start:start + 50])
    assert [type(b) for b in link.backlog] == [bytes, bytes]
    assert list(link.backlog) == [chunk[100:150], chunk[200:250]]
    assert link.backlog_bytes == 100 and link.dropped == 1


def _frames_of_a_plain_bag(tmp_path: Path) -> tuple[Path, list[FileRegion], list[bytes]]:
    """An uncompressed bag of 300 std_msgs/String of 0 to 6 KB in 3 chunks: its frames (regions) and the frames'
    bytes as its payloads give them."""
    from rostui.core.msg import get_message_class

    text = get_message_class("std_msgs/String")
    path = tmp_path / "plain.bag"
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/text", "std_msgs/String", text._md5sum, text._full_text, "/t"))
    for i in range(300):
        writer.write(0, T0 + i * STEP_NS, text(data=chr(65 + i % 26) * (i * 20)).serialize())
        if i % 100 == 99:
            writer.flush()
    writer.close()
    reader = open_reader(str(path))
    frames = [f for _c, _t, f in framed_messages(reader)]
    assert all(isinstance(f, FileRegion) for f in frames)
    return path, frames, [frame_of(d) for _c, _t, d, _i in merged_messages([reader])]


@pytest.mark.parametrize("kind", ["region of the file", "view of a chunk"])
def test_frames_reach_a_socket_whole_however_little_it_takes_at_once(tmp_path: Path, kind: str) -> None:
    """A subscriber's link sends a frame itself while nothing waits before it (a region by sendfile, a view by
    send); what a full socket does not take is queued in the transport (a region's bytes read first), and what
    follows waits behind it: the bytes arrive in order."""
    from rostui.core.node.topics import OutgoingLink

    _path, regions, expected = _frames_of_a_plain_bag(tmp_path)
    frames: list[Any] = regions if kind == "region of the file" else [memoryview(bytes(e)) for e in expected]
    transport, theirs = _SocketTransport.pair()
    link = _link_over(transport)
    got = bytearray()
    for number, frame in enumerate(frames):
        link.send(frame)
        if number % 10 == 9:  # a subscriber that reads now and then, a little at a time
            got += theirs.recv(8192)
            transport.flush()
    want = sum(len(f) for f in expected)
    _read_all(transport, theirs, got, want)
    assert bytes(got) == b"".join(expected)
    assert 0 < transport.queued_writes < len(frames), "the direct send or the queue went untried"
    assert link.messages_sent == len(frames) and link.bytes_sent == want


class _SocketTransport:
    """What an asyncio transport does with a write: send what the socket takes, queue the rest (a link's
    connection, and its transport)."""

    def __init__(self, sock: socket.socket) -> None:
        self.sock = sock
        self.queue = bytearray()
        self.queued_writes = 0
        self.transport = self

    @classmethod
    def pair(cls) -> tuple[_SocketTransport, socket.socket]:
        """A transport over one end of a socket pair whose other end (returned) takes 4 KB at a time."""
        ours, theirs = socket.socketpair()
        ours.setblocking(False)
        theirs.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        return cls(ours), theirs

    def is_closing(self) -> bool:
        return False

    def get_write_buffer_size(self) -> int:
        return len(self.queue)

    def write(self, data: bytes) -> None:
        self.queue += data
        self.queued_writes += 1
        self.flush()

    def flush(self) -> None:
        while self.queue:
            try:
                sent = self.sock.send(self.queue)
            except BlockingIOError:
                return
            del self.queue[:sent]


def _link_over(transport: _SocketTransport, pub: Any = None) -> Any:
    """An outgoing link of ``pub`` whose connection is ``transport``."""
    from rostui.core.node.topics import OutgoingLink

    link = OutgoingLink.__new__(OutgoingLink)
    link.pub = pub
    link.paused = False
    link.conn = transport  # type: ignore[assignment]
    link._sock = transport.sock
    link.remainder_pending = False
    link.messages_sent = link.bytes_sent = 0
    return link


def _read_all(transport: _SocketTransport, theirs: socket.socket, got: bytearray, want: int) -> None:
    while len(got) < want:
        transport.flush()
        got += theirs.recv(1 << 16)


def test_a_players_frame_sender_goes_straight_to_one_subscriber_and_the_general_way_otherwise(
        tmp_path: Path) -> None:
    """The player's sender gives frames (a file's regions, views of a chunk) to a lone subscriber's socket itself;
    what a full socket does not take is queued as the link would, and frames go the publication's way while that
    queue waits and once a second subscriber comes: every subscriber gets whole frames in order, counted."""
    import threading

    from rostui.core.node.topics import FrameSender, Publication

    _path, regions, expected = _frames_of_a_plain_bag(tmp_path)

    class Pub:
        """The parts of a publication its frame sender reads; its general path counts its calls."""

        latch = False
        local = ()
        lock = threading.Lock()
        messages_published = 0
        general = 0
        links: tuple[Any, ...] = ()

        class node:  # noqa: N801 (the publication's node: this thread is its engine's)
            loop_thread_id = threading.get_ident()

        def publish_frame(self, frame: Any) -> None:
            self.general += 1
            Publication.publish_frame(self, frame)  # type: ignore[arg-type]

    pub = Pub()
    first, first_peer = _SocketTransport.pair()
    first.sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 16384)
    second, second_peer = _SocketTransport.pair()
    pub.links = (_link_over(first, pub),)
    send = FrameSender(pub).send  # type: ignore[arg-type]
    got_first, got_second = bytearray(), bytearray()
    frames: list[Any] = [*regions[:50], *(memoryview(bytes(e)) for e in expected[50:60]), *regions[60:]]

    for frame in frames[:100]:  # a subscriber that keeps up: nothing waits, every frame goes straight
        send(frame)
        _drain(first, first_peer, got_first)
    assert pub.general == 0 and first.queued_writes == 0

    for frame in frames[100:200]:  # one that does not read for a while: its socket fills
        send(frame)
    assert first.queued_writes > 0 and 0 < pub.general < 100
    _drain(first, first_peer, got_first)

    pub.links = (*pub.links, _link_over(second, pub))
    for frame in frames[200:]:
        send(frame)
        _drain(first, first_peer, got_first)
        _drain(second, second_peer, got_second)
    assert bytes(got_first) == b"".join(expected)
    assert bytes(got_second) == b"".join(expected[200:])
    assert pub.messages_published == len(frames)
    assert pub.links[0].messages_sent == len(frames) and pub.links[1].messages_sent == 100


def _drain(transport: _SocketTransport, theirs: socket.socket, got: bytearray) -> None:
    """Read what ``theirs`` holds until ``transport`` has nothing queued and nothing more arrives."""
    while True:
        transport.flush()
        try:
            got += theirs.recv(1 << 16, socket.MSG_DONTWAIT)
        except BlockingIOError:
            if not transport.queue:
                return


def test_a_file_cut_short_under_its_regions_is_the_chunks_error(tmp_path: Path) -> None:
    path, frames, _expected = _frames_of_a_plain_bag(tmp_path)
    os.truncate(path, frames[-1].offset + 2)
    with pytest.raises(MalformedRecord, match=f"{path}: a chunk is cut short"):
        frames[-1].read()
    assert frames[0].read()  # what is still there reads


@pytest.mark.parametrize("seed", range(6))
def test_chunk_order_is_exact_over_overlapping_chunks(seed: int) -> None:
    """Chunks whose spans overlap, touch, nest or stand apart, equal times across chunks: the merge gives
    brute force's order (time, then chunk number, then offset), reading each chunk once."""
    import random

    from rostui.core.bag.chunkorder import chunk_order

    rng = random.Random(seed)
    chunks: dict[int, list[tuple[int, int, int]]] = {}
    for number in range(rng.randint(1, 12)):
        base = rng.choice([0, 10, 50, rng.randint(0, 200)])
        times = sorted(base + rng.randint(0, rng.choice([0, 5, 40])) for _ in range(rng.randint(1, 20)))
        chunks[number] = sorted((t, offset * 7, rng.randint(0, 3)) for offset, t in enumerate(times))
    spans = [(rows[0][0], rows[-1][0], number) for number, rows in chunks.items()]
    read: list[int] = []

    def rows(number: int) -> list[tuple[int, int, int]]:
        read.append(number)
        return chunks[number]

    got = list(chunk_order(spans, rows))
    expected = sorted((t, number, offset, conn) for number, entries in chunks.items() for t, offset, conn in entries)
    assert got == expected
    assert sorted(read) == sorted(chunks)


def test_chunk_runs_give_a_lone_chunk_as_one_run_and_overlapping_chunks_a_message_at_a_time() -> None:
    """Chunks apart in time come whole (the player frames each run with one look at its chunk); where two
    overlap, the merge hands out one message at a time, each run of one chunk; a chunk's last run says so."""
    from rostui.core.bag.chunkorder import chunk_runs

    chunks = {0: [(1, 0, 0), (2, 10, 0), (3, 20, 1)],
              1: [(10, 0, 0), (12, 10, 0)],
              2: [(11, 0, 1), (13, 10, 1)]}
    spans = [(rows[0][0], rows[-1][0], number) for number, rows in chunks.items()]
    runs = list(chunk_runs(spans, chunks.__getitem__))
    assert runs == [(0, chunks[0], True), (1, [(10, 0, 0)], False), (2, [(11, 0, 1)], False),
                    (1, [(12, 10, 0)], True), (2, [(13, 10, 1)], True)]
