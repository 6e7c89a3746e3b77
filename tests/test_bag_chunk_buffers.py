"""A player's chunk buffers (core/bag/chunk_buffers.py): a compressed ``.bag``'s chunks take turns in a few
buffers, and a buffer is used again only once nothing refers to it, so a frame still held (queued for a slow
subscriber, or kept by a caller) keeps its bytes however many chunks are read after it.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from rostui.core.bag.chunk_buffers import MAX_BUFFERS, BufferPool
from rostui.core.bag.files import merged_messages, open_reader
from rostui.core.bag.frames import framed_messages

from bag_view_helpers import write_counts


def test_a_buffer_is_taken_again_only_once_nothing_refers_to_it() -> None:
    pool = BufferPool()
    first = pool.take(1000)
    first[:] = b"a" * 1000
    first_id = id(first)
    view = memoryview(first)[10:20]
    pool.give(first)
    del first
    second = pool.take(1000)  # a slice of a view still holds the first
    assert id(second) != first_id and bytes(view) == b"a" * 10
    pool.give(second)
    kept = second  # a plain reference holds it too
    assert pool.take(1000) is not kept
    del view
    again = pool.take(900)
    assert id(again) == first_id and len(again) == 900 and again == b"a" * 900
    pool.give(again)
    del again
    grown = pool.take(1100)
    assert id(grown) == first_id and len(grown) == 1100 and grown[:900] == b"a" * 900


def test_the_pool_keeps_a_few_buffers_the_newest() -> None:
    pool = BufferPool()
    given = [bytearray(10) for _ in range(MAX_BUFFERS + 2)]
    ids = [id(b) for b in given]
    for buffer in given:
        pool.give(buffer)
    del given, buffer
    taken = [pool.take(10) for _ in range(MAX_BUFFERS + 1)]
    assert sorted(id(b) for b in taken[:MAX_BUFFERS]) == sorted(ids[2:])
    assert id(taken[-1]) not in ids[2:]


@pytest.mark.parametrize("hold", [False, True], ids=["frames let go", "every frame held"])
def test_a_played_lz4_bag_reads_its_chunks_into_a_few_buffers_and_held_frames_keep_their_bytes(
        tmp_path: Path, hold: bool) -> None:
    """Frames let go as they are sent: the chunks take turns in two buffers.  Every frame held (a subscriber that
    never reads): no buffer is used again, and each frame is still its message at the end."""
    path = str(write_counts(tmp_path / "c.bag", count=300, flush_every=20, compression="lz4"))
    first = open_reader(path)
    expected = [d for _c, _t, d, _i in merged_messages([first])]
    first.close()
    reader = open_reader(path)
    pool = reader.cache.pool = BufferPool()
    taken: list[int] = []
    take = pool.take
    pool.take = lambda size: taken.append(id(buffer := take(size))) or buffer  # type: ignore[method-assign]
    held = []
    for (_c, _t, frame), payload in zip(framed_messages(reader), expected, strict=True):
        assert bytes(frame)[4:] == payload
        if hold:
            held.append(frame)
    reader.close()
    assert len(taken) == 15  # one a chunk
    if hold:
        assert len(set(taken)) == 15
        assert [bytes(f)[4:] for f in held] == expected
    else:
        assert len(set(taken)) <= 2


@pytest.mark.parametrize("compression", ["bz2", "lz4"])
def test_compressed_chunks_read_through_the_pools_read_buffer_give_every_message(
        tmp_path: Path, compression: str) -> None:
    """Each chunk's stored bytes go into the pool's one read buffer and are decompressed out of it before the next
    chunk is read over them: bz2 (the general way, from a view) and lz4 (straight into a pooled buffer) alike."""
    path = str(write_counts(tmp_path / "c.bag", count=300, flush_every=20, compression=compression))
    plain = open_reader(path)
    expected = [d for _c, _t, d, _i in merged_messages([plain])]
    plain.close()
    reader = open_reader(path)
    reader.cache.pool = BufferPool()
    assert [bytes(frame)[4:] for _c, _t, frame in framed_messages(reader)] == expected
    reader.close()


def test_the_read_buffer_gives_what_the_file_holds_and_fewer_bytes_at_its_end(tmp_path: Path) -> None:
    """A larger read takes a new buffer: a view of the previous read keeps its bytes, and no resize of a buffer
    still viewed is attempted (which Python refuses)."""
    data = bytes(range(256)) * 40
    path = tmp_path / "f"
    path.write_bytes(data)
    pool = BufferPool()
    with open(path, "rb") as f:
        small = pool.read_stored(f.fileno(), 100, 50)
        assert bytes(small) == data[100:150]
        large = pool.read_stored(f.fileno(), 1000, 5000)
        assert bytes(large) == data[1000:6000] and bytes(small) == data[100:150]
        tail = pool.read_stored(f.fileno(), len(data) - 10, 100)
        assert bytes(tail) == data[-10:]
