"""``rostui bag record``: a node ``record_...`` that writes raw messages as received into a bag.

Messages are never decoded: each arrives as an AnyMsg with its publisher's
connection header, and its bytes go straight to the writer with the
connection's type, md5sum, definition, callerid and latching.
"""

from __future__ import annotations

import asyncio
import os
import queue
import re
import signal
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from rostui.core.bag.files import Writer, open_writer
from rostui.tools.bag.info import status_size
from rostui.core.bag.receive import BufferPool, subscribe_raw
from rostui.core.bag.model import BagError, Connection, connection_key

STATUS_PERIOD = 1.0
DISCOVERY_PERIOD = 1.0
FLUSH_PERIOD = 0.2


@dataclass
class RecordOptions:
    """What to record and where (see ``rostui bag record --help``)."""

    topics: list[str] = field(default_factory=list)
    all_topics: bool = False
    regex: bool = False  # -e: the topics are regular expressions
    exclude: str | None = None
    output_name: str | None = None
    output_prefix: str | None = None
    compression: str = "none"
    split: bool = False
    size_mb: float | None = None
    duration_s: float | None = None
    max_size_mb: float | None = None
    max_chunk_age: float = 0.5
    mcap: bool = False  # --mcap: MCAP where the name gives no format (rosbag's .bag otherwise)


_DURATION_UNITS = {"": 1.0, "s": 1.0, "m": 60.0, "h": 3600.0}


def parse_duration(text: str) -> float:
    """Seconds from rosbag record's ``--duration`` forms: ``30``, ``30s``, ``1.5m``, ``2h``.

    Anything else (or a duration that is not positive) is a BagError naming the accepted forms.
    """
    raw = text.strip()
    unit = raw[-1:] if raw[-1:] in ("s", "m", "h") else ""
    number = raw[:-1] if unit else raw
    try:
        value = float(number) * _DURATION_UNITS[unit]
    except ValueError:
        value = float("nan")
    if not value > 0 or value == float("inf"):
        raise BagError(f"invalid duration '{text}' (a positive number of seconds, optionally with s, m or h: "
                       "30, 30s, 5m, 2h)")
    return value


def stamp(now: float | None = None) -> str:
    """``YYYY-MM-DD-HH-MM-SS`` in local time, as rosbag names its files."""
    return time.strftime("%Y-%m-%d-%H-%M-%S", time.localtime(now))


def base_file_name(opts: RecordOptions, now: float | None = None) -> str:
    """The file name to record to: ``-O`` as given (``.bag`` added when it names no format, as rosbag adds it;
    ``.mcap`` with ``--mcap``), ``-o PREFIX`` plus the date and time, or the date and time alone."""
    default_ext = ".mcap" if opts.mcap else ".bag"
    if opts.output_name:
        name = opts.output_name
        return name if name.endswith((".bag", ".mcap")) else name + default_ext
    ext = default_ext
    prefix = opts.output_prefix or ""
    if prefix.endswith(".bag") or prefix.endswith(".mcap"):
        prefix, ext = os.path.splitext(prefix)
    if prefix and not prefix.endswith("/"):
        prefix += "_"
    return f"{prefix}{stamp(now)}{ext}"


def file_format(name: str) -> str:
    """How a recording's file is written, as the start and end lines say it."""
    return "rosbag v2.0 .bag" if name.endswith(".bag") else "MCAP, not readable by rosbag: `rostui bag convert` makes a .bag"


def recording_line(name: str) -> str:
    """The line that says where recording goes: rosbag's own for a .bag; for MCAP also that it is MCAP (rosbag
    cannot read it)."""
    return f"Recording to '{name}'." if name.endswith(".bag") else f"Recording to '{name}' ({file_format(name)})."


def split_file_name(base: str, index: int) -> str:
    """``name_<index>.ext`` for the pieces of a split recording, as rosbag names them."""
    root, ext = os.path.splitext(base)
    return f"{root}_{index}{ext}"


def _compile(pattern: str) -> re.Pattern[str]:
    try:
        return re.compile(pattern)
    except re.error as exc:
        raise BagError(f"invalid regular expression '{pattern}': {exc}") from None


