"""The recorder's receive path: raw TCPROS frames read straight into their own buffers.

A normal subscription reads each chunk of the socket into a new ``bytes``,
appends it to a reassembly buffer and copies the finished frame out again:
three copies of every byte in Python before the message reaches the file. For
1 MB messages those copies (of memory not in any cache) cost more than the
kernel's own receive copy. :class:`RawFrameConnection` is an
``asyncio.BufferedProtocol``: small frames are read into a staging buffer and
sliced out once, and a large frame (``BIG_FRAME`` bytes or more) gets a buffer
of its exact size that the kernel fills directly, which is then handed to the
recorder as it is.

:class:`RawSubscription` is a subscription whose publisher connections use it;
:func:`subscribe_raw` registers one with ``AsyncNode.add_subscription``, so
publisher updates, reconnects and shutdown work as for any other subscription.
"""

from __future__ import annotations

import asyncio
import ctypes
import logging
import mmap
import socket
from collections.abc import Callable
from typing import Any, cast

from rostui.core.bag.sink import LendableBuffer
from rostui.core.node import AnyMsg, AsyncNode, Subscriber
from rostui.core.node.topics import Subscription, TopicHost
from rostui.core.node.transport import PublisherConnection, StallWatch
from rostui.core.tcpros import LEN, MAX_HEADER, decode_header, encode_header, max_frame_from_env

log = logging.getLogger("rostui.bag")

BIG_FRAME = 64 * 1024
"""Frames of this many bytes or more are read into a buffer of their own."""
STAGING_BYTES = 256 * 1024
"""The staging buffer for small frames (it always has room for one whole small frame)."""
LOW_WATER_CAP = 512 * 1024
"""While a big frame is read, the loop wakes only once this much of it (or all the rest) has arrived."""

POOL_CLASS = 64 * 1024
"""Pooled buffers come in multiples of this size (plus a page, so the bytes can start on one)."""
PAGE = mmap.PAGESIZE

#: ``(payload, publisher connection header)``; the payload is ``bytes`` or, for big frames, a writable buffer.
FrameSink = Callable[[Any, dict[str, str]], None]


