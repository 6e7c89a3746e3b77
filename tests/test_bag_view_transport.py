"""The bag transport and index without a ROS graph: what gets published, in what order, after each control.

No test measures wall time: the transport plays a bag of 100 messages 10 ms
apart at a high rate, and the tests check which messages were published.
"""

from __future__ import annotations

import asyncio
import os
from pathlib import Path
from typing import Awaitable, Callable

import pytest

from rostui.core.bag.files import merged_messages, open_reader, open_writer
from rostui.core.bag.index import BagIndex, IndexSource, MessageRef, load_index, message_yaml
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.transport import StreamSource, Transport

from bag_view_helpers import STEP_NS, T0, Int32, write_counts
from conftest import until


def _conn_and_data(index: BagIndex, ref: MessageRef) -> tuple[Connection, bytes]:
    conn, _t, data = index.item(ref)
    return conn, data


@pytest.fixture
def index(tmp_path: Path) -> BagIndex:
    """The counts bag, indexed."""
    write_counts(tmp_path / "counts.mcap")
    return load_index([str(tmp_path / "counts.mcap")])


class Sink:
    """Collects what the transport publishes: ``(topic, value)``."""

    def __init__(self) -> None:
        self.got: list[tuple[str, int]] = []

    def __call__(self, conn: Connection, _t: int, data: bytes) -> None:
        self.got.append((conn.topic, Int32().deserialize(data).data))

    def values(self, topic: str = "/count") -> list[int]:
        """Values published on ``topic``."""
        return [v for t, v in self.got if t == topic]


def drive(transport: Transport, scenario: Callable[[], Awaitable[None]]) -> None:
    """Run the transport and ``scenario`` side by side; stop the transport when the scenario ends."""
    async def main() -> None:
        runner = asyncio.ensure_future(transport.run())
        try:
            await scenario()
        finally:
            transport.stop()
            await asyncio.wait_for(runner, 30)

    asyncio.run(main())


def viewer(index: BagIndex, sink: Sink, **kw: object) -> Transport:
    """A transport as the app makes one: paused, held at the end."""
    return Transport(IndexSource(index), sink, start_ns=index.start_ns, end_ns=index.end_ns, paused=True,
                     hold_at_end=True, **kw)  # type: ignore[arg-type]


def test_index_counts_density_and_message_under_cursor(index: BagIndex) -> None:
    assert len(index) == 150 and index.topics == ["/count", "/odd"]
    assert index.tracks["/odd"].count == 50
    assert sum(index.density("/count", 10)) == 100
    assert index.density("/count", 10) == [10] * 10
    at = index.message_at("/count", T0 + 42 * STEP_NS + 5)
    assert at is not None and message_yaml(*_conn_and_data(index, at)) == "data: 42"
    at = index.message_at("/odd", T0)  # before the first: the first
    assert at is not None and message_yaml(*_conn_and_data(index, at)) == "data: 1"


def test_seek_to_half_then_play_publishes_the_second_half_only(index: BagIndex) -> None:
    sink = Sink()
    transport = viewer(index, sink, rate=20.0)

    async def scenario() -> None:
        transport.seek_fraction(0.5)
        transport.resume()
        await until(lambda: transport.paused and transport.at_end, "the end of the bag")

    drive(transport, scenario)
    assert sink.values() == list(range(50, 100))
    assert sink.values("/odd") == list(range(51, 100, 2))


def test_each_step_publishes_exactly_one_message(index: BagIndex) -> None:
    sink = Sink()
    transport = viewer(index, sink)

    async def scenario() -> None:
        await asyncio.sleep(0.2)
        assert sink.got == []
        for n in range(1, 6):
            assert transport.step()
            await until(lambda: len(sink.got) >= n, f"step {n}")
            await asyncio.sleep(0.05)
            assert len(sink.got) == n
        transport.set_topic_enabled("/count", False)
        transport.step()
        await until(lambda: len(sink.got) >= 6, "a step with /count off")

    drive(transport, scenario)
    assert sink.got == [("/count", 0), ("/count", 1), ("/odd", 1), ("/count", 2), ("/count", 3), ("/odd", 3)]


def test_pause_resume_rate_and_topics(index: BagIndex) -> None:
    sink = Sink()
    transport = viewer(index, sink, rate=0.5)

    async def scenario() -> None:
        transport.resume()
        await until(lambda: len(sink.values()) >= 3, "the first messages")
        transport.pause()
        frozen = len(sink.got)
        await asyncio.sleep(0.2)
        assert len(sink.got) == frozen and transport.paused
        transport.set_topic_enabled("/odd", False)
        transport.set_rate(25.0)
        transport.resume()
        await until(lambda: transport.paused and transport.at_end, "the end")

    drive(transport, scenario)
    assert sink.values() == list(range(100))
    assert all(v < 10 for v in sink.values("/odd"))


def test_a_connections_own_sender_takes_its_bytes_in_place_of_publish_until_its_topic_is_off(
        index: BagIndex) -> None:
    sink = Sink()
    odd: list[int] = []

    def sender_for(conn: Connection) -> Callable[[bytes], None] | None:
        return (lambda data: odd.append(Int32().deserialize(data).data)) if conn.topic == "/odd" else None

    transport = viewer(index, sink, rate=2.0, sender_for=sender_for)
    sent_when_off: list[int] = []

    async def scenario() -> None:
        transport.resume()
        await until(lambda: len(odd) >= 3, "the first odd values")
        transport.set_topic_enabled("/odd", False)
        sent_when_off.append(len(odd))
        transport.set_rate(50.0)
        await until(lambda: transport.paused and transport.at_end, "the end")

    drive(transport, scenario)
    assert sink.values() == list(range(100)) and sink.values("/odd") == []
    assert odd == list(range(1, 2 * len(odd), 2)) and len(odd) == sent_when_off[0] < 50