class TopicFilter:
    """Which topics to record, as rosbag record chooses them: the named ones; all (-a); with -e, those whose
    whole name matches one of the topics taken as regular expressions; -x leaves out, from -a and -e, those
    whose whole name matches its regular expression."""

    def __init__(self, opts: RecordOptions, resolve: Callable[[str], str]) -> None:
        self.all = opts.all_topics
        self.patterns = [_compile(t) for t in opts.topics] if opts.regex else []
        self.explicit = [] if opts.regex else [resolve(t) for t in opts.topics]
        self.exclude = _compile(opts.exclude) if opts.exclude else None
        if not (self.explicit or self.all or self.patterns):
            raise BagError("no topics given: name topics, or use -a (all), or -e with regular expressions")

    @property
    def discovers(self) -> bool:
        """True when topics that appear later must be found by polling the master."""
        return self.all or bool(self.patterns)

    def wants(self, topic: str) -> bool:
        """True when a published topic found by polling should be recorded."""
        if self.exclude is not None and self.exclude.fullmatch(topic):
            return False
        return self.all or any(p.fullmatch(topic) for p in self.patterns)


@dataclass(frozen=True)
class NextFile:
    """A marker in the writer's queue: close the file and go on in ``name`` (a split asked for from outside)."""

    name: str


