"""``rostui bag play``: a node ``play_...`` that publishes a bag's messages with their original spacing.

Each topic is advertised with the recorded type, md5sum and definition (so any
subscriber of that type accepts it, known locally or not) and latched when it
was latched while recording. The raw bytes are published unchanged.
"""

from __future__ import annotations

import asyncio
import signal
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rostui.core.bag.files import Reader, merged_messages, open_reader
from rostui.core.bag.model import BagError, BagSummary, Connection

SPIN_BEFORE = 0.003  # the last moments before a message are slept without the loop (its timers are ms-grained)
SPIN_LAST = 0.0002
_now = time.perf_counter  # uvloop's loop.time() advances in whole milliseconds: too coarse at 1 kHz
STATUS_PERIOD = 0.1


@dataclass
class PlayOptions:
    """How to play (see ``rostui bag play --help``)."""

    files: list[str] = field(default_factory=list)
    rate: float = 1.0
    loop: bool = False
    start_paused: bool = False
    start_s: float = 0.0
    duration_s: float | None = None
    delay_s: float = 0.2
    clock: bool = False
    clock_hz: float = 100.0
    topics: list[str] = field(default_factory=list)
    queue_size: int = 100


@dataclass
class PlayStats:
    """What playback did: messages published and the lateness of each (seconds)."""

    published: int = 0
    lateness: list[float] = field(default_factory=list)


def status_text(state: str, bag_time_ns: int, elapsed_s: float, total_s: float) -> str:
    """rosbag's status line: `` [RUNNING]  Bag Time: 1234.567890   Duration: 1.000000 / 9.000000``."""
    return (f" [{state}]  Bag Time: {bag_time_ns / 1e9:13.6f}   Duration: {elapsed_s:.6f} / {total_s:.6f}"
            "               ")


