"""Bag view's index holds chunks, not messages (issue 35): what it holds, and exact order over overlapping chunks.

The oracle is the per-message index the player uses (``merged_messages``): every
message of the files in time order, ties by file, then file order.  Bag view's
index must give the same order, the same message under a cursor, the same
neighbours and numbers, while holding at most its budget of chunk entries.
"""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag import index as index_module
from rostui.core.bag.files import merged_messages, open_reader, open_writer
from rostui.core.bag.index import VIEW_CACHE_BYTES, BagIndex, IndexSource, load_index
from rostui.core.bag.model import Connection

from bag_view_helpers import Int32

T0 = 1_700_000_000_000_000_000
MS = 1_000_000


def _writer(path: Path) -> Any:
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/a", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/x"))
    writer.add_connection(Connection(1, "/b", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/x"))
    return writer


def write_shuffled(path: Path, count: int, per_chunk: int, seed: int) -> Path:
    """``count`` messages (value = order written) at times drawn from a few hundred instants (so many share a
    time), ``per_chunk`` a chunk: every chunk spans most of the bag, overlapping every other."""
    rng = random.Random(seed)
    writer = _writer(path)
    for i in range(count):
        writer.write(i % 2, T0 + rng.randrange(300) * MS, Int32(data=i).serialize())
        if i % per_chunk == per_chunk - 1:
            writer.flush()
    writer.close()
    return path


def write_steady(path: Path, count: int, per_chunk: int) -> Path:
    """``count`` messages 1 ms apart, in time order, ``per_chunk`` a chunk."""
    writer = _writer(path)
    for i in range(count):
        writer.write(i % 2, T0 + i * MS, Int32(data=i).serialize())
        if i % per_chunk == per_chunk - 1:
            writer.flush()
    writer.close()
    return path


def oracle(paths: list[Path]) -> list[tuple[int, int, str, int]]:
    """``(time, file, topic, value)`` of every message in the player's order."""
    readers = [open_reader(str(p)) for p in paths]
    try:
        return [(t, i, conn.topic, Int32().deserialize(data).data) for conn, t, data, i in merged_messages(readers)]
    finally:
        for reader in readers:
            reader.close()


def heard(index: BagIndex, t_ns: int | None = None) -> list[tuple[int, str, int]]:
    """``(time, topic, value)`` of every message from ``t_ns`` on, as bag view plays them."""
    source = IndexSource(index)
    if t_ns is not None:
        source.seek(t_ns)
    got = []
    while (item := source.peek()) is not None:
        got.append((item[1], item[0].topic, Int32().deserialize(item[2]).data))
        source.advance()
    return got


@pytest.mark.parametrize("suffix", [".bag", ".mcap"])
def test_overlapping_chunks_and_files_play_in_exact_time_order_within_a_small_budget(tmp_path: Path,
                                                                                      suffix: str) -> None:
    paths = [write_shuffled(tmp_path / f"one{suffix}", 1200, 50, 1),
             write_shuffled(tmp_path / f"two{suffix}", 700, 30, 2)]
    expected = oracle(paths)
    index = load_index([str(p) for p in paths], budget=120)
    try:
        assert len(index) == 1900 and len(index.table) == 24 + 24  # type: ignore[arg-type]
        assert index.table is not None and index.table.held_entries == 0  # nothing read but the chunks' counts
        plain = [(t, topic, value) for t, _f, topic, value in expected]
        assert heard(index) == plain
        assert index.table.held_entries <= 120 and index.table.held_chunks <= 4
        assert all(reader.cache.max_bytes <= VIEW_CACHE_BYTES // 2 for reader in index.readers)
        rng = random.Random(3)
        for t in [T0 - 1, T0, T0 + 299 * MS, T0 + 300 * MS] + [T0 + rng.randrange(300) * MS for _ in range(5)]:
            assert heard(index, t) == [m for m in plain if m[0] >= t]
            assert index.table.held_entries <= 120
    finally:
        index.close()


@pytest.mark.parametrize("suffix", [".bag", ".mcap"])
def test_message_under_the_cursor_neighbours_and_numbers_match_the_messages(tmp_path: Path, suffix: str) -> None:
    paths = [write_shuffled(tmp_path / f"one{suffix}", 600, 40, 4),
             write_shuffled(tmp_path / f"two{suffix}", 300, 25, 5)]
    expected = oracle(paths)
    index = load_index([str(p) for p in paths], budget=100)
    try:
        assert index.tracks["/a"].count + index.tracks["/b"].count == 900
        for topic in ("/a", "/b"):
            mine = [m for m in expected if m[2] == topic]
            assert index.tracks[topic].count == len(mine)
            for t in [T0 - 5, T0, T0 + 17 * MS, T0 + 150 * MS + 3, T0 + 299 * MS, T0 + 400 * MS]:
                upto = [m for m in mine if m[0] <= t]
                want = upto[-1] if upto else mine[0]
                ref = index.message_at(topic, t)
                assert ref is not None
                conn, got_t, data = index.item(ref)
                assert (got_t, conn.topic, Int32().deserialize(data).data) == (want[0], topic, want[3])
                assert index.number_in_track(topic, ref) == mine.index(want) + 1
                after = [m[0] for m in mine if m[0] > t]
                before = [m[0] for m in mine if m[0] < t]
                assert index.neighbour_time(topic, t, +1) == (after[0] if after else None)
                assert index.neighbour_time(topic, t, -1) == (before[-1] if before else None)
        assert index.table is not None and index.table.held_entries <= 100
    finally:
        index.close()


def test_what_the_index_holds_follows_the_chunks_not_the_messages(tmp_path: Path) -> None:
    """Ten times the messages in the same number of chunks: the same table, nothing per message held at open,
    and at most the budget once every message has been played."""
    small = load_index([str(write_steady(tmp_path / "small.bag", 2_000, 100))], budget=1000)
    big = load_index([str(write_steady(tmp_path / "big.bag", 20_000, 1000))], budget=1000)
    try:
        assert (len(small), len(big)) == (2_000, 20_000)
        assert small.table is not None and big.table is not None
        assert len(small.table) == len(big.table) == 20
        for index in (small, big):
            arrays = [value for value in vars(index.table).values() if hasattr(value, "shape")]
            arrays += [a for track in index.tracks.values() for a in (track.rows, track.row_counts)]
            assert all(a.shape[0] <= 20 for a in arrays)
            assert index.table.held_entries == 0
        assert len(heard(big)) == 20_000
        assert big.table.held_entries <= 1000 and big.table.loads == 20
        assert [m[2] for m in heard(big, T0 + 12_345 * MS)[:3]] == [12_345, 12_346, 12_347]
    finally:
        small.close()
        big.close()


def test_a_chunk_larger_than_the_budget_is_still_read_and_only_it_is_held(tmp_path: Path) -> None:
    index = load_index([str(write_steady(tmp_path / "steady.mcap", 3_000, 1_000))], budget=10)
    try:
        assert [m[2] for m in heard(index, T0 + 1_500 * MS)[:2]] == [1_500, 1_501]
        assert index.table is not None and index.table.held_chunks == 1
    finally:
        index.close()


def test_density_is_exact_over_few_chunks_and_spread_over_many(tmp_path: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    index = load_index([str(write_steady(tmp_path / "steady.bag", 4_000, 100))])
    try:
        exact = index.density("/a", 8)
        assert exact == [250] * 8
        window = index.density("/b", 4, T0 + 1_000 * MS, T0 + 1_399 * MS)  # 4 chunks reach it: exact
        assert window == [50] * 4
        monkeypatch.setattr(index_module, "EXACT_CHUNKS", 2)
        spread = index.density("/a", 8)
        assert sum(spread) == 2_000 and all(abs(n - 250) <= 2 for n in spread)
        assert sum(index.density("/a", 3, T0 + 1_000 * MS, T0 + 1_999 * MS)) == pytest.approx(500, abs=2)
    finally:
        index.close()


def test_a_file_without_an_index_reads_its_chunks_again_on_demand(tmp_path: Path) -> None:
    path = write_shuffled(tmp_path / "shuffled.bag", 500, 40, 6)
    expected = [(t, topic, value) for t, _f, topic, value in oracle([path])]
    reader = open_reader(str(path))
    index_pos = reader.index_pos  # type: ignore[attr-defined]
    reader.close()
    cut = tmp_path / "cut.bag"
    cut.write_bytes(path.read_bytes()[:index_pos])
    index = load_index([str(cut)], budget=50)
    try:
        assert len(index.notices) == 1 and "cut.bag" in index.notices[0]
        assert heard(index) == expected
        assert index.table is not None and index.table.held_entries <= 50
    finally:
        index.close()


def test_messages_outside_chunks_are_held_whole_and_merged_in_time_order(tmp_path: Path) -> None:
    """An MCAP file of messages outside any chunk (the mcap library without chunking) has no chunk to read
    them again from: they are kept, and still come in time order with the right counts."""
    from mcap.writer import Writer

    path = tmp_path / "loose.mcap"
    rng = random.Random(7)
    times = [T0 + rng.randrange(50) * MS for _ in range(200)]
    with open(path, "wb") as f:
        writer = Writer(f, use_chunking=False)
        writer.start(profile="ros1", library="test")
        schema = writer.register_schema("std_msgs/Int32", "ros1msg", Int32._full_text.encode())
        channels = [writer.register_channel(topic, "ros1", schema, {"md5sum": Int32._md5sum}) for topic in ("/a", "/b")]
        for i, t in enumerate(times):
            writer.add_message(channels[i % 2], t, Int32(data=i).serialize(), t)
        writer.finish()
    index = load_index([str(path)], budget=10)
    try:
        assert len(index) == 200 and index.tracks["/a"].count == 100
        want = sorted((t, i) for i, t in enumerate(times))  # equal times keep the file's order
        assert [(t, value) for t, _topic, value in heard(index)] == want
        assert index.table is not None and index.table.held_entries == 0  # held apart, whole, as said
        ref = index.message_at("/b", T0 + 25 * MS)
        assert ref is not None and index.item(ref)[1] <= T0 + 25 * MS
    finally:
        index.close()
