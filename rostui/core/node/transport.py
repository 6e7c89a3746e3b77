"""asyncio protocols for TCPROS connections of a node.

`InboundConnection` is every connection accepted by a node's TCPROS server: it
reads the peer's header and hands the connection to a topic publication or a
service.  `SubscriberConnection` is the connection a subscription opens to a
publisher (a `PublisherConnection`).  Both drop a peer that stalls mid-frame,
sends a bad header or a length over the cap, and never let one peer affect
another.
"""

from __future__ import annotations

import asyncio
import logging
import socket
from typing import Any, Callable, Protocol, cast

from rostui.core.node.busypoll import BusyPoll
from rostui.core.tcpros import (
    MAX_HEADER,
    FrameReader,
    TcprosError,
    decode_header,
    encode_header,
    max_frame_from_env,
    stall_timeout_from_env,
)

log = logging.getLogger("rostui.tcpros")


def set_nodelay(transport: asyncio.BaseTransport) -> None:
    """Turn on TCP_NODELAY on a transport's socket where it has one."""
    sock = transport.get_extra_info("socket")
    if sock is not None:
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        except OSError:
            pass


class StallWatch:
    """Closes a transport when a partial frame sees no progress for too long."""

    __slots__ = ("_loop", "_timeout", "_handle", "_last", "_close")

    def __init__(self, close: Callable[[str], None], timeout: float | None = None) -> None:
        self._loop = asyncio.get_running_loop()
        self._timeout = stall_timeout_from_env() if timeout is None else timeout
        self._handle: asyncio.TimerHandle | None = None
        self._last = 0.0
        self._close = close

    def progress(self, pending: int) -> None:
        """Record received bytes; ``pending`` is how many wait for a frame end."""
        if pending:
            self._last = self._loop.time()
            if self._handle is None:
                self._handle = self._loop.call_later(self._timeout, self._check, pending)
        elif self._handle is not None:
            self._handle.cancel()
            self._handle = None

    def _check(self, _pending: int) -> None:
        idle = self._loop.time() - self._last
        if idle >= self._timeout:
            self._handle = None
            self._close(f"peer stalled mid-frame for {idle:.1f}s")
        else:
            self._handle = self._loop.call_later(self._timeout - idle, self._check, 0)

    def cancel(self) -> None:
        """Stop watching (connection closed)."""
        if self._handle is not None:
            self._handle.cancel()
            self._handle = None


class ConnectionRouter(Protocol):
    """What an InboundConnection needs from its node to route a new peer."""

    busy_poll: BusyPoll | None

    def route_inbound(self, header: dict[str, str], conn: "InboundConnection") -> "InboundHandler | str":
        """Return a handler for the connection, or an error string to refuse it."""


class InboundHandler(Protocol):
    """The per-connection logic that takes over after the header exchange."""

    def frames_received(self, frames: list[bytes]) -> None:
        """Frames sent by the peer after its header."""

    def connection_lost(self) -> None:
        """The peer went away or was dropped."""

    def pause_writing(self) -> None:
        """The transport's write buffer is full."""

    def resume_writing(self) -> None:
        """The transport's write buffer drained."""


class InboundConnection(asyncio.Protocol):
    """A connection accepted by a node's TCPROS server."""

    def __init__(self, router: ConnectionRouter) -> None:
        self.router = router
        self.transport: asyncio.Transport | None = None
        self.reader = FrameReader(MAX_HEADER)
        self.handler: InboundHandler | None = None
        self.peer: Any = None
        self.busy_poll = router.busy_poll
        self._watch: StallWatch | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        """Start the header timer."""
        self.transport = cast(asyncio.Transport, transport)  # TCP: a stream transport
        self.peer = transport.get_extra_info("peername")
        self._watch = StallWatch(self.drop)
        self._watch.progress(1)

    def data_received(self, data: bytes) -> None:
        """Read the header, route, then pass frames to the handler."""
        if self.busy_poll is not None:
            self.busy_poll.traffic()
        handler = self.handler
        if handler is not None:
            # One whole frame with nothing buffered: the stall watch is idle (see SubscriberConnection).
            payload = self.reader.whole_frame(data)
            if payload is not None:
                handler.frames_received([payload])
                return
        try:
            if self.handler is None:
                if not self._read_header(data):
                    return
                data = b""
            frames = self.reader.feed(data)
        except TcprosError as exc:
            if self.handler is None:
                self.refuse(str(exc))
            else:
                self.drop(str(exc))
            return
        finally:
            if self._watch is not None:
                self._watch.progress(self.reader.pending)
        if frames and self.handler is not None:
            self.handler.frames_received(frames)

    def _read_header(self, data: bytes) -> bool:
        """Take the peer's header and route the connection; True once routed."""
        frames = self.reader.feed(data, limit=1)
        if not frames:
            return False
        routed = self.router.route_inbound(decode_header(frames[0]), self)
        if isinstance(routed, str):
            raise TcprosError(routed)
        self.handler = routed
        self.reader.max_frame = max_frame_from_env()
        return self.transport is not None and not self.transport.is_closing()

    def write(self, data: bytes) -> None:
        """Send bytes unless the connection is closing."""
        if self.transport is not None and not self.transport.is_closing():
            self.transport.write(data)

    def refuse(self, reason: str) -> None:
        """Send an ``error=`` header and close, as ROS does for a bad peer."""
        log.warning("refusing TCPROS connection from %s: %s", self.peer, reason)
        self.write(encode_header({"error": reason}))
        self.close()

    def drop(self, reason: str) -> None:
        """Close the connection after logging why."""
        log.warning("dropping TCPROS connection from %s: %s", self.peer, reason)
        self.close()

    def close(self) -> None:
        """Close the transport."""
        if self.transport is not None:
            self.transport.close()

    def pause_writing(self) -> None:
        """Forward back-pressure to the handler."""
        if self.handler is not None:
            self.handler.pause_writing()

    def resume_writing(self) -> None:
        """Forward back-pressure relief to the handler."""
        if self.handler is not None:
            self.handler.resume_writing()

    def connection_lost(self, exc: Exception | None) -> None:
        """Tell the handler the peer is gone."""
        if self._watch is not None:
            self._watch.cancel()
        if self.handler is not None:
            self.handler.connection_lost()