class Player:
    """Publishes the messages of one or more bags in time order."""

    def __init__(self, node: Any, opts: PlayOptions, readers: list[Reader], *,
                 status: Callable[[str], None] | None = None, summaries: list[BagSummary] | None = None) -> None:
        if opts.rate <= 0:
            raise BagError("the rate must be greater than 0")
        self.node = node
        self.opts = opts
        self.readers = readers
        self.status = status
        self.summaries = summaries if summaries is not None else [r.summary() for r in readers]
        starts = [s.start_ns for s in self.summaries if s.message_count]
        ends = [s.end_ns for s in self.summaries if s.message_count]
        if not starts:
            starts = ends = [0]
        self.bag_start = min(starts)
        self.bag_end = max(ends)
        self.play_from = self.bag_start + int(opts.start_s * 1e9)
        self.play_until = (self.play_from + int(opts.duration_s * 1e9)) if opts.duration_s is not None else None
        from rostui.core.names import resolve_name

        # --topics names topics as recorded: resolved, but not remapped
        self.wanted = {resolve_name(t, node.namespace, node.name) for t in opts.topics} if opts.topics else None
        self.publishers: dict[tuple[str, str], Any] = {}
        self.clock_pub: Any = None
        self.paused = opts.start_paused
        self.step = asyncio.Event()
        self.resume = asyncio.Event()
        self.stop = asyncio.Event()
        self.stats = PlayStats()
        self._last_status = 0.0
        self._bag_now = self.play_from
        self._next_ns = self.play_from

    def _topics(self) -> dict[str, list[Connection]]:
        by_topic: dict[str, list[Connection]] = {}
        for summary in self.summaries:
            for conn in summary.connections:
                if self.wanted is None or conn.topic in self.wanted:
                    by_topic.setdefault(conn.topic, []).append(conn)
        return by_topic

    async def advertise(self) -> None:
        """Advertise every topic to play with its recorded type; latched when recorded latched."""
        from rostui.core.node import AnyMsg
        from rostui.core.node.topics import TopicType

        for topic, conns in self._topics().items():
            latch = any(c.latching for c in conns)
            for conn in conns:
                key = (conn.topic, conn.md5sum)
                if key in self.publishers:
                    continue
                ttype = TopicType(conn.type, conn.md5sum, conn.definition)
                try:
                    self.publishers[key] = await self.node.advertise(topic, AnyMsg, queue_size=self.opts.queue_size,
                                                                     latch=latch, topic_type=ttype)
                except ValueError:  # the same topic recorded with two types: play the first
                    continue
        if self.opts.clock:
            from rostui.core.msg import get_message_class

            self.clock_pub = await self.node.advertise("/clock", get_message_class("rosgraph_msgs/Clock"),
                                                       queue_size=1)

    def _publish_clock(self, bag_ns: int) -> None:
        if self.clock_pub is not None:
            msg = self.clock_pub.msg_class()
            msg.clock.secs, msg.clock.nsecs = divmod(bag_ns, 1_000_000_000)
            self.clock_pub.publish(msg)

    def toggle_pause(self) -> None:
        """Space: pause or resume."""
        self.paused = not self.paused
        if not self.paused:
            self.resume.set()
        self._show(force=True)

    def step_once(self) -> None:
        """``s`` while paused: publish the next message."""
        if self.paused:
            self.step.set()

    def _show(self, force: bool = False) -> None:
        if self.status is None:
            return
        now = time.monotonic()
        if not force and now - self._last_status < STATUS_PERIOD:
            return
        self._last_status = now
        state = "PAUSED " if self.paused else "RUNNING"
        self.status(status_text(state, self._bag_now, (self._bag_now - self.bag_start) / 1e9,
                                (self.bag_end - self.bag_start) / 1e9))

    async def _wait_until(self, loop: asyncio.AbstractEventLoop, target: float) -> None:
        while True:
            remaining = target - _now()
            if remaining <= 0 or self.stop.is_set():
                return
            if remaining > SPIN_BEFORE:
                period = STATUS_PERIOD if self.clock_pub is None else min(STATUS_PERIOD, 1 / self.opts.clock_hz)
                await asyncio.sleep(min(remaining - SPIN_BEFORE, period))  # stop is checked on each pass
                if self.clock_pub is not None and not self.paused:
                    ahead = max(0.0, target - _now()) * self.opts.rate
                    self._publish_clock(max(self._bag_now, self._next_ns - int(ahead * 1e9)))
                self._show()
                if self.paused:
                    return
            else:
                # a short blocking sleep: precise to tens of microseconds, and it yields the CPU
                # (spinning would make the scheduler preempt us for whole time slices on a busy machine)
                time.sleep(max(0.0, target - _now() - SPIN_LAST))
                while _now() < target:  # the last ~0.2 ms: a sleep's wake-up is about that late
                    pass
                return

    async def _wait_while_paused(self) -> float:
        """Block while paused (a step lets one message through); returns the seconds spent paused."""
        began = time.monotonic()
        while self.paused and not self.stop.is_set():
            self.resume.clear()
            waiters = [asyncio.ensure_future(e.wait()) for e in (self.resume, self.step, self.stop)]
            await asyncio.wait(waiters, timeout=STATUS_PERIOD, return_when=asyncio.FIRST_COMPLETED)
            for w in waiters:
                w.cancel()
            self._show()
            if self.step.is_set():
                self.step.clear()
                return -1.0
        return time.monotonic() - began

    async def play_once(self) -> None:
        """Publish every message once, in time order, with the original spacing divided by the rate."""
        loop = asyncio.get_running_loop()
        rate = self.opts.rate
        wall_zero: float | None = None
        for conn, t, data, _i in merged_messages(self.readers):
            if self.stop.is_set():
                return
            if t < self.play_from:
                continue
            await asyncio.sleep(0)  # the loop's turn: sends, connections, signals, keys
            if self.play_until is not None and t > self.play_until:
                break
            pub = self.publishers.get((conn.topic, conn.md5sum))
            if pub is None:
                continue
            if wall_zero is None:
                wall_zero = _now() - (t - self.play_from) / 1e9 / rate
            target = wall_zero + (t - self.play_from) / 1e9 / rate
            self._next_ns = t
            stepped = False
            while True:
                if self.paused:
                    spent = await self._wait_while_paused()
                    if spent < 0:
                        stepped = True
                        wall_zero = _now() - (t - self.play_from) / 1e9 / rate
                        break
                    wall_zero += spent
                    target += spent
                await self._wait_until(loop, target)
                if not self.paused or self.stop.is_set():
                    break
            if self.stop.is_set():
                return
            self._bag_now = t
            self._publish_clock(t)
            actual = _now()
            pub.publish(_raw(data))
            if not stepped:
                self.stats.lateness.append(actual - target)
            self.stats.published += 1
            self._show()
        if wall_zero is not None and self.opts.loop and not self.stop.is_set():
            end = self.play_until if self.play_until is not None else self.bag_end
            await self._wait_until(loop, wall_zero + (end - self.play_from) / 1e9 / rate)
        await asyncio.sleep(0)

    async def run(self) -> PlayStats:
        """Advertise, wait ``delay`` for subscribers to connect, then play (again and again with ``loop``)."""
        await self.advertise()
        try:
            await asyncio.wait_for(self.stop.wait(), self.opts.delay_s)
        except asyncio.TimeoutError:
            pass
        import gc

        was_enabled = gc.isenabled()
        gc.collect()
        gc.disable()  # playback makes no reference cycles; a collection pause would delay messages by ms
        try:
            while not self.stop.is_set():
                await self.play_once()
                if not self.opts.loop:
                    break
        finally:
            if was_enabled:
                gc.enable()
        self._show(force=True)
        return self.stats


