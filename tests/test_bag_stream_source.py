"""A player's message source (read ahead in batches, errors raised where they stand, seeks forwards and back) and
how often a player looks at its schedule while it waits.

The stream here is a generator of ``(connection, time, bytes)`` items that counts
how many it has produced; no node is needed.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from rostui.core.bag.model import Connection
from rostui.core.bag.transport import READ_AHEAD, MessageItem, StreamSource, Transport
from rostui.tools.bag.player import QUIET_TICK_PERIOD, STATUS_PERIOD, PlayOptions, Player, open_bags

from bag_view_helpers import write_counts


class Stream:
    """Opens passes over ``count`` messages 1 ns apart, the pass optionally failing at message ``fail_at``."""

    def __init__(self, count: int, fail_at: int | None = None) -> None:
        self.count = count
        self.fail_at = fail_at
        self.produced = 0
        self.passes = 0

    def open(self) -> Iterator[MessageItem]:
        """A new pass from the first message."""
        self.passes += 1
        return self._pass()

    def _pass(self) -> Iterator[MessageItem]:
        for t in range(self.count):
            if t == self.fail_at:
                raise ValueError(f"damaged record at message {t}")
            self.produced += 1
            yield "conn", t, b"%d" % t


def _drain(source: StreamSource) -> list[int]:
    times = []
    while (item := source.peek()) is not None:
        times.append(item[1])
        source.advance()
    return times


def test_messages_are_read_from_the_stream_a_batch_at_a_time() -> None:
    stream = Stream(READ_AHEAD * 2 + 5)
    source = StreamSource(stream.open)
    assert source.peek() == ("conn", 0, b"0")
    assert stream.produced == READ_AHEAD  # one run of the stream's code, not one a message
    for _ in range(READ_AHEAD - 1):
        source.advance()
    assert stream.produced == READ_AHEAD
    assert source.peek() == ("conn", READ_AHEAD - 1, b"%d" % (READ_AHEAD - 1))
    source.advance()
    assert source.peek() is not None
    assert stream.produced == READ_AHEAD * 2
    assert _drain(source) == list(range(READ_AHEAD, READ_AHEAD * 2 + 5))
    assert source.peek() is None


def test_an_error_of_the_stream_comes_after_every_message_before_it_and_ends_the_pass() -> None:
    stream = Stream(100, fail_at=10)
    source = StreamSource(stream.open)
    times = []
    with pytest.raises(ValueError, match="damaged record at message 10"):
        while (item := source.peek()) is not None:
            times.append(item[1])
            source.advance()
    assert times == list(range(10))
    assert source.peek() is None  # raised once, as the stream itself did; the pass is over
    source.advance()
    assert source.peek() is None


@pytest.mark.parametrize("fail_at", [READ_AHEAD, READ_AHEAD * 2 + 3])
def test_a_transport_sends_every_message_before_an_error_of_the_stream_then_raises_it(fail_at: int) -> None:
    stream = Stream(READ_AHEAD * 3, fail_at=fail_at)
    sent: list[int] = []
    conn = Connection(0, "/t", "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data\n")
    transport = Transport(StreamSource(lambda: ((conn, t, data) for _c, t, data in stream.open())),
                          lambda _c, t, _d: sent.append(t), start_ns=0,
                          end_ns=READ_AHEAD * 3 - 1, rate=1000.0)
    with pytest.raises(ValueError, match=f"damaged record at message {fail_at}"):
        asyncio.run(transport.run())
    assert sent == list(range(fail_at)) and transport.published == fail_at


def test_seeking_forwards_skips_and_seeking_back_starts_a_new_pass() -> None:
    stream = Stream(200)
    source = StreamSource(stream.open)
    source.seek(150)
    assert source.peek() == ("conn", 150, b"150")
    assert stream.passes == 1
    source.advance()
    source.seek(151)  # at the read position already: no new pass
    assert source.peek() == ("conn", 151, b"151") and stream.passes == 1
    source.seek(20)
    assert stream.passes == 2
    assert _drain(source)[:3] == [20, 21, 22]
    source.seek(0)  # at the end, back to the start
    assert source.peek() == ("conn", 0, b"0") and stream.passes == 3


class _NodeStub:
    """What a :class:`Player` reads of its node before it plays."""

    namespace = "/"
    name = "/play_test"


@pytest.mark.parametrize(("status", "clock", "tick"), [
    (None, False, QUIET_TICK_PERIOD),  # `bag play -q`: nothing to show while it waits
    (print, False, STATUS_PERIOD),  # the status line moves ten times a second
    (None, True, None),  # /clock at its own rate
])
def test_a_player_looks_at_its_schedule_while_it_waits_only_as_often_as_it_shows_something(
        tmp_path: Path, status: Callable[[str], None] | None, clock: bool, tick: float | None) -> None:
    bag = write_counts(tmp_path / "counts.bag", count=3)
    readers, summaries = open_bags([str(bag)], warn=print)
    try:
        player = Player(_NodeStub(), PlayOptions(files=[str(bag)], clock=clock, clock_hz=100.0), readers,
                        status=status, summaries=summaries)
        if tick is None:
            assert player.transport.tick_period <= 0.01
        else:
            assert player.transport.tick_period == tick
    finally:
        for reader in readers:
            reader.close()
