"""The rosbag API's reads hold chunks, not messages (issue 35), and keep rosbag's exact order.

``rosbag.Bag(...).read_messages()`` reads what the index says of each chunk and
merges the chunks' entries as it reaches them (:func:`rostui.core.bag.chunkmerge.merged_batches`),
holding at most the budget of entries (``ROSTUI_BAG_INDEX_ENTRIES``). The oracle
in process is brute force: every message in the order written, sorted by time,
then connection (rosbag merges one index per connection), the rest in file
order; across processes it is Debian's rosbag reading the same bag.
"""

from __future__ import annotations

import random
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from rostui.compat import rosbag_bag
from rostui.compat.rosbag_bag import Bag
from rostui.core.bag import chunkmerge
from rostui.core.bag.files import open_reader, open_writer
from rostui.core.bag.model import Connection

from bag_view_helpers import Int32
from test_rosbag_shim import _env, _real, _rosbag_ok
from conftest import need_peer

T0 = 1_700_000_000_000_000_000
MS = 1_000_000

Written = list[tuple[int, int, int]]  # (time, connection id, value) in the order written


def write_bag(path: Path, count: int, per_chunk: int, seed: int | None) -> Written:
    """``count`` Int32 messages (value = order written) on /a and /b, ``per_chunk`` a chunk; with a ``seed``
    their times are drawn from a few hundred instants (ties across connections and chunks, every chunk
    overlapping the others), else 1 ms apart in order."""
    rng = random.Random(seed)
    writer = open_writer(str(path))
    for conn_id, topic in enumerate(("/a", "/b")):
        writer.add_connection(Connection(conn_id, topic, "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/x"))
    written = []
    for i in range(count):
        t = T0 + (rng.randrange(300) * MS if seed is not None else i * MS)
        conn_id = rng.randrange(2) if seed is not None else i % 2
        writer.write(conn_id, t, Int32(data=i).serialize())
        written.append((t, conn_id, i))
        if i % per_chunk == per_chunk - 1:
            writer.flush()
    writer.close()
    return written


def rosbag_order(written: Written) -> list[tuple[int, str, int]]:
    """``(time, topic, value)`` in rosbag's order: time, then connection, then file order."""
    return [(t, ("/a", "/b")[c], v) for t, c, v in sorted(written, key=lambda m: (m[0], m[1]))]


def read(bag: Bag, held: list[int], **kw: Any) -> list[tuple[int, str, int]]:
    """What ``read_messages(**kw)`` gives, noting the entries the bag's chunk table holds after each message."""
    got = []
    for topic, msg, t in bag.read_messages(**kw):
        got.append((t.to_nsec(), topic, msg.data))
        assert bag._table is not None
        held.append(bag._table[1].held_entries)
    return got


@pytest.fixture
def budget(monkeypatch: pytest.MonkeyPatch) -> Iterator[int]:
    """A small entry budget (as ROSTUI_BAG_INDEX_ENTRIES=150 gives)."""
    monkeypatch.setattr(chunkmerge, "ENTRY_BUDGET", 150)
    yield 150


@pytest.mark.parametrize("suffix", [".bag", ".mcap"])
def test_overlapping_chunks_read_in_rosbag_order_within_the_budget(tmp_path: Path, budget: int,
                                                                   suffix: str) -> None:
    path = tmp_path / f"shuffled{suffix}"
    expected = rosbag_order(write_bag(path, 3_000, 40, seed=1))
    held: list[int] = []
    with Bag(str(path)) as bag:
        assert read(bag, held) == expected
        assert bag._table is not None
        table = bag._table[1]
        assert len(table) == 75
        assert all(a.shape[0] <= 75 for a in vars(table).values() if hasattr(a, "shape"))
        for t in (T0 - 1, T0, T0 + 17 * MS, T0 + 150 * MS, T0 + 299 * MS, T0 + 300 * MS):
            assert read(bag, held, start_time=rosbag_bag._time(t)) == [m for m in expected if m[0] >= t]
            assert read(bag, held, end_time=rosbag_bag._time(t)) == [m for m in expected if m[0] <= t]
        lo, hi = T0 + 100 * MS, T0 + 101 * MS
        assert read(bag, held, topics="/b", start_time=rosbag_bag._time(lo), end_time=rosbag_bag._time(hi)) == \
            [m for m in expected if lo <= m[0] <= hi and m[1] == "/b"]
        raw = list(bag.read_messages(raw=True, start_time=rosbag_bag._time(T0 + 200 * MS)))
        if suffix == ".mcap":  # the raw position of an MCAP message is its place in time order
            first = sum(1 for m in expected if m[0] < T0 + 200 * MS)
            assert [r.message[3] for r in raw] == list(range(first, len(expected)))
        assert [Int32().deserialize(r.message[1]).data for r in raw] == \
            [m[2] for m in expected if m[0] >= T0 + 200 * MS]
    assert len(held) > 3_000 and max(held) <= budget


