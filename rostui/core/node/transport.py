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

    @property
    def is_shutdown(self) -> bool:
        """True once the node began shutting down (its topics and services are going away)."""

    def route_inbound(self, header: dict[str, str], conn: "InboundConnection") -> "InboundHandler | str":
        """Return a handler for the connection, or an error string to refuse it."""


#: Bytes a peer whose handler takes no frames (a subscriber) may send after its header before it is dropped.
MAX_UNEXPECTED_BYTES = 64 * 1024

#: Frames an InboundConnection hands its handler at a time; the rest wait, unparsed, in its reader.
FRAME_BATCH = 16


class InboundHandler(Protocol):
    """The per-connection logic that takes over after the header exchange."""

    @property
    def takes_frames(self) -> bool:
        """False when the peer has nothing to send after its header (a subscriber): its bytes are discarded
        and, past :data:`MAX_UNEXPECTED_BYTES`, the peer is dropped."""

    def frames_received(self, frames: list[bytes]) -> None:
        """Frames sent by the peer after its header (at most :data:`FRAME_BATCH` at a time).

        A handler that cannot keep up calls the connection's ``pause_reading``; no more frames come
        until it calls ``resume_reading``.
        """

    def connection_lost(self) -> None:
        """The peer went away or was dropped."""

    def pause_writing(self) -> None:
        """The transport's write buffer is full."""

    def resume_writing(self) -> None:
        """The transport's write buffer drained."""


class InboundConnection(asyncio.Protocol):
    """A connection accepted by a node's TCPROS server.

    Every byte the peer sends is bounded: its header by ``MAX_HEADER``; after
    the header, a handler that takes frames gets at most :data:`FRAME_BATCH`
    at a time and may pause reading (the rest stays unparsed, at most one read
    of the socket, and the kernel's buffers push back on the peer); a handler
    that takes none (a subscriber link) has the bytes discarded, and a peer
    that sends more than :data:`MAX_UNEXPECTED_BYTES` is dropped.
    """

    def __init__(self, router: ConnectionRouter) -> None:
        self.router = router
        self.transport: asyncio.Transport | None = None
        self.reader = FrameReader(MAX_HEADER)
        self.handler: InboundHandler | None = None
        self.peer: Any = None
        self.busy_poll = router.busy_poll
        self.reading_paused = False
        self.unexpected_bytes = 0
        self._discard = False
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
        if self._discard:
            self._unexpected(len(data))
            return
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
                if self._discard:
                    self._unexpected(self.reader.discard())
                    return
            self._pump(data)
        except TcprosError as exc:
            if self.handler is None:
                self.refuse(str(exc))
            else:
                self.drop(str(exc))
            return
        finally:
            if self._watch is not None:
                # While we hold the peer back, whatever waits in the reader is ours to take, not a stall.
                self._watch.progress(0 if self.reading_paused or self._discard else self.reader.pending)

    def _pump(self, data: bytes) -> None:
        """Hand complete frames to the handler in small batches until it pauses or none are left."""
        handler = self.handler
        assert handler is not None
        frames = self.reader.feed(data, limit=FRAME_BATCH)
        while frames:
            handler.frames_received(frames)
            if self.reading_paused or self._discard or len(frames) < FRAME_BATCH:
                return
            frames = self.reader.feed(b"", limit=FRAME_BATCH)

    def _unexpected(self, size: int) -> None:
        """Discard bytes a peer had no business sending; drop it once they add up."""
        self.unexpected_bytes += size
        if self.unexpected_bytes > MAX_UNEXPECTED_BYTES and self.transport is not None \
                and not self.transport.is_closing():
            self.drop(f"peer sent {self.unexpected_bytes} bytes after its header, where none are expected")

    def _read_header(self, data: bytes) -> bool:
        """Take the peer's header and route the connection; True once routed."""
        frames = self.reader.feed(data, limit=1)
        if not frames:
            return False
        routed = self.router.route_inbound(decode_header(frames[0]), self)
        if isinstance(routed, str):
            raise TcprosError(routed)
        self.handler = routed
        self._discard = self._discard or not routed.takes_frames
        self.reader.max_frame = max_frame_from_env()
        return self.transport is not None and not self.transport.is_closing()

    def pause_reading(self) -> None:
        """Stop reading from the peer until :meth:`resume_reading` (the handler is busy)."""
        if not self.reading_paused:
            self.reading_paused = True
            if self._watch is not None:
                self._watch.progress(0)
            if self.transport is not None and not self.transport.is_closing():
                self.transport.pause_reading()

    def resume_reading(self) -> None:
        """Hand over the frames that waited, then read from the peer again unless the handler paused anew."""
        if not self.reading_paused:
            return
        self.reading_paused = False
        transport = self.transport
        if transport is None or transport.is_closing():
            return
        try:
            self._pump(b"")
        except TcprosError as exc:
            self.drop(str(exc))
            return
        if not self.reading_paused and not transport.is_closing():
            if self._watch is not None:
                self._watch.progress(self.reader.pending)
            transport.resume_reading()

    def write(self, data: bytes) -> None:
        """Send bytes unless the connection is closing."""
        if self.transport is not None and not self.transport.is_closing():
            self.transport.write(data)

    def refuse(self, reason: str) -> None:
        """Send an ``error=`` header and close, as ROS does for a bad peer.

        A node shutting down says so only at debug level: peers that connect to a topic it has just closed
        (rosout, most often) are expected then, and are no one's mistake.
        """
        level = logging.DEBUG if self.router.is_shutdown else logging.WARNING
        log.log(level, "refusing TCPROS connection from %s: %s", self.peer, reason)
        self.write(encode_header({"error": reason}))
        self.close()

    def drop(self, reason: str) -> None:
        """Close the connection at once after logging why: what waits to be sent to the peer is discarded too."""
        log.warning("dropping TCPROS connection from %s: %s", self.peer, reason)
        self.close(abort=True)

    def close(self, abort: bool = False) -> None:
        """Close the transport (after sending what is buffered, unless ``abort``) and forget what the peer
        sent: anything still arriving is dropped unread."""
        self._discard = True
        self.reader.discard()
        if self.transport is not None:
            if abort:
                self.transport.abort()
            else:
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
        self.reader.discard()
        if self.handler is not None:
            self.handler.connection_lost()