def test_loop_plays_again_and_end_holds(index: BagIndex) -> None:
    sink = Sink()
    transport = viewer(index, sink, rate=50.0, loop=True)

    async def scenario() -> None:
        transport.resume()
        await until(lambda: len(sink.values()) >= 150, "a second pass")
        transport.set_loop(False)
        await until(lambda: transport.paused and transport.at_end, "the end with loop off")

    drive(transport, scenario)
    counts = sink.values()
    assert counts[:100] == list(range(100)) and counts[100:150] == list(range(50))
    assert counts[-1] == 99


def test_stream_source_seeks_back_by_reading_again(tmp_path: Path) -> None:
    write_counts(tmp_path / "c.bag")
    reader = open_reader(str(tmp_path / "c.bag"))
    source = StreamSource(lambda: ((c, t, d) for c, t, d, _i in merged_messages([reader])))
    source.seek(T0 + 90 * STEP_NS)
    item = source.peek()
    assert item is not None and Int32().deserialize(item[2]).data == 90
    source.seek(T0 + 10 * STEP_NS)
    item = source.peek()
    assert item is not None and item[1] == T0 + 10 * STEP_NS
    reader.close()


def test_a_truncated_file_indexes_what_is_readable_with_a_notice(tmp_path: Path) -> None:
    path = tmp_path / "cut.bag"
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/c"))
    for i in range(300):
        writer.write(0, T0 + i * STEP_NS, Int32(data=i).serialize())
        if i % 100 == 99:
            writer.flush()
    size = writer.size
    os.close(writer.fd) if hasattr(writer, "fd") else writer.out.close()  # killed: no close()
    with open(path, "r+b") as f:
        f.truncate(size - 2500)  # the last chunk loses its end
    index = load_index([str(path)])
    assert 200 <= len(index) < 300
    assert len(index.notices) == 1 and "cut.bag" in index.notices[0] and "readable" in index.notices[0]


def test_garbage_is_a_bag_error(tmp_path: Path) -> None:
    path = tmp_path / "junk.mcap"
    path.write_bytes(os.urandom(4000))
    with pytest.raises(BagError, match="junk.mcap"):
        load_index([str(path)])


def test_clock_ticks_never_run_ahead_of_the_next_message(index: BagIndex) -> None:
    """What /clock hears (ticks) and what is published, in order, never goes back in bag time.

    The test moves the transport's clock in 13 ms jumps (messages are 10 ms apart), so the clock often
    passes a message's time while the transport sleeps before it: a tick then must not say a later time.
    """
    times: list[int] = []
    now = [0.0]

    def clock() -> float:
        now[0] += 1e-5  # also runs on by itself, for the transport's last busy-wait before a message
        return now[0]

    transport = Transport(IndexSource(index), lambda _c, t, _d: times.append(t), start_ns=index.start_ns,
                          end_ns=index.end_ns, on_tick=times.append, tick_period=0.0005, clock=clock)

    async def scenario() -> None:
        while transport.published < 60:
            await asyncio.sleep(0.001)
            now[0] += 0.013

    drive(transport, scenario)
    ticks = len(times) - transport.published
    assert ticks > 0
    assert times == sorted(times)


def _turns_seen(tmp_path: Path, count: int = 100, **options: float) -> set[int]:
    """``count`` messages 10 ms apart played at ``-r 5`` (2 ms): how many had gone out each time a callback on
    the loop looked, between the first and the last."""
    reader = open_reader(str(write_counts(tmp_path / f"dense{count}.bag", count=count)))
    sink = Sink()
    transport = Transport(StreamSource(lambda: ((c, t, d) for c, t, d, _i in merged_messages([reader]))), sink,
                          start_ns=T0, end_ns=T0 + 99 * STEP_NS, rate=5.0, **options)
    seen: list[int] = []

    async def scenario() -> None:
        loop = asyncio.get_running_loop()

        def look() -> None:
            seen.append(len(sink.got))
            if len(sink.got) < every:
                loop.call_later(0.005, look)

        look()
        await until(lambda: len(sink.got) == every, "every message")

    every = count + count // 2  # /count and /odd
    drive(transport, scenario)
    reader.close()
    assert sink.values() == list(range(count))
    return {n for n in seen if 0 < n < every}


def test_messages_due_close_together_still_leave_the_loop_its_turns(tmp_path: Path) -> None:
    """They go out without a loop turn each, but the loop still runs between them at least every LOOP_TURN_PERIOD
    (20 ms) of the schedule: a callback on the loop sees playback part-way."""
    part_way = _turns_seen(tmp_path)
    # the schedule is 0.2 s long: 9 turns of 20 ms part-way (a look re-armed less than 5 ms before a turn misses
    # it: a stall can cost one); a transport that turned the loop only where messages are far apart would show
    # none, one whose turn ran callbacks only after the next batch 4
    assert len(part_way) >= 6, part_way


def test_a_longer_turn_period_turns_the_loop_less_often_but_still_turns_it(tmp_path: Path) -> None:
    """A player's turn period (0.1 s) over a 0.6 s schedule: the loop runs part-way 5 times, against 27 at the
    default 20 ms."""
    player = _turns_seen(tmp_path, count=300, turn_period=0.1)
    screen = _turns_seen(tmp_path, count=300)
    assert 4 <= len(player) <= 6 and len(screen) >= 20, (player, screen)
