"""Recording from the bag view: start, stop and split without leaving the app, with per-topic meters.

Each recording (from ``r`` to ``r``) is one :class:`~rostui.tools.bag.recorder.Recorder`
on its own node ``/record_...`` (what ``rostui bag record`` runs). A split asks that
recorder to go on in the next file: the request joins its writer's queue behind
the messages already received, so every message lands in exactly one file, as
with ``rosbag record --split``. Files are named like rosbag's:
``NAME_0.mcap``, ``NAME_1.mcap``, ...

``--size`` and ``--duration`` without ``--split`` are the recorder's own
limits (it stops at the message that reaches them; :attr:`RecordSession.notice`
says which); with ``--split`` the session watches the file and splits as
above, so no message is lost at the change of file.
"""

from __future__ import annotations

import asyncio
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

from rostui.core.bag.model import BagError
from rostui.tools.bag.recorder import Recorder, RecordOptions, base_file_name, split_file_name

#: Seconds of history behind a topic's rate and bandwidth.
RATE_WINDOW = 3.0

#: Seconds a recorder's node may take to shut down.
NODE_TIMEOUT = 3.0

#: Seconds between two looks at the file's size and age (``--split`` with ``--size`` or ``--duration``).
LIMIT_CHECK = 0.05


@dataclass
class TopicMeter:
    """Messages and bytes of one topic: in all, in the current file, and their recent rate."""

    topic: str
    count: int = 0
    size: int = 0
    file_count: int = 0
    file_size: int = 0
    samples: deque[tuple[float, int, int]] = field(default_factory=deque)

    def add(self, nbytes: int) -> None:
        """One message of ``nbytes``."""
        self.count += 1
        self.size += nbytes
        self.file_count += 1
        self.file_size += nbytes

    def sample(self, now: float) -> None:
        """Remember the totals at ``now`` (call a few times a second)."""
        self.samples.append((now, self.count, self.size))
        while self.samples and now - self.samples[0][0] > RATE_WINDOW:
            self.samples.popleft()

    def rates(self) -> tuple[float, float]:
        """Messages per second and bytes per second over the last few seconds."""
        if len(self.samples) < 2:
            return 0.0, 0.0
        (t0, n0, b0), (t1, n1, b1) = self.samples[0], self.samples[-1]
        if t1 <= t0:
            return 0.0, 0.0
        return (n1 - n0) / (t1 - t0), (b1 - b0) / (t1 - t0)


class MeteredRecorder(Recorder):
    """A Recorder that counts each topic's messages."""

    def __init__(self, node: Any, opts: RecordOptions, meters: dict[str, TopicMeter], *,
                 report: Callable[[str], None]) -> None:
        super().__init__(node, opts, report=report)
        self.meters = meters

    def on_frame(self, data: Any, header: dict[str, str], topic: str) -> None:
        """Count and queue the message (the subscriber callback)."""
        if self.stop.is_set():
            return
        meter = self.meters.get(topic)
        if meter is None:
            meter = self.meters[topic] = TopicMeter(topic)
        meter.add(len(data))
        super().on_frame(data, header, topic)


@dataclass
class _Running:
    node: Any
    recorder: MeteredRecorder
    task: asyncio.Task[int]
    started: float = field(default_factory=time.monotonic)  # when its current file began
    retired: bool = False  # its counts have moved to the session's totals


