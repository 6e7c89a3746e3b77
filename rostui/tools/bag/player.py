"""``rostui bag play``: a node ``play_...`` that publishes a bag's messages with their original spacing.

Each topic is advertised with the recorded type, md5sum and definition (so any
subscriber of that type accepts it, known locally or not) and latched when it
was latched while recording. The raw bytes are published unchanged. Messages
play in time order through each file's index, whatever order the file keeps
them in; a file without an index plays in file order, and a line on stderr says so.
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Protocol

from rostui.core.bag.chunk_buffers import BufferPool
from rostui.core.bag.clock import DEFAULT_HZ, BagClock
from rostui.core.bag.files import Reader, open_reader, unordered_notice
from rostui.core.bag.frames import merged_framed_messages
from rostui.core.bag.model import BagError, BagSummary, Connection
from rostui.core.bag.rosbag2_0 import BagReader
from rostui.core.bag.transport import MessageItem, StreamSource, Transport
from rostui.core.records import Record

STATUS_PERIOD = 0.1
QUIET_TICK_PERIOD = 1.0
"""How long a player with no status line and no /clock waits at most before it looks at its schedule again (s):
nothing is shown while it waits, and controls wake it at once.  Each wake-up of an idle process costs this
VM 50-70 µs of CPU (bench/README.md, "Bag play CPU", sixth pass): ten a second were 4 ms of CPU a second
through a bag's quiet stretches."""
TURN_PERIOD = 0.1
"""The longest the player publishes messages due close together without a turn of its event loop (s): keys,
Ctrl-C and new subscribers wait at most this long (a screen's 20 ms is for bag view).  About 25 µs of CPU a
turn: 40 turns a second fewer than at 20 ms are about 6% of a 20 s play's CPU (bench/README.md, "Bag play CPU",
fifth pass)."""
PLAY_CACHE_BYTES = int(os.environ.get("ROSTUI_BAG_PLAY_CACHE_BYTES", str(16 * 1024 * 1024)))
"""Bytes of decompressed chunks the player keeps, shared by its files, while chunks overlap in time (about 20
chunks of rosbag's 768 KB may interleave before one is read twice); a chunk whose last message has gone leaves
at once (:func:`~rostui.core.bag.frames.framed_messages`). Each reader's own 64 MB filled with chunks never read
again: 60 MB more resident memory and 16 000 page faults in a 160 MB bag's play."""


class PlayOptions(Record):
    """How to play (see ``rostui bag play --help``). Records, not dataclasses, here and in the bag reader: a
    player's start is part of what it costs beside ``rosbag play`` (:mod:`rostui.core.records`)."""

    _fields = ("files", "rate", "loop", "start_paused", "start_s", "duration_s", "delay_s", "clock", "clock_hz",
               "topics", "queue_size")

    def __init__(self, files: list[str] | None = None, rate: float = 1.0, loop: bool = False,
                 start_paused: bool = False, start_s: float = 0.0, duration_s: float | None = None,
                 delay_s: float = 0.2, clock: bool = False, clock_hz: float = DEFAULT_HZ,
                 topics: list[str] | None = None, queue_size: int = 100) -> None:
        self.files: list[str] = [] if files is None else files
        self.rate = rate
        self.loop = loop
        self.start_paused = start_paused
        self.start_s = start_s
        self.duration_s = duration_s
        self.delay_s = delay_s
        self.clock = clock
        self.clock_hz = clock_hz
        self.topics: list[str] = [] if topics is None else topics
        self.queue_size = queue_size


class PlayStats(Record):
    """What playback did: messages published and the lateness of each (seconds)."""

    _fields = ("published", "lateness")

    def __init__(self, published: int = 0, lateness: list[float] | None = None) -> None:
        self.published = published
        self.lateness: list[float] = [] if lateness is None else lateness


def status_text(state: str, bag_time_ns: int, elapsed_s: float, total_s: float) -> str:
    """rosbag's status line: `` [RUNNING]  Bag Time: 1234.567890   Duration: 1.000000 / 9.000000``."""
    return (f" [{state}]  Bag Time: {bag_time_ns / 1e9:13.6f}   Duration: {elapsed_s:.6f} / {total_s:.6f}"
            "               ")


async def advertise_connections(node: Any, conns: Sequence[Connection], queue_size: int = 100, *,
                                warn: Callable[[str], None] | None = None) -> dict[tuple[str, str], Any]:
    """Advertise each connection's topic with its recorded type, md5sum and definition (latched when any
    connection of the topic was); returns the publishers by ``(topic, md5sum)``.

    A topic recorded with two types is published with the first. A connection recorded without a type
    (an MCAP channel with no schema), or with a name or type the node or the master refuses (a ROS 2 type in
    an MCAP file), cannot be advertised: it is skipped, and ``warn`` says so once a topic.
    """
    from rostui.core.node import AnyMsg
    from rostui.core.node.node import MasterRefusedError
    from rostui.core.node.topics import TopicType

    latched = {c.topic for c in conns if c.latching}
    publishers: dict[tuple[str, str], Any] = {}
    untyped: set[str] = set()
    for conn in conns:
        key = (conn.topic, conn.md5sum)
        if key in publishers:
            continue
        if not conn.type:
            if warn is not None and conn.topic not in untyped:
                warn(f"{conn.topic} was recorded without a message type: it is not played")
            untyped.add(conn.topic)
            continue
        ttype = TopicType(conn.type, conn.md5sum, conn.definition)
        try:
            publishers[key] = await node.advertise(conn.topic, AnyMsg, queue_size=queue_size,
                                                   latch=conn.topic in latched, topic_type=ttype)
        except (ValueError, MasterRefusedError) as exc:
            if warn is not None and conn.topic not in untyped:
                warn(f"{conn.topic} ({conn.type}) cannot be advertised ({exc}): it is not played")
            untyped.add(conn.topic)
    return publishers