def _raw(data: bytes) -> Any:
    from rostui.core.node import AnyMsg

    return AnyMsg(data)


class KeyReader:
    """Space and ``s`` from a terminal on stdin, in cbreak mode (restored on close)."""

    def __init__(self, player: Player) -> None:
        self.player = player
        self.saved: Any = None
        self.fd = -1

    def open(self, loop: asyncio.AbstractEventLoop) -> None:
        """Start reading keys when stdin is a terminal."""
        if not sys.stdin.isatty():
            return
        import termios
        import tty

        self.fd = sys.stdin.fileno()
        self.saved = termios.tcgetattr(self.fd)
        tty.setcbreak(self.fd)
        loop.add_reader(self.fd, self._on_key)

    def _on_key(self) -> None:
        import os

        key = os.read(self.fd, 16)
        if b" " in key:
            self.player.toggle_pause()
        elif b"s" in key:
            self.player.step_once()

    def close(self, loop: asyncio.AbstractEventLoop) -> None:
        """Give the terminal back as it was."""
        if self.saved is None:
            return
        import termios

        loop.remove_reader(self.fd)
        termios.tcsetattr(self.fd, termios.TCSADRAIN, self.saved)
        self.saved = None


async def _drain(node: Any, timeout: float) -> None:
    """Give publications a moment to send what they queued before the node goes away."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        busy = any(getattr(p, "_pending", None) for p in node.publications.values())
        if not busy:
            return
        await asyncio.sleep(0.02)


async def play(opts: PlayOptions, argv: Sequence[str] = (), *,
               status: Callable[[str], None] | None = None) -> PlayStats:
    """Open the files, start a ``play_...`` node and play; Ctrl-C stops."""
    from rostui.core.node import AsyncNode, MasterUnreachableError

    if not opts.files:
        raise BagError("no bag file given")
    readers: list[Reader] = []
    summaries: list[BagSummary] = []
    try:
        for path in opts.files:
            reader = open_reader(path)
            readers.append(reader)
            summary = reader.summary()
            summaries.append(summary)
            if not summary.message_count:
                why = f" ({summary.problem})" if summary.problem else ""
                raise BagError(f"{path} holds no messages{why}")
        node = AsyncNode("play", anonymous=True, argv=list(argv))
        try:
            await node.start()
        except MasterUnreachableError as exc:
            raise BagError(str(exc)) from None
        loop = asyncio.get_running_loop()
        player = Player(node, opts, readers, status=status, summaries=summaries)
        keys = KeyReader(player)
        try:
            for sig in (signal.SIGINT, signal.SIGTERM):
                loop.add_signal_handler(sig, player.stop.set)
            node.shutdown_hooks.append(lambda _reason: player.stop.set())
            keys.open(loop)
            stats = await player.run()
            await _drain(node, 2.0)
            return stats
        finally:
            keys.close(loop)
            try:
                await asyncio.wait_for(node.shutdown("play finished"), 3.0)
            except (asyncio.TimeoutError, Exception):
                pass
    finally:
        for reader in readers:
            reader.close()