class Recorder:
    """Records subscribed topics into one file, or a series of files with ``--split``.

    The subscriber callbacks only queue ``(connection, time, bytes)``; a writer
    thread does the file work (chunks, compression, splitting), so a slow disk
    write never stalls receiving. Like rosbag's ``--buffsize``, at most
    ``buffer_bytes`` may wait; past that, messages are dropped with a warning.
    """

    def __init__(self, node: Any, opts: RecordOptions, *, report: Callable[[str], None] = lambda _l: None,
                 buffer_bytes: int = 256 * 1024 * 1024) -> None:
        self.node = node
        self.opts = opts
        self.report = report
        self.buffer_bytes = buffer_bytes
        self.filter = TopicFilter(opts, node.resolve)
        self.base = base_file_name(opts)
        self.connections: dict[int, tuple[dict[str, str], Connection]] = {}
        self.by_key: dict[tuple[str, str, str, str, bool], Connection] = {}
        self.subscribed: set[str] = set()
        self.files: list[str] = []
        self.writer: Writer | None = None
        self.messages = 0
        self.dropped = 0
        self.bytes_before = 0
        self.error: str | None = None
        self.limit_reached: str | None = None  # which limit stopped the recording (``reached --size 1 MB``)
        self.stop = asyncio.Event()
        self._queue: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self._pool = BufferPool()
        self._held: list[Any] = []  # pooled buffers the writer's open chunk or its file may still refer to
        self._queued_bytes = 0
        self._written_bytes = 0
        self._loop: asyncio.AbstractEventLoop | None = None
        self._file_started = 0.0
        self._recent: list[tuple[float, int]] = []

    # -- on the loop thread ---------------------------------------------------------------
    def _connection(self, topic: str, header: dict[str, str]) -> Connection:
        known = self.connections.get(id(header))
        if known is not None and known[0] is header:
            return known[1]
        key = connection_key(topic, header)
        conn = self.by_key.get(key)
        if conn is None:
            conn = Connection(len(self.by_key), topic, header.get("type", ""), header.get("md5sum", ""),
                              header.get("message_definition", ""), header.get("callerid", ""), key[4])
            self.by_key[key] = conn
        self.connections[id(header)] = (header, conn)
        return conn

    def on_frame(self, data: Any, header: dict[str, str], topic: str) -> None:
        """Queue one raw message for the writer thread (the hot path: no decoding, no copy)."""
        if self.stop.is_set():
            return
        if self._queued_bytes - self._written_bytes + len(data) > self.buffer_bytes:
            self.dropped += 1
            if self.dropped == 1 or self.dropped % 100 == 0:
                self.report(f"rostui bag record buffer exceeded ({self.dropped} messages dropped so far)")
            return
        self._queued_bytes += len(data)
        self._queue.put((self._connection(topic, header), time.time_ns(), data))

    def next_file(self, name: str) -> None:
        """Go on in file ``name``: messages received before this call go to the current file, the rest to
        ``name``. One subscriber feeds both files, so none is lost or doubled."""
        if not self.stop.is_set():
            self._queue.put(NextFile(name))

    def on_message(self, raw: Any, topic: str) -> None:
        """Queue a message of a publisher in this process (delivered as an AnyMsg)."""
        self.on_frame(raw._buff, raw._connection_header or {}, topic)

    def _fail(self, message: str) -> None:
        if self.error is None:
            self.error = message
        self.stop.set()

    def _from_writer(self, fn: Callable[..., None], *args: Any) -> None:
        """Run ``fn`` on the loop thread (reports and errors raised by the writer thread)."""
        assert self._loop is not None
        self._loop.call_soon_threadsafe(fn, *args)

    @property
    def current_file(self) -> tuple[str, int]:
        """The file being written and its size so far (``("", 0)`` between two files)."""
        writer = self.writer
        return (writer.path, writer.size) if writer is not None else ("", 0)

    @property
    def total_bytes(self) -> int:
        """Bytes written across all files of this recording."""
        writer = self.writer
        return self.bytes_before + (writer.size if writer is not None else 0)

    # -- on the writer thread -----------------------------------------------------------------
    def _open_next(self) -> None:
        self._open(split_file_name(self.base, len(self.files)) if self.opts.split else self.base)

    def _open(self, name: str) -> None:
        folder = os.path.dirname(name)
        if folder and not os.path.isdir(folder):
            raise BagError(f"cannot record to {name}: folder {folder} does not exist")
        # no chunk CRCs: a CRC of every byte costs more CPU than writing it (rosbag files carry none either)
        self.writer = open_writer(name, self.opts.compression, max_chunk_age=self.opts.max_chunk_age, chunk_crcs=False,
                                  direct=True)
        self.files.append(name)
        self._file_started = time.monotonic()

    def _close_writer(self) -> None:
        writer, self.writer = self.writer, None
        if writer is None:
            return
        self.bytes_before += writer.size
        try:
            writer.close()
        except OSError as exc:
            self._from_writer(self._fail, f"cannot finish {writer.path}: {exc.strerror or exc}")
        self._release_held()

    def _release_held(self) -> None:
        """Give the pooled buffers back once the writer refers to none of them (its open chunk is empty) and
        its file no longer writes straight from them."""
        writer = self.writer
        if self._held and (writer is None or not writer.buffered):
            give = self._pool.give
            busy = writer.out.lent_in_use() if writer is not None else ()
            kept = []
            for view in self._held:
                if id(view.obj) in busy:
                    kept.append(view)
                else:
                    give(view)
            self._held = kept

    def _go_on_in(self, name: str) -> None:
        """Close the file and open ``name`` at this message boundary (a :class:`NextFile` from the queue)."""
        self._close_writer()
        self._open(name)
        self._from_writer(self.report, recording_line(name))

    def _limit(self, why: str) -> None:
        """A --size or --duration limit: the next file with --split, else stop (saying ``why``)."""
        if self.opts.split:
            self._close_writer()
            self._open_next()
            self._from_writer(self.report, recording_line(self.files[-1]))
        else:
            self.limit_reached = why
            self._from_writer(self.stop.set)

    def _write(self, conn: Connection, stamp_ns: int, data: Any) -> bool:
        writer = self.writer
        if writer is None:
            return False
        if conn.id not in writer.connections:
            writer.add_connection(conn)
        if isinstance(data, memoryview):
            self._held.append(data)
        try:
            writer.write(conn.id, stamp_ns, data)
        except OSError as exc:
            self._from_writer(self._fail, f"recording stopped: cannot write {writer.path}: {exc.strerror or exc}")
            return False
        finally:
            self._release_held()
        self.messages += 1
        self._written_bytes += len(data)
        opts = self.opts
        if opts.max_size_mb is not None and self.total_bytes >= opts.max_size_mb * 1e6:
            self.limit_reached = f"reached --max-size {opts.max_size_mb:g} MB"
            self._from_writer(self.report, f"Reached the maximum size of {opts.max_size_mb:g} MB; stopping.")
            self._from_writer(self.stop.set)
            return False
        if opts.size_mb is not None and writer.size >= opts.size_mb * 1e6:
            self._limit(f"reached --size {opts.size_mb:g} MB")
        return True

    def _housekeeping(self) -> bool:
        writer = self.writer
        if writer is None:
            return False
        try:
            writer.flush_if_old()
        except OSError as exc:
            self._from_writer(self._fail, f"recording stopped: cannot write {writer.path}: {exc.strerror or exc}")
            return False
        finally:
            self._release_held()
        if self.opts.duration_s is not None and time.monotonic() - self._file_started >= self.opts.duration_s:
            self._limit(f"reached --duration {self.opts.duration_s:g} s")
        return True

    def _writer_thread(self) -> None:
        """Write queued messages until the stop marker; keep chunks young; close the file."""
        get = self._queue.get
        writing = True
        last_housekeeping = time.monotonic()
        try:
            while True:
                try:
                    item = get(timeout=FLUSH_PERIOD)
                except queue.Empty:
                    item = ()
                if item is None:
                    break
                if isinstance(item, NextFile):
                    if writing:
                        self._go_on_in(item.name)
                    continue
                if item and writing:
                    writing = self._write(*item)
                elif item:
                    self._written_bytes += len(item[2])
                now = time.monotonic()
                if writing and now - last_housekeeping >= FLUSH_PERIOD:
                    last_housekeeping = now
                    writing = self._housekeeping()
        except BagError as exc:
            self._from_writer(self._fail, str(exc))
        finally:
            self._close_writer()

    # -- running ------------------------------------------------------------------------------
    async def _subscribe(self, topic: str) -> None:
        if topic in self.subscribed:
            return
        self.subscribed.add(topic)
        self.report(f"Subscribing to {topic}")
        await subscribe_raw(self.node, topic, self.on_frame, self.on_message, self._pool.take)

    async def _discover(self) -> None:
        while not self.stop.is_set():
            try:
                published = await self.node.master_call("getPublishedTopics", "")
            except Exception:
                published = []
            for topic, _type in published:
                if self.filter.wants(topic):
                    await self._subscribe(topic)
            try:
                await asyncio.wait_for(self.stop.wait(), DISCOVERY_PERIOD)
            except asyncio.TimeoutError:
                pass

    async def _status(self, status: Callable[[str], None]) -> None:
        while not self.stop.is_set():
            try:
                await asyncio.wait_for(self.stop.wait(), STATUS_PERIOD)
                return
            except asyncio.TimeoutError:
                status(self.status_line(time.monotonic()))

    def status_line(self, now: float) -> str:
        """``Recording 'name': N msgs, SIZE, R msg/s`` (rate over the last few seconds)."""
        self._recent.append((now, self.messages))
        self._recent = [(t, n) for t, n in self._recent if now - t <= 5.0]
        t0, n0 = self._recent[0]
        rate = (self.messages - n0) / (now - t0) if now > t0 else 0.0
        name = self.files[-1] if self.files else self.base
        dropped = f", {self.dropped} dropped" if self.dropped else ""
        return (f"Recording '{name}': {self.messages} msgs, {status_size(self.total_bytes)}, "
                f"{rate:.1f} msg/s, {len(self.subscribed)} topics{dropped}")

    async def run(self, status: Callable[[str], None] | None = None) -> int:
        """Record until ``stop`` is set (Ctrl-C, a size or duration limit, or a write error); finalise the file."""
        self._loop = asyncio.get_running_loop()
        self._open_next()
        self.report(recording_line(self.files[-1]))
        thread = threading.Thread(target=self._writer_thread, name="rostui-bag-writer", daemon=True)
        thread.start()
        tasks = [asyncio.ensure_future(self._status(status))] if status is not None else []
        try:
            for topic in self.filter.explicit:
                await self._subscribe(topic)
            if self.filter.discovers:
                tasks.append(asyncio.ensure_future(self._discover()))
            await self.stop.wait()
        finally:
            for task in tasks:
                task.cancel()
            self._queue.put(None)
            await asyncio.get_running_loop().run_in_executor(None, thread.join)
            await asyncio.sleep(0)  # errors the writer thread posted while closing
        return self.messages