class ReportedRefusal(str):
    """Why a subscriber refuses a publisher's header, when whoever refused it says so itself: the connection is
    dropped without a warning of its own (one line to the user, not two)."""


class PublisherConnection(asyncio.BaseProtocol):
    """The base of every connection a subscription opens to a publisher.

    The subscription and the slave API read ``header`` (the publisher's
    connection header once accepted, else None), ``error`` (why the
    connection was dropped, or None), ``refused`` (True when the subscriber
    itself refused the publisher's header: asking again would get the same
    header) and ``bytes_received``, and call :meth:`close`.  Subclasses set
    the attributes in ``__init__`` and are asyncio protocols
    (``asyncio.Protocol`` or ``asyncio.BufferedProtocol`` first among their
    bases).
    """

    header: dict[str, str] | None
    error: str | None
    refused: bool = False
    bytes_received: int
    transport: asyncio.BaseTransport | None

    def drop(self, reason: str) -> None:
        """Close the connection, remembering why (a :class:`ReportedRefusal` is logged at debug level only)."""
        self.error = str(reason)
        if isinstance(reason, ReportedRefusal):
            log.debug("refusing publisher: %s", reason)
        else:
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
                problem = header.get("error")
                if not problem:
                    problem = self.on_header(header)
                    if problem:
                        self.refused = True
                        self.drop(problem)
                        return
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
        self.reader.discard()  # a partial frame (up to the cap) goes back at once
        self.on_lost(self.error or (str(exc) if exc else None))