class BufferPool:
    """Reusable buffers for big frames, so each one is neither zeroed nor faulted in again.

    :meth:`take` (on the receiving thread) hands out a memoryview of exactly
    the asked size, starting on a page, over a :class:`LendableBuffer`
    rounded up to ``POOL_CLASS``: a direct bag file can write it without
    copying it. :meth:`give` (on any thread, once nothing refers to the
    bytes any more) returns it. At most ``limit_bytes`` are kept per size
    class.
    """

    def __init__(self, limit_bytes: int = 64 * 1024 * 1024) -> None:
        self.limit_bytes = limit_bytes
        self._free: dict[int, list[bytearray]] = {}

    def take(self, size: int) -> memoryview:
        """A writable buffer of ``size`` bytes (contents undefined)."""
        capacity = -(-size // POOL_CLASS) * POOL_CLASS + PAGE
        free = self._free.get(capacity)
        try:
            buf = free.pop() if free else LendableBuffer(capacity)
        except IndexError:  # emptied by another thread meanwhile
            buf = LendableBuffer(capacity)
        view = memoryview(buf)
        start = -ctypes.addressof(ctypes.c_char.from_buffer(view)) % PAGE
        return view[start:start + size]

    def give(self, view: Any) -> None:
        """Return a buffer from :meth:`take`; anything else is ignored."""
        if not isinstance(view, memoryview) or not isinstance(view.obj, bytearray):
            return
        buf = view.obj
        free = self._free.setdefault(len(buf), [])
        if (len(free) + 1) * len(buf) <= self.limit_bytes:
            free.append(buf)


class RawFrameConnection(asyncio.BufferedProtocol, PublisherConnection):
    """A subscription's connection to one publisher that delivers raw frames with as few copies as possible.

    ``on_header`` checks the publisher's header (an error string drops the
    connection), ``on_frame(payload, header)`` takes each message, and
    ``on_lost(reason)`` is called once when the connection ends. Big frames
    are read into ``allocate(size)`` (a new bytearray unless a pool is given).

    After a big frame only the next length prefix is read into the stage, so
    the next big frame lands in its own buffer from its first byte instead
    of being copied there from the stage.
    """

    def __init__(self, request_header: dict[str, str], on_header: Callable[[dict[str, str]], str | None],
                 on_frame: FrameSink, on_lost: Callable[[str | None], None],
                 allocate: Callable[[int], Any] = bytearray) -> None:
        self.request_header = request_header
        self.on_header = on_header
        self.on_frame = on_frame
        self.on_lost = on_lost
        self.header: dict[str, str] | None = None
        self.transport: asyncio.Transport | None = None
        self.error: str | None = None
        self.bytes_received = 0
        self.messages_received = 0
        self.max_frame = MAX_HEADER
        self._stage = bytearray(STAGING_BYTES)
        self._stage_view = memoryview(self._stage)
        self._start = 0  # first byte of the stage not yet parsed
        self._end = 0  # end of the bytes received into the stage
        self.allocate = allocate
        self._big: Any = None
        self._big_view: memoryview | None = None
        self._big_filled = 0
        self._expect_big = False
        self._watch: StallWatch | None = None
        self._sock: Any = None
        self._low_water = 1

    # -- asyncio ----------------------------------------------------------------------------
    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        """Send our subscriber header."""
        self.transport = stream = cast(asyncio.Transport, transport)  # TCP: a stream transport
        self._sock = transport.get_extra_info("socket")
        self._watch = StallWatch(self.drop)
        self._watch.progress(1)
        stream.write(encode_header(self.request_header))

    def get_buffer(self, sizehint: int) -> memoryview:
        """Where the next read goes: the rest of the big frame being filled, or the stage's free space."""
        if self._big_view is not None:
            return self._big_view[self._big_filled:]
        if len(self._stage) - self._end < BIG_FRAME + 4:
            self._compact()
        pending = self._end - self._start
        if self._expect_big and pending < 4:
            return self._stage_view[self._end:self._end + 4 - pending]
        return self._stage_view[self._end:]

    def buffer_updated(self, nbytes: int) -> None:
        """``nbytes`` arrived in the buffer :meth:`get_buffer` returned."""
        self.bytes_received += nbytes
        try:
            if self._big is not None:
                self._big_filled += nbytes
                remaining = len(self._big) - self._big_filled
                if not remaining:
                    payload, self._big, self._big_view = self._big, None, None
                    self._expect_big = True
                    self._set_low_water(1)
                    self._frame(payload)
                elif remaining < self._low_water:
                    self._set_low_water(remaining)
            else:
                self._end += nbytes
                self._parse_stage()
        except Exception as exc:  # a bad header or length, or the sink failing: this connection only
            self.drop(str(exc))
            return
        if self._watch is not None:
            self._watch.progress(self._big_filled if self._big is not None else self._end - self._start)

    def eof_received(self) -> bool | None:
        """The publisher closed its side: close ours."""
        return None

    def connection_lost(self, exc: Exception | None) -> None:
        """Report the end of the connection once."""
        if self._watch is not None:
            self._watch.cancel()
        self.on_lost(self.error or (str(exc) if exc else None))

    # -- frames -----------------------------------------------------------------------------
    def _set_low_water(self, nbytes: int) -> None:
        """Wake the loop for this socket only once ``nbytes`` can be read (SO_RCVLOWAT): a 1 MB message then
        takes two or three reads instead of one per 64 KB that trickles in. Never more than the frame still
        needs, so the loop is never left waiting for bytes that are not coming."""
        if self._sock is None or nbytes == self._low_water:
            return
        try:
            self._sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVLOWAT, nbytes)
        except (OSError, AttributeError):
            self._sock = None  # not supported here: read whatever arrives
            return
        self._low_water = nbytes

    def _compact(self) -> None:
        """Move the unparsed tail of the stage to its front."""
        start, end = self._start, self._end
        if start:
            self._stage[: end - start] = self._stage_view[start:end]
            self._start, self._end = 0, end - start

    def _parse_stage(self) -> None:
        """Take every complete frame out of the stage; move a big frame's start to its own buffer."""
        view, start, end = self._stage_view, self._start, self._end
        unpack_from = LEN.unpack_from
        while end - start >= 4:
            (size,) = unpack_from(view, start)
            if size > self.max_frame:
                raise ValueError(f"frame length {size} exceeds the cap of {self.max_frame} bytes")
            stop = start + 4 + size
            if stop <= end:
                payload = bytes(view[start + 4:stop])
                start = stop
                self._expect_big = False
                self._start = start
                self._frame(payload)
                if self.transport is None or self.transport.is_closing():
                    return
                continue
            if size >= BIG_FRAME:
                big = self.allocate(size) if self.header is not None else bytearray(size)
                have = end - start - 4
                big_view = memoryview(big)
                big_view[:have] = view[start + 4:end]
                self._big, self._big_view, self._big_filled = big, big_view, have
                self._set_low_water(min(size - have, LOW_WATER_CAP))
                start = end
            break
        if start == end:
            start = end = 0
        self._start, self._end = start, end

    def _frame(self, payload: Any) -> None:
        """The publisher's header first, then messages."""
        header = self.header
        if header is not None:
            self.messages_received += 1
            self.on_frame(payload, header)
            return
        header = decode_header(payload)
        problem = header.get("error") or self.on_header(header)
        if problem:
            raise ValueError(problem)
        self.header = header
        self.max_frame = max_frame_from_env()


class RawSubscription(Subscription):
    """A raw (``*``) subscription whose publisher connections hand frames to ``sink`` without decoding.

    Publishers in the same process still deliver through the subscription's
    callbacks (as AnyMsg), so register it with a callback too (as
    :func:`subscribe_raw` does).
    """

    def __init__(self, node: TopicHost, topic: str, sink: Callable[[Any, dict[str, str], str], None],
                 allocate: Callable[[int], Any] = bytearray) -> None:
        super().__init__(node, topic, AnyMsg, queue_size=None, tcp_nodelay=False)
        self.sink = sink
        self.allocate = allocate

    def publisher_connection(self, on_lost: Callable[[str | None], None]) -> RawFrameConnection:
        """A RawFrameConnection handing frames to the sink."""
        sink, topic = self.sink, self.topic

        def on_frame(payload: Any, header: dict[str, str]) -> None:
            self.messages_received += 1
            sink(payload, header, topic)

        return RawFrameConnection(self.request_header(), self.check_header, on_frame, on_lost, self.allocate)


async def subscribe_raw(node: AsyncNode, topic: str, sink: Callable[[Any, dict[str, str], str], None],
                        local_callback: Callable[[AnyMsg, str], None],
                        allocate: Callable[[int], Any] = bytearray) -> Subscriber:
    """Subscribe to ``topic`` with md5 ``*``: remote frames go to ``sink(payload, header, topic)`` (big ones
    in buffers from ``allocate``), messages of same-process publishers to ``local_callback(msg, topic)``."""
    name = node.resolve(topic)
    return await node.add_subscription(RawSubscription(node, name, sink, allocate), local_callback, name)