class Player:
    """Publishes the messages of one or more bags in time order, through one :class:`Transport`."""

    def __init__(self, node: Any, opts: PlayOptions, readers: list[Reader], *,
                 status: Callable[[str], None] | None = None, summaries: list[BagSummary] | None = None,
                 warn: Callable[[str], None] | None = None) -> None:
        if opts.rate <= 0:
            raise BagError("the rate must be greater than 0")
        self.node = node
        self.warn = warn
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
        play_from = self.bag_start + int(opts.start_s * 1e9)
        play_until = (play_from + int(opts.duration_s * 1e9)) if opts.duration_s is not None else None
        from rostui.core.names import resolve_name

        # --topics names topics as recorded: resolved, but not remapped
        self.wanted = {resolve_name(t, node.namespace, node.name) for t in opts.topics} if opts.topics else None
        self.publishers: dict[tuple[str, str], Any] = {}
        # by id() of a Connection, kept beside it so that no other object can take its id
        self._senders: dict[int, tuple[Connection, Callable[[Any], None]]] = {}
        self.clock = BagClock(opts.clock_hz) if opts.clock else None
        self.stop = asyncio.Event()
        self.stats = PlayStats()
        self._last_status = 0.0
        if self.clock is not None:
            tick = self.clock.tick_period(STATUS_PERIOD)
        else:
            tick = STATUS_PERIOD if status is not None else QUIET_TICK_PERIOD
        self.transport = Transport(StreamSource(self._stream), self._publish, start_ns=self.bag_start,
                                   end_ns=self.bag_end, rate=opts.rate, loop=opts.loop, paused=opts.start_paused,
                                   play_from=play_from, play_until=play_until, accepts=self._accepts,
                                   on_tick=self._on_tick, tick_period=tick, turn_period=TURN_PERIOD,
                                   sender_for=self._sender_for)

    def _stream(self) -> Iterator[MessageItem]:
        return merged_framed_messages(self.readers)  # items carry frames, not payloads: see _publish

    @property
    def paused(self) -> bool:
        """True while paused."""
        return self.transport.paused

    def _topics(self) -> dict[str, list[Connection]]:
        by_topic: dict[str, list[Connection]] = {}
        for summary in self.summaries:
            for conn in summary.connections:
                if self.wanted is None or conn.topic in self.wanted:
                    by_topic.setdefault(conn.topic, []).append(conn)
        return by_topic

    async def advertise(self) -> None:
        """Advertise every topic to play with its recorded type; latched when recorded latched."""
        conns = [c for conns in self._topics().values() for c in conns]
        self.publishers = await advertise_connections(self.node, conns, self.opts.queue_size, warn=self.warn)
        if self.clock is not None:
            await self.clock.advertise(self.node)

    def _accepts(self, conn: Connection) -> bool:
        return (conn.topic, conn.md5sum) in self.publishers

    def _frame_sender(self, conn: Connection) -> Callable[[Any], None]:
        """The call that publishes ``conn``'s frames."""
        sender: Callable[[Any], None] = self.publishers[(conn.topic, conn.md5sum)].impl.frame_sender()
        return sender

    def _sender_for(self, conn: Connection) -> Callable[[Any], None] | None:
        """For the transport: ``conn``'s frame sender while nothing else is done a message (no /clock, no status
        line), so each message goes from the transport to the publication; else None (:meth:`_publish`)."""
        return self._frame_sender(conn) if self.clock is None and self.status is None else None

    def _look_up_sender(self, conn: Connection) -> Callable[[Any], None]:
        """The call that publishes ``conn``'s frames, remembered for the connection (:meth:`_publish` asks once)."""
        self._senders[id(conn)] = (conn, self._frame_sender(conn))
        return self._senders[id(conn)][1]

    def _publish(self, conn: Connection, t: int, frame: Any) -> None:
        """Publish one message of the stream: ``frame`` is its bytes as TCPROS frames them."""
        if self.clock is not None:
            self.clock.publish(t)
        known = self._senders.get(id(conn))
        (known[1] if known is not None and known[0] is conn else self._look_up_sender(conn))(frame)
        if self.status is not None:
            self._show()

    def _on_tick(self, bag_ns: int) -> None:
        if self.clock is not None:  # paused too: rosbag play keeps publishing the time it stands at
            self.clock.publish(bag_ns)
        self._show()

    def toggle_pause(self) -> None:
        """Space: pause or resume."""
        self.transport.toggle_pause()
        self._show(force=True)

    def step_once(self) -> None:
        """``s`` while paused: publish the next message."""
        self.transport.step()

    def _show(self, force: bool = False) -> None:
        if self.status is None:
            return
        now = time.monotonic()
        if not force and now - self._last_status < STATUS_PERIOD:
            return
        self._last_status = now
        state = "PAUSED " if self.transport.paused else "RUNNING"
        shown = self.transport.last_ns if self.transport.last_ns is not None else self.transport.play_from
        self.status(status_text(state, shown, (shown - self.bag_start) / 1e9, (self.bag_end - self.bag_start) / 1e9))

    async def run(self) -> PlayStats:
        """Advertise, wait ``delay`` for subscribers to connect, then play (again and again with ``loop``)."""
        await self.advertise()
        try:
            await asyncio.wait_for(self.stop.wait(), self.opts.delay_s)
        except asyncio.TimeoutError:
            pass
        if self.stop.is_set():
            return self.stats
        import gc

        was_enabled = gc.isenabled()
        gc.freeze()  # what is alive now stays: out of every collection's walk, for less than one full collection
        gc.disable()  # playback makes no reference cycles; a collection pause would delay messages by ms
        stopper = asyncio.ensure_future(self.stop.wait())
        stopper.add_done_callback(lambda _f: self.transport.stop())
        try:
            await self.transport.run()
        finally:
            stopper.cancel()
            if was_enabled:
                gc.enable()
        self.stats.published = self.transport.published
        self.stats.lateness = self.transport.lateness
        self._show(force=True)
        return self.stats