class RecordSession:
    """Start, stop and split recordings of ``opts``'s topics; ``report`` gets rosbag-style progress lines."""

    def __init__(self, opts: RecordOptions, *, master_uri: str | None = None,
                 report: Callable[[str], None] = lambda _line: None) -> None:
        self.opts = opts
        self.master_uri = master_uri
        self.report = report
        self.base = base_file_name(opts)
        self.meters: dict[str, TopicMeter] = {}
        self.files: list[str] = []
        self.errors: list[str] = []
        self.finished_messages = 0
        self.finished_bytes = 0
        self.current: _Running | None = None
        self._notice = ""
        self._closing: set[asyncio.Task[None]] = set()
        self._busy = asyncio.Lock()
        self._watcher: asyncio.Task[None] | None = None

    # -- state --------------------------------------------------------------------------------------
    @property
    def recording(self) -> bool:
        """True while a file is being written."""
        running = self.current
        return running is not None and not running.recorder.stop.is_set() and not running.task.done()

    @property
    def messages(self) -> int:
        """Messages written into all files so far."""
        return self.finished_messages + (self.current.recorder.messages if self.current else 0)

    @property
    def total_bytes(self) -> int:
        """Bytes in all files so far."""
        return self.finished_bytes + (self.current.recorder.total_bytes if self.current else 0)

    @property
    def dropped(self) -> int:
        """Messages dropped because the disk could not keep up."""
        return self.current.recorder.dropped if self.current else 0

    @property
    def notice(self) -> str:
        """Why the recording stopped by itself (``reached --duration 30 s``), from the moment it stops."""
        running = self.current
        if running is not None and running.recorder.limit_reached:
            return running.recorder.limit_reached
        return self._notice

    @property
    def file(self) -> str:
        """The file being written (or the last one)."""
        return self.files[-1] if self.files else ""

    @property
    def subscribed(self) -> set[str]:
        """Topics the current recorder subscribes to."""
        return set(self.current.recorder.subscribed) if self.current else set()

    def next_name(self) -> str:
        """The name of the next file: ``NAME_<n>`` like ``rosbag record --split``."""
        return split_file_name(self.base, len(self.files))

    def sample(self) -> None:
        """Take a rate sample of every topic (the app's timer)."""
        now = time.monotonic()
        for meter in self.meters.values():
            meter.sample(now)
        if self.current is not None and self.current.task.done():
            self._collect_error(self.current)

    # -- control ------------------------------------------------------------------------------------
    async def _launch(self) -> _Running:
        from rostui.core.node import AsyncNode, MasterUnreachableError

        name = self.next_name()
        opts = replace(self.opts, output_name=name, output_prefix=None, split=False)
        if self.opts.split:  # the session starts the next file itself (see split)
            opts = replace(opts, size_mb=None, duration_s=None)
        node = AsyncNode("record", anonymous=True, master_uri=self.master_uri)
        node.log.console = None  # library warnings must not write over the screen
        try:
            await node.start(publish_rosout=False)
            await asyncio.wait_for(node.master_call("getPid"), NODE_TIMEOUT)
            recorder = MeteredRecorder(node, opts, self.meters, report=self.report)
        except MasterUnreachableError as exc:
            await _shutdown(node)
            raise BagError(str(exc)) from None
        except (OSError, asyncio.TimeoutError):
            await _shutdown(node)
            raise BagError(f"no master answers at {node.master_uri}") from None
        except BagError:
            await _shutdown(node)
            raise
        self.files.append(name)
        task = asyncio.ensure_future(recorder.run())
        running = _Running(node, recorder, task)
        task.add_done_callback(lambda _task: self._ended(running))
        return running

    def _ended(self, running: _Running) -> None:
        """A recorder's run is over; when that was not our stop or split (a limit, an error), say why and
        close its node."""
        if self.current is not running:
            return
        self.current = None
        self._retire(running)
        self._notice = running.recorder.limit_reached or ""
        self._in_background(_shutdown(running.node))

    def _in_background(self, coro: Any) -> None:
        task = asyncio.ensure_future(coro)
        self._closing.add(task)
        task.add_done_callback(self._closing.discard)

    async def start(self) -> None:
        """Start recording into the next file (BagError when there is no master)."""
        async with self._busy:
            if self.recording:
                return
            stopped, self.current = self.current, None
            if stopped is not None:  # it stopped by itself (a limit) and may still be closing its file
                await self._finish(stopped)
            for meter in self.meters.values():
                meter.file_count = meter.file_size = 0
            self._notice = ""
            self.current = await self._launch()
            if self.opts.split and (self.opts.size_mb or self.opts.duration_s) and self._watcher is None:
                self._watcher = asyncio.ensure_future(self._split_at_limits())

    async def stop(self) -> None:
        """Finish the current file (index and statistics) and wait until it is closed."""
        async with self._busy:
            running, self.current = self.current, None
            if running is not None:
                await self._finish(running)

    async def split(self) -> None:
        """Close the current file and go on in the next one, losing no message and doubling none."""
        async with self._busy:
            running = self.current
            if running is None or running.recorder.stop.is_set():
                return
            name = self.next_name()
            running.recorder.next_file(name)  # these lines run in one step of the loop, between two messages
            self.files.append(name)
            running.started = time.monotonic()
            for meter in self.meters.values():
                meter.file_count = meter.file_size = 0

    async def close(self) -> None:
        """Stop recording and wait for every file to be closed."""
        if self._watcher is not None:
            self._watcher.cancel()
            self._watcher = None
        await self.stop()
        if self._closing:
            await asyncio.gather(*self._closing, return_exceptions=True)

    # -- helpers ------------------------------------------------------------------------------------
    def limit_due(self, running: _Running, now: float) -> str:
        """With --split: which limit the current file has reached (``""``: none)."""
        opts = self.opts
        if opts.size_mb is not None:
            name, size = running.recorder.current_file
            if name == self.file and size >= opts.size_mb * 1e6:  # not before the writer has begun that file
                return f"--size {opts.size_mb:g} MB"
        if opts.duration_s is not None and now - running.started >= opts.duration_s:
            return f"--duration {opts.duration_s:g} s"
        return ""

    async def _split_at_limits(self) -> None:
        """With --split: go on in the next file whenever the current one reaches --size or --duration."""
        while True:
            await asyncio.sleep(LIMIT_CHECK)
            running = self.current
            if running is not None and self.recording and self.limit_due(running, time.monotonic()):
                await self.split()

    async def _finish(self, running: _Running) -> None:
        running.recorder.stop.set()
        try:
            await running.task
        except Exception:
            pass
        self._retire(running)
        await _shutdown(running.node)

    def _retire(self, running: _Running) -> None:
        """Move a finished recorder's counts to the session's totals (once) and keep its error."""
        if running.retired:
            return
        running.retired = True
        self._collect_error(running)
        self.finished_messages += running.recorder.messages
        self.finished_bytes += running.recorder.total_bytes

    def _collect_error(self, running: _Running) -> None:
        task = running.task
        problem = running.recorder.error
        if task.done() and not task.cancelled() and task.exception() is not None:
            problem = str(task.exception())
        if problem and problem not in self.errors:
            self.errors.append(problem)


async def _shutdown(node: Any) -> None:
    try:
        await asyncio.wait_for(node.shutdown("rostui bag view: recording finished"), NODE_TIMEOUT)
    except Exception:  # the master may be gone; closing our own sockets is all that matters
        pass