class PublisherConnection(asyncio.BaseProtocol):
    """The base of every connection a subscription opens to a publisher.

    The subscription and the slave API read ``header`` (the publisher's
    connection header once accepted, else None), ``error`` (why the
    connection was dropped, or None) and ``bytes_received``, and call
    :meth:`close`.  Subclasses set the three attributes in ``__init__`` and
    are asyncio protocols (``asyncio.Protocol`` or ``asyncio.BufferedProtocol``
    first among their bases).
    """

    header: dict[str, str] | None
    error: str | None
    bytes_received: int
    transport: asyncio.BaseTransport | None

    def drop(self, reason: str) -> None:
        """Close the connection, remembering why."""
        self.error = reason
        log.warning("dropping connection to publisher: %s", reason)
        if self.transport is not None:
            self.transport.close()

    def close(self) -> None:
        """Close the connection without error."""
        if self.transport is not None:
            self.transport.close()


class SubscriberConnection(asyncio.Protocol, PublisherConnection):
    """A subscription's connection to one publisher.

    ``on_header`` validates the publisher's header and returns an error string
    or None; ``on_frames`` receives message payloads with the publisher header; ``on_lost`` is called
    once when the connection ends.  ``on_frame``, when given, takes the common
    case of a read holding exactly one frame (``on_frame(payload, header)``)
    and must behave like ``on_frames([payload], header)``.  ``busy_poll``, when
    given, hears of every read (see :mod:`rostui.core.node.busypoll`).
    """

    def __init__(
        self,
        request_header: dict[str, str],
        on_header: Callable[[dict[str, str]], str | None],
        on_frames: Callable[[list[bytes], dict[str, str]], None],
        on_lost: Callable[[str | None], None],
        on_frame: Callable[[bytes, dict[str, str]], None] | None = None,
        busy_poll: BusyPoll | None = None,
    ) -> None:
        self.request_header = request_header
        self.on_header = on_header
        self.on_frames = on_frames
        self.on_frame = on_frame if on_frame is not None else (lambda payload, header: on_frames([payload], header))
        self.on_lost = on_lost
        self.busy_poll = busy_poll
        self.reader = FrameReader(MAX_HEADER)
        self.header: dict[str, str] | None = None
        self.transport: asyncio.Transport | None = None
        self.error: str | None = None
        self.bytes_received = 0
        self.messages_received = 0
        self._watch: StallWatch | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        """Send our subscriber header."""
        self.transport = stream = cast(asyncio.Transport, transport)  # TCP: a stream transport
        set_nodelay(stream)
        self._watch = StallWatch(self.drop)
        self._watch.progress(1)
        stream.write(encode_header(self.request_header))

    def data_received(self, data: bytes) -> None:
        """Parse the publisher header, then message frames."""
        if self.busy_poll is not None:
            self.busy_poll.traffic()
        self.bytes_received += len(data)
        header = self.header
        if header is not None:
            # The usual case, one read holding one whole frame: nothing is buffered
            # and the stall watch is idle, so neither needs updating.
            payload = self.reader.whole_frame(data)
            if payload is not None:
                self.messages_received += 1
                self.on_frame(payload, header)
                return
        try:
            if self.header is None:
                frames = self.reader.feed(data, limit=1)
                if not frames:
                    return
                header = decode_header(frames[0])
                problem = header.get("error") or self.on_header(header)
                if problem:
                    raise TcprosError(problem)
                self.header = header
                self.reader.max_frame = max_frame_from_env()
                data = b""
            frames = self.reader.feed(data)
        except TcprosError as exc:
            self.drop(str(exc))
            return
        finally:
            if self._watch is not None:
                self._watch.progress(self.reader.pending)
        if frames:
            self.messages_received += len(frames)
            self.on_frames(frames, self.header)

    def connection_lost(self, exc: Exception | None) -> None:
        """Report the end of the connection once."""
        if self._watch is not None:
            self._watch.cancel()
        self.on_lost(self.error or (str(exc) if exc else None))