class PlayControls(Protocol):
    """What steers a player while it plays (``rostui bag play``'s keys on its terminal)."""

    def open(self, loop: asyncio.AbstractEventLoop, player: Player) -> None:
        """Start steering ``player`` from ``loop``."""

    def close(self, loop: asyncio.AbstractEventLoop) -> None:
        """Stop, leaving whatever was borrowed as it was."""


async def _drain(node: Any, timeout: float) -> None:
    """Give publications a moment to send what they queued before the node goes away."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        busy = any(getattr(p, "_pending", None) for p in node.publications.values())
        if not busy:
            return
        await asyncio.sleep(0.02)


def _stderr_line(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


def open_bags(paths: Sequence[str], warn: Callable[[str], None]) -> tuple[list[Reader], list[BagSummary]]:
    """Open each bag to play and read its summary; ``warn`` gets one line per file that cannot play in time
    order. BagError (every file closed) for a file that cannot be read or holds no messages."""
    readers: list[Reader] = []
    summaries: list[BagSummary] = []
    try:
        for path in paths:
            reader = open_reader(path)
            readers.append(reader)
            reader.cache.max_bytes = min(reader.cache.max_bytes, PLAY_CACHE_BYTES // len(paths))
            if isinstance(reader, BagReader):  # its frames are views of its chunks, which take turns in a few buffers
                reader.cache.pool = BufferPool()
            summary = reader.summary()
            summaries.append(summary)
            if not summary.message_count:
                why = f" ({summary.problem})" if summary.problem else ""
                raise BagError(f"{path} holds no messages{why}")
            notice = unordered_notice(reader)
            if notice:
                warn(notice)
    except BaseException:
        for reader in readers:
            reader.close()
        raise
    return readers, summaries


async def play(opts: PlayOptions, argv: Sequence[str] = (), *, status: Callable[[str], None] | None = None,
               warn: Callable[[str], None] = _stderr_line, controls: PlayControls | None = None) -> PlayStats:
    """Open the files, start a ``play_...`` node and play; Ctrl-C stops. ``warn`` gets one line per file
    that cannot play in time order; ``controls`` steer the player while it plays."""
    from rostui.core.node import AsyncNode, MasterUnreachableError

    if not opts.files:
        raise BagError("no bag file given")
    readers, summaries = open_bags(opts.files, warn)
    try:
        node = AsyncNode("play", anonymous=True, argv=list(argv))
        try:
            await node.start()
        except MasterUnreachableError as exc:
            raise BagError(str(exc)) from None
        loop = asyncio.get_running_loop()
        player = Player(node, opts, readers, status=status, summaries=summaries, warn=warn)
        try:
            for sig in (signal.SIGINT, signal.SIGTERM):
                loop.add_signal_handler(sig, player.stop.set)
            node.shutdown_hooks.append(lambda _reason: player.stop.set())
            if controls is not None:
                controls.open(loop, player)
            try:
                stats = await player.run()
            finally:  # what was published before a damaged record still reaches its subscribers
                await _drain(node, 2.0)
            return stats
        finally:
            if controls is not None:
                controls.close(loop)
            try:
                await asyncio.wait_for(node.shutdown("play finished"), 3.0)
            except (asyncio.TimeoutError, Exception):
                pass
    finally:
        for reader in readers:
            reader.close()