def test_memory_follows_the_chunks_not_the_messages(tmp_path: Path, budget: int) -> None:
    """Ten times the messages in the same number of chunks: the same table, at most the budget held while
    every message is read, and a read from a start time reads only the chunks from there on."""
    small, big = tmp_path / "small.bag", tmp_path / "big.bag"
    write_bag(small, 2_000, 100, seed=None)
    expected = rosbag_order(write_bag(big, 20_000, 1_000, seed=None))
    for path in (small, big):
        with Bag(str(path)) as bag:
            assert bag._table is None  # opening reads the chunks' counts only
            assert bag.get_message_count() == (2_000 if path is small else 20_000)
    held: list[int] = []
    with Bag(str(big)) as bag:
        assert read(bag, held) == expected
        assert bag._table is not None
        table = bag._table[1]
        assert len(table) == 20 and table.loads == 20 and max(held) <= 1_000  # one chunk (1 000) at a time
        assert all(a.shape[0] <= 20 for a in vars(table).values() if hasattr(a, "shape"))
    with Bag(str(big)) as bag:
        first = next(bag.read_messages(start_time=rosbag_bag._time(T0 + 12_345 * MS)))
        assert first.message.data == 12_345
        assert bag._table is not None and bag._table[1].loads == 1


def test_a_bag_without_an_index_reads_its_chunks_in_order(tmp_path: Path, budget: int) -> None:
    path = tmp_path / "shuffled.bag"
    expected = rosbag_order(write_bag(path, 1_000, 40, seed=2))
    reader = open_reader(str(path))
    index_pos = reader.index_pos  # type: ignore[attr-defined]
    reader.close()
    cut = tmp_path / "cut.bag"
    cut.write_bytes(path.read_bytes()[:index_pos])
    with pytest.raises(rosbag_bag.ROSBagUnindexedException):
        Bag(str(cut))
    held: list[int] = []
    with Bag(str(cut), allow_unindexed=True) as bag:
        assert read(bag, held) == expected
        assert read(bag, held, topics=["/a"]) == [m for m in expected if m[1] == "/a"]
    assert max(held) <= budget


def test_a_bag_being_written_reads_what_it_holds_in_order(tmp_path: Path, budget: int) -> None:
    rng = random.Random(4)
    written: Written = []
    held: list[int] = []
    with Bag(str(tmp_path / "live.bag"), "w", chunk_threshold=400) as bag:
        for i in range(600):
            t = T0 + rng.randrange(100) * MS
            topic = ("/a", "/b")[i % 2]
            bag.write(topic, Int32(data=i), rosbag_bag._time(t))
            written.append((t, i % 2, i))
            if i % 150 == 149:
                assert read(bag, held) == rosbag_order(written)
    assert max(held) <= budget


# Reads a bag through whichever rosbag the interpreter has: every message, a start time, topics, a window,
# raw, connection headers, and the topics' frequencies.
READ_ALL = textwrap.dedent('''
    import sys, rosbag, genpy
    with rosbag.Bag(sys.argv[1]) as bag:
        print([(m.topic, m.message.data, m.timestamp.to_nsec()) for m in bag.read_messages()])
        print([m.message.data for m in bag.read_messages(start_time=genpy.Time(100, 150000000))])
        print([m.message.data for m in bag.read_messages(topics=['/b'], end_time=genpy.Time(100, 30000000))])
        print([m.message.data for m in bag.read_messages(['/a', '/c'], genpy.Time(100, 40000000),
                                                          genpy.Time(100, 60000000))])
        print([(t, raw[0], raw[1].hex()) for t, raw, _ in bag.read_messages(raw=True)][:50])
        print([sorted(m.connection_header) for m in bag.read_messages(return_connection_header=True)][:3])
        info = bag.get_type_and_topic_info()
        print(sorted((k, v.message_count, v.frequency) for k, v in info.topics.items()))
        print(bag.get_message_count(), bag.get_start_time(), bag.get_end_time())
''')

