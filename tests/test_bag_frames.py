"""A player's frames: each message of a bag as TCPROS sends it, a view of the chunk in a ``.bag``.

Every frame must be the message's 4-byte little-endian length and then exactly the bytes :meth:`payload` reads,
in the order the player plays (time order, ties in file order; file order without an index), for both formats;
and a view queued for a slow subscriber must not keep its chunk alive.
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

import pytest

from rostui.core.bag.files import merged_messages, open_reader, open_writer
from rostui.core.bag.frames import framed_messages, merged_framed_messages
from rostui.core.bag.model import Connection

from bag_view_helpers import STEP_NS, T0, Int32, write_counts


def _plain(frame: bytes | memoryview) -> bytes:
    (length,) = struct.unpack_from("<I", frame)
    assert length == len(frame) - 4
    return bytes(frame[4:])


@pytest.mark.parametrize("name", ["c.bag", "c.mcap"])
def test_frames_are_the_payloads_with_their_length_in_play_order(tmp_path: Path, name: str) -> None:
    path = str(write_counts(tmp_path / name, count=120, flush_every=25))
    reader = open_reader(path)
    expected = [(c.topic, t, d) for c, t, d, _i in merged_messages([reader])]
    frames = list(framed_messages(reader))
    assert [(c.topic, t, _plain(f)) for c, t, f in frames] == expected
    if name.endswith(".bag"):  # the record's own length field: no copy
        assert all(isinstance(f, memoryview) for _c, _t, f in frames)
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