async def record(opts: RecordOptions, argv: Sequence[str] = (), *, status: Callable[[str], None] | None = None,
                 report: Callable[[str], None] = print) -> tuple[int, list[str], str | None]:
    """Run a recording node until Ctrl-C or a limit; returns (messages, files, error or None)."""
    from rostui.core.node import AsyncNode, MasterUnreachableError

    loop = asyncio.get_running_loop()
    if hasattr(signal, "SIGXFSZ"):
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a file-size limit becomes a write error, not death
    # the writer thread waits for the GIL after each write; the default 5 ms switch interval would
    # stall it behind the receiving loop (a convoy), capping 1 MB messages at a few hundred per second
    sys.setswitchinterval(0.0005)
    node = AsyncNode("record", anonymous=True, argv=list(argv))
    try:
        await node.start()
    except MasterUnreachableError as exc:
        raise BagError(str(exc)) from None
    try:
        recorder = Recorder(node, opts, report=report)
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, recorder.stop.set)
        node.shutdown_hooks.append(lambda _reason: recorder.stop.set())
        count = await recorder.run(status)
        return count, recorder.files, recorder.error
    finally:
        try:
            await asyncio.wait_for(node.shutdown("record finished"), 3.0)
        except (asyncio.TimeoutError, Exception):
            pass