# Debian's rosbag writes the bag: three topics, each with its own clock (steps of 0, 1 or 2 ms) running
# 40 ms behind the one before, so chunks overlap in time while each topic's messages stay in order (where a
# topic's own messages are out of order in the file, Debian's rosbag's merge gives them out of order; rostui's
# gives time order); equal times within and across topics and chunks; small chunks.
WRITE_SHUFFLED = textwrap.dedent('''
    import random, sys, rosbag, genpy
    from std_msgs.msg import Int32
    rng = random.Random(7)
    clocks = {'/a': 100000, '/b': 99960, '/c': 99920}
    with rosbag.Bag(sys.argv[1], 'w', chunk_threshold=600) as bag:
        for i in range(2000):
            topic = ('/a', '/b', '/c')[rng.randrange(3)]
            clocks[topic] += rng.randrange(3)
            bag.write(topic, Int32(data=i), genpy.Time(clocks[topic] // 1000, clocks[topic] % 1000 * 1000000))
''')


def test_overlapping_chunks_of_a_real_rosbag_read_as_debian_reads_them(tmp_path: Path) -> None:
    need_peer(_rosbag_ok(), "Debian's rosbag under /usr/bin/python3 (python3-rosbag)")
    (tmp_path / "write.py").write_text(WRITE_SHUFFLED)
    (tmp_path / "read.py").write_text(READ_ALL)
    _real(["write.py", "real.bag"], tmp_path)
    reader = open_reader(str(tmp_path / "real.bag"))
    infos = reader.chunk_infos()
    reader.close()
    assert infos is not None and len(infos) > 30
    assert bool((infos.starts[1:] < infos.ends[:-1]).any()), "the chunks overlap in time"
    theirs = _real(["read.py", "real.bag"], tmp_path)
    r = subprocess.run([sys.executable, "-m", "rostui", "python", "--rostui", "read.py", "real.bag"],
                       env={**_env(), "ROSTUI_BAG_INDEX_ENTRIES": "300"}, cwd=tmp_path, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout == theirs


def test_merged_batches_of_several_files_give_the_players_order(tmp_path: Path) -> None:
    """Ties by file, then file order (rosbag play's order), over overlapping chunks of two files, from any
    start time, within the budget, a few messages a batch."""
    from rostui.core.bag.files import merged_messages

    paths = [tmp_path / "one.mcap", tmp_path / "two.bag"]
    write_bag(paths[0], 400, 30, seed=5)
    write_bag(paths[1], 250, 20, seed=6)
    readers = [open_reader(str(p)) for p in paths]
    try:
        expected = [(t, i, conn.id, Int32().deserialize(data).data) for conn, t, data, i in merged_messages(readers)]
        infos = [r.chunk_infos() for r in readers]
        assert all(i is not None for i in infos)
        table = chunkmerge.table_of([i for i in infos if i is not None],
                                    lambda file, chunk: readers[file].chunk_entries(chunk), budget=60)
        for start in (None, T0, T0 + 123 * MS, T0 + 299 * MS):
            got = []
            for part in chunkmerge.merged_batches(table, start, batch=7):
                assert len(part.times) <= max(7, len(table)) or len(set(part.times.tolist())) == 1
                for t, f, chunk, offset, conn_id in zip(*(column.tolist() for column in part)):
                    got.append((t, f, conn_id, Int32().deserialize(readers[f].payload(chunk, offset)).data))
                assert table.held_entries <= 60
            assert got == [m for m in expected if start is None or m[0] >= start]
    finally:
        for reader in readers:
            reader.close()


def brute_frequency(stamps: list[int]) -> float | None:
    """rosbag's frequency of a topic: 1 / the median difference of its stamps in seconds, in time order."""
    seen = sorted(stamps)
    if len(seen) < 2:
        return None
    periods = sorted(b / 1e9 - a / 1e9 for a, b in zip(seen, seen[1:]))
    half = len(periods) // 2
    period = periods[half] if len(periods) % 2 else float(periods[half - 1] + periods[half]) / 2
    return 1.0 / period if period > 0.0 else None


@pytest.mark.parametrize("suffix", [".bag", ".mcap"])
def test_frequencies_are_rosbags_exact_medians_within_the_budget(tmp_path: Path, budget: int, suffix: str) -> None:
    """Topics of thousands of jittered periods (several passes over the index), equal stamps, two messages,
    one, an even count of equal periods; written out of order in small chunks that overlap."""
    rng = random.Random(8)
    stamps: dict[str, list[int]] = {
        "/jitter": [T0 + i * 10 * MS + rng.randrange(-3 * MS, 3 * MS) for i in range(3_001)],
        "/ties": [T0 + rng.randrange(40) * 25 * MS for _ in range(2_000)],
        "/steady": [T0 + i * 4 * MS for i in range(1_000)],
        "/two": [T0 + 5 * MS, T0 + 7 * MS],
        "/one": [T0],
        "/same": [T0 + 3 * MS] * 10,
    }
    messages = [(t, topic) for topic, ts in stamps.items() for t in ts]
    messages.sort(key=lambda m: m[0] + rng.randrange(100 * MS))  # out of order by up to 0.1 s
    path = tmp_path / f"periods{suffix}"
    writer = open_writer(str(path))
    ids = {topic: i for i, topic in enumerate(stamps)}
    for topic, conn_id in ids.items():
        writer.add_connection(Connection(conn_id, topic, "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/x"))
    for i, (t, topic) in enumerate(messages):
        writer.write(ids[topic], t, Int32(data=i).serialize())
        if i % 50 == 49:
            writer.flush()
    writer.close()
    with Bag(str(path)) as bag:
        info = bag.get_type_and_topic_info()
        assert bag._table is not None and bag._table[1].held_entries <= budget
    for topic, ts in stamps.items():
        assert info.topics[topic].message_count == len(ts)
        assert info.topics[topic].frequency == brute_frequency(ts), topic
    assert info.topics["/one"].frequency is None and info.topics["/same"].frequency is None


@pytest.mark.parametrize("seed", range(6))
def test_median_periods_are_exact_whatever_the_spread(seed: int) -> None:
    """rosbag_periods against brute force on streams cut in blocks: steady, jittered, bursty (many zero
    periods), spread over decades, a few distinct values; 64 periods held at most per rank."""
    import numpy as np

    from rostui.compat.rosbag_periods import median_periods

    rng = random.Random(seed)
    shapes = {
        "steady": [T0 + i * 3 * MS for i in range(5_000)],
        "jitter": [T0 + i * 10 * MS + rng.randrange(-4 * MS, 4 * MS) for i in range(4_001)],
        "bursts": [T0 + (i // 7) * 50 * MS for i in range(3_000)],
        "decades": [T0 + int(10 ** rng.uniform(2, 9)) for _ in range(2_000)],
        "few": [T0 + rng.choice((1, 2, 3)) * i * MS for i in range(1_500)],
    }
    ids = {name: i for i, name in enumerate(shapes)}
    merged = sorted((t, ids[name]) for name, ts in shapes.items() for t in ts)
    times = np.array([t for t, _ in merged], dtype=np.int64)
    conns = np.array([c for _, c in merged], dtype=np.uint32)
    step = rng.randrange(50, 500)

    def passes() -> Iterator[tuple[Any, Any]]:
        for lo in range(0, len(times), step):
            yield times[lo:lo + step], conns[lo:lo + step]

    medians = median_periods(passes, {name: [i] for name, i in ids.items()}, held=64)
    for name, ts in shapes.items():
        frequency = brute_frequency(ts)
        got = medians[name]
        assert (1.0 / got if got > 0.0 else None) == frequency, name
