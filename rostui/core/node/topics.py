"""Topic publications and subscriptions of a node.

A `Publication` owns every outgoing connection of one topic: it serialises a
message once, frames it, and writes it to each subscriber; a latched topic
keeps its last frame for newcomers.  Publishing from a thread other than the
engine's queues the frame and wakes the loop once per batch.

A `Subscription` connects to every publisher the master lists, checks each
publisher header, deserialises frames and calls callbacks.  A callback may
come with a header check (:mod:`rostui.core.node.header_check`): it hears
only the publishers the check accepts, and a publisher no callback accepts
is refused and not asked again while it stays listed.  Publishers in the
same process are linked directly: message objects are handed over without
serialisation.  Both reach their node only through `TopicHost`.
"""

from __future__ import annotations

import asyncio
import collections
import logging
import os
import socket
import threading
from threading import get_ident
from typing import Any, Callable, Iterable, Iterator, Protocol, Sequence

from rostui.core.file_region import FileRegion
from rostui.core.localhost import connect_host
from rostui.core.node.anymsg import AnyMsg
from rostui.core.node.busypoll import BusyPoll
from rostui.core.node.header_check import HeaderCheck
from rostui.core.node.transport import (
    InboundConnection, PublisherConnection, ReportedRefusal, SubscriberConnection, set_nodelay,
)
from rostui.core.records import FrozenRecord
from rostui.core.tcpros import LEN, encode_header, max_backlog_from_env

log = logging.getLogger("rostui.topics")


class TopicType(FrozenRecord):
    """What a topic carries: type name, md5sum and message_definition (immutable).

    A record rather than a dataclass: :mod:`rostui.core.records` says why.
    """

    __slots__ = _fields = ("type", "md5sum", "definition")

    type: str
    md5sum: str
    definition: str

    def __init__(self, type: str, md5sum: str, definition: str) -> None:
        self._set(type, md5sum, definition)

    @classmethod
    def of(cls, msg_class: Any) -> "TopicType":
        """The TopicType of a generated message class."""
        return cls(msg_class._type, msg_class._md5sum, msg_class._full_text)


class TopicHost(Protocol):
    """What publications and subscriptions need from their node (an AsyncNode is one)."""

    @property
    def name(self) -> str:
        """The node's name: the callerid in connection headers."""

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        """The engine loop that runs the node's connections."""

    @property
    def loop_thread_id(self) -> int:
        """The thread id of the engine loop (publishing from it needs no hand-off)."""

    @property
    def busy_poll(self) -> BusyPoll | None:
        """The loop's busy poller, told of every read, if the node uses one."""

    def next_connection_id(self) -> int:
        """A fresh id for a connection (getBusInfo / getBusStats)."""

    async def request_topic(self, uri: str, topic: str) -> tuple[str, int]:
        """The TCPROS host and port a publisher's slave API (at ``uri``) offers for ``topic``."""

    def local_publication(self, uri: str, topic: str) -> Publication | None:
        """The publication of ``topic`` by a node of this process at ``uri``, for direct delivery."""


COALESCE_BYTES = 64 * 1024


def coalesce(frames: Iterable[bytes]) -> Iterator[tuple[bytes, int]]:
    """Group consecutive small frames into writes of about 64 KiB; big frames go alone.

    Yields ``(data, number_of_frames)``; a frame is never split.
    """
    group: list[bytes] = []
    size = 0
    for data in frames:
        if size + len(data) > COALESCE_BYTES and group:
            yield b"".join(group), len(group)
            group, size = [], 0
        group.append(data)
        size += len(data)
    if group:
        yield (group[0] if len(group) == 1 else b"".join(group)), len(group)


class OutgoingLink:
    """One subscriber's connection to a publication, with its own drop queue.

    Writes happen under the publication's lock: on the engine thread through
    the transport, or, from a user thread while the transport has nothing
    buffered, straight to the socket (no thread hand-off).  While the
    subscriber does not keep up, messages queue for it: at most
    ``queue_size`` of them, the oldest dropped, as in ROS.  A publication
    without a queue size drops no message, so its queue is bounded in bytes
    instead (``max_backlog``: ROSTUI_TCPROS_MAX_BACKLOG, 64 MiB by default):
    a subscriber that lets more pile up is dropped (it may connect again).
    """

    #: A subscriber sends nothing after its header: its connection discards stray bytes and drops a peer
    #: that keeps sending (InboundConnection).
    takes_frames = False

    def __init__(self, pub: "Publication", conn: InboundConnection, header: dict[str, str]) -> None:
        self.pub = pub
        self.conn = conn
        self.callerid = header.get("callerid", "")
        self.paused = False
        self.backlog: collections.deque[bytes] = collections.deque()
        self.backlog_bytes = 0
        self.max_backlog = max_backlog_from_env()
        self.gone = False
        self.messages_sent = 0
        self.bytes_sent = 0
        self.dropped = 0
        self.id = pub.node.next_connection_id()
        self.remainder_pending = False
        self._sock = _direct_socket(conn)

    def send(self, data: bytes | memoryview | FileRegion, count: int = 1) -> None:
        """Write framed bytes on the engine thread, or queue them while the peer is slow."""
        if not isinstance(data, bytes):
            self.send_frame(data)
            return
        if self.paused:
            self._queue(data)
            return
        self.conn.write(data)
        self.messages_sent += count
        self.bytes_sent += len(data)

    def send_frame(self, frame: bytes | memoryview | FileRegion) -> None:
        """A bag's message (engine thread), to the socket at once while nothing waits before it (a view of a
        chunk by ``send``, a file's region by ``sendfile``); what the socket does not take (all, when something
        waits) goes through the transport, a region's bytes read first; queued while the peer is slow."""
        if self.paused:
            self._queue(frame)
            return
        length = frame.length if isinstance(frame, FileRegion) else len(frame)  # (a region's len() is a Python call)
        sent = 0
        sock = self._sock
        if sock is not None and self.can_send_direct():
            try:
                sent = os.sendfile(sock.fileno(), frame.fd, frame.offset, length) if isinstance(frame, FileRegion) \
                    else sock.send(frame)
            except OSError:
                sent = 0  # a full socket, or a broken one (its transport sees that)
        if sent < length:
            self.conn.write(frame.read(sent) if isinstance(frame, FileRegion) else frame[sent:])
        self.messages_sent += 1
        self.bytes_sent += length

    def _queue(self, data: bytes | memoryview | FileRegion) -> None:
        """Keep a message for a subscriber that does not keep up: within the queue size, else the byte bound."""
        backlog = self.backlog
        if self.gone:
            return
        limit = self.pub.queue_limit
        if limit is not None:
            if len(backlog) >= limit:
                self.backlog_bytes -= len(backlog.popleft())
                self.dropped += 1
        elif backlog and self.backlog_bytes + len(data) > self.max_backlog:
            self.gone = True
            backlog.clear()
            self.backlog_bytes = 0
            self.conn.drop(f"subscriber [{self.callerid}] of {self.pub.topic} does not keep up: over "
                           f"{self.max_backlog} bytes queued for it")
            return
        if not isinstance(data, bytes):  # a view of a bag's chunk would keep it alive; a file's region is read
            data = bytes(data)
        backlog.append(data)
        self.backlog_bytes += len(data)

    def can_send_direct(self) -> bool:
        """True when a user thread may write to the socket itself (nothing queued anywhere)."""
        transport = self.conn.transport
        return (self._sock is not None and not self.paused and not self.remainder_pending
                and transport is not None and not transport.is_closing()
                and transport.get_write_buffer_size() == 0)

    def send_direct(self, data: bytes) -> None:
        """Write from a user thread; a part the socket does not take goes to the engine."""
        assert self._sock is not None
        try:
            sent = self._sock.send(data)
        except BlockingIOError:
            sent = 0
        except OSError:
            return  # the transport sees the broken connection and closes the link
        self.messages_sent += 1
        self.bytes_sent += len(data)
        if sent < len(data):
            self.remainder_pending = True
            self.pub.node.loop.call_soon_threadsafe(self._write_remainder, data[sent:])

    def _write_remainder(self, rest: bytes) -> None:
        with self.pub.lock:
            self.conn.write(rest)
            self.remainder_pending = False

    def frames_received(self, frames: list[bytes]) -> None:
        """Never called: a subscriber sends nothing after its header (see ``takes_frames``)."""

    def pause_writing(self) -> None:
        """Start queueing (bounded: see the class docstring)."""
        self.paused = True

    def resume_writing(self) -> None:
        """Flush what queued while paused."""
        with self.pub.lock:
            if self.gone:
                return
            self.paused = False
            while self.backlog and not self.paused:
                data = self.backlog.popleft()
                self.backlog_bytes -= len(data)
                self.send(data)

    def connection_lost(self) -> None:
        """Forget this subscriber."""
        self.pub.remove_link(self)
        if self._sock is not None:
            self._sock.close()
            self._sock = None


def _direct_socket(conn: InboundConnection) -> socket.socket | None:
    """A second handle on the connection's socket for writes from user threads."""
    transport = conn.transport
    raw = transport.get_extra_info("socket") if transport is not None else None
    if raw is None:
        return None
    try:
        return socket.socket(fileno=os.dup(raw.fileno()))
    except OSError:
        return None


class PeerListener(Protocol):
    """Told when a subscriber connects to or leaves a :class:`Publication` (rospy's SubscribeListener)."""

    def peer_added(self, pub: "Publication", link: OutgoingLink) -> None:
        """A remote subscriber connected (engine thread; *link* already receives what is published)."""

    def peer_removed(self, pub: "Publication", remaining: int) -> None:
        """A remote subscriber left; *remaining* remote subscribers are still connected (engine thread)."""


class Publication:
    """Every publisher handle of one topic in one node shares this object.

    ``extra_header`` fields go into the header sent to every subscriber;
    ``peer_listeners`` hear of subscribers coming and going; with
    ``seq_when_connected`` a Header's ``seq`` counts from 1 and only messages
    sent while a subscriber is connected, as rospy numbers them (otherwise
    from 0, every message).
    """

    def __init__(
        self, node: TopicHost, topic: str, topic_type: TopicType, *,
        queue_size: int | None, latch: bool, tcp_nodelay: bool,
    ) -> None:
        self.node = node
        self.topic = topic
        self.topic_type = topic_type
        self.latch = latch
        self.tcp_nodelay = tcp_nodelay
        self.queue_limit = queue_size if queue_size and queue_size > 0 else None
        self.links: tuple[OutgoingLink, ...] = ()
        self.local: tuple["Subscription", ...] = ()
        self.latched_frame: bytes | None = None
        self.latched_msg: Any = None
        self.handles = 0
        self.messages_published = 0
        self.seq = 0
        self.extra_header: dict[str, str] = {}
        self.peer_listeners: list[PeerListener] = []
        self.seq_when_connected = False
        self._pending: collections.deque[tuple[bytes, Any]] = collections.deque(maxlen=self.queue_limit)
        self._flush_scheduled = False
        self.lock = threading.Lock()

    # -- connections ---------------------------------------------------------
    def accept(self, header: dict[str, str], conn: InboundConnection) -> OutgoingLink | str:
        """Answer a subscriber's header; return the link or a refusal reason."""
        md5 = header.get("md5sum")
        if md5 is None:
            return "header did not have required element: md5sum"
        ours = self.topic_type.md5sum
        if md5 not in ("*", ours) and ours != "*":
            return (f"Client [{header.get('callerid', '?')}] wants topic {self.topic} to have datatype/md5sum "
                    f"[{header.get('type', '?')}/{md5}], but our version has [{self.topic_type.type}/{ours}]. "
                    "Dropping connection.")
        link = OutgoingLink(self, conn, header)
        if self.tcp_nodelay or header.get("tcp_nodelay") == "1":
            if conn.transport is not None:
                set_nodelay(conn.transport)
        reply = {
            "callerid": self.node.name,
            "md5sum": ours,
            "type": self.topic_type.type,
            "message_definition": self.topic_type.definition,
            "latching": "1" if self.latch else "0",
            "topic": self.topic,
            **self.extra_header,
        }
        conn.write(encode_header(reply))
        listeners = list(self.peer_listeners)
        with self.lock:
            self.links = self.links + (link,)
            if not listeners:
                self._send_latched(link)
                return link
        for listener in listeners:
            self._tell(listener.peer_added, link)
        with self.lock:
            if link in self.links:
                self._send_latched(link)
        return link

    def _send_latched(self, link: OutgoingLink) -> None:
        """Give a new subscriber the last message of a latched topic (under the lock)."""
        if self.latch and self.latched_frame is not None:
            link.send(self.latched_frame)

    def remove_link(self, link: OutgoingLink) -> None:
        """Drop a subscriber connection."""
        before = len(self.links)
        self.links = tuple(x for x in self.links if x is not link)
        if len(self.links) < before:
            for listener in list(self.peer_listeners):
                self._tell(listener.peer_removed, len(self.links))

    def _tell(self, hook: Callable[..., None], arg: Any) -> None:
        try:
            hook(self, arg)
        except Exception:  # a user's listener must not cost the connection
            log.exception("error in subscriber listener of %s", self.topic)

    def publish_to(self, link: OutgoingLink, msg: Any) -> None:
        """Send *msg* to one subscriber only (any thread), numbered like :meth:`publish`.

        On a latched topic it becomes the latched message, as in rospy.
        """
        self._number(msg)
        payload = msg.serialize() if not isinstance(msg, AnyMsg) else msg._buff
        data = LEN.pack(len(payload)) + payload
        if self.latch:
            with self.lock:
                self.latched_frame, self.latched_msg = data, msg
        if get_ident() == self.node.loop_thread_id:
            self._send_one(link, data)
        else:
            self.node.loop.call_soon_threadsafe(self._send_one, link, data)

    def _send_one(self, link: OutgoingLink, data: bytes) -> None:
        with self.lock:
            if link in self.links:
                link.send(data)

    def _number(self, msg: Any) -> None:
        """Give a message with a Header the next sequence number."""
        if not msg._has_header:
            return
        with self.lock:
            if not self.seq_when_connected:
                msg.header.seq = self.seq
                self.seq += 1
            elif self.links or self.local:
                self.seq += 1
                msg.header.seq = self.seq

    def add_local(self, sub: "Subscription") -> None:
        """Link a subscription of this process for direct delivery."""
        if sub not in self.local:
            self.local = self.local + (sub,)
            if self.latch and self.latched_msg is not None:
                sub.deliver_local(self.latched_msg, self)

    def remove_local(self, sub: "Subscription") -> None:
        """Unlink a same-process subscription."""
        self.local = tuple(x for x in self.local if x is not sub)

    @property
    def num_subscribers(self) -> int:
        """Connected subscribers, remote and in-process."""
        return len(self.links) + len(self.local)

    def subscriber_names(self) -> set[str]:
        """Node names (callerids) of the connected subscribers, remote and in-process."""
        return {link.callerid for link in self.links} | {sub.node.name for sub in self.local}

    # -- publishing -----------------------------------------------------------
    def publish(self, msg: Any) -> None:
        """Serialise once and send to every subscriber (any thread).

        Messages with a Header get the next sequence number, as rospy does.
        """
        self._number(msg)
        payload = msg.serialize() if not isinstance(msg, AnyMsg) else msg._buff
        data = LEN.pack(len(payload)) + payload
        if get_ident() == self.node.loop_thread_id:
            with self.lock:
                for link in self.links:
                    link.send(data)
                self.messages_published += 1
                if self.latch:
                    self.latched_frame = data
                    self.latched_msg = msg
            if self.local:
                self._deliver_local((msg,))
            return
        with self.lock:
            if not self._flush_scheduled and not self.local and self._all_direct():
                for link in self.links:
                    link.send_direct(data)
                self.messages_published += 1
                if self.latch:
                    self.latched_frame = data
                    self.latched_msg = msg
                return
            self._pending.append((data, msg))
            if self._flush_scheduled:
                return
            self._flush_scheduled = True
        self.node.loop.call_soon_threadsafe(self._flush)

    def publish_serialized(self, payload: bytes) -> None:
        """Send a message already in wire form (a bag's bytes) to every subscriber, as :meth:`publish` would.

        On the engine thread, with no same-process subscriber and no latching, the bytes go out with no message
        object made for them (a bag player's path, once per message); otherwise this is :meth:`publish`.
        """
        if self.local or self.latch or get_ident() != self.node.loop_thread_id:
            self.publish(AnyMsg(payload))
            return
        data = LEN.pack(len(payload)) + payload
        with self.lock:
            for link in self.links:
                link.send(data)
            self.messages_published += 1

    def publish_frame(self, frame: bytes | memoryview | FileRegion) -> None:
        """Send a message already framed as TCPROS sends it (its 4-byte length, then its bytes: a view of a bag's
        chunk, or the region of the file that holds them) to every subscriber, as :meth:`publish` would.

        On the engine thread, with no same-process subscriber and no latching, the frame goes out as it is;
        otherwise this is :meth:`publish` of a copy of its bytes.
        """
        if self.local or self.latch or get_ident() != self.node.loop_thread_id:
            self.publish(AnyMsg(frame.read(4) if isinstance(frame, FileRegion) else bytes(frame[4:])))
            return
        with self.lock:
            for link in self.links:
                link.send_frame(frame)
            self.messages_published += 1

    def frame_sender(self) -> Callable[[bytes | memoryview | FileRegion], None]:
        """A call that sends frames as :meth:`publish_frame` does, on the engine thread only, with a shorter path
        for a file's region to one subscriber (:class:`FrameSender`)."""
        return FrameSender(self).send

    def _flush(self) -> None:
        """Engine side of publishes from user threads that could not go direct."""
        with self.lock:
            batch = list(self._pending)
            self._pending.clear()
            self._flush_scheduled = False
            if not batch:
                return
            if self.links:
                for chunk, count in coalesce(item[0] for item in batch):
                    for link in self.links:
                        link.send(chunk, count)
            self._remember(batch[-1][0], batch[-1][1], len(batch))
        self._deliver_local([msg for _, msg in batch])

    def _all_direct(self) -> bool:
        """True when a user thread may write to every subscriber's socket itself."""
        for link in self.links:
            if not link.can_send_direct():
                return False
        return True

    def _remember(self, data: bytes, msg: Any, count: int) -> None:
        """Count what was sent and keep the last message of a latched topic."""
        self.messages_published += count
        if self.latch:
            self.latched_frame = data
            self.latched_msg = msg

    def _deliver_local(self, msgs: Sequence[Any]) -> None:
        """Hand messages to same-process subscribers (engine thread, outside the lock)."""
        for sub in self.local:
            for msg in msgs:
                sub.deliver_local(msg, self)

    def close(self) -> None:
        """Close every subscriber connection."""
        for link in self.links:
            link.conn.close()
        self.links = ()
        for sub in self.local:
            sub.publication_gone(self)
        self.local = ()


Callback = Callable[..., Any]
#: One registered callback: the callable, its extra argument, and the check deciding which publishers it hears.
Registration = tuple[Callback, Any, "HeaderCheck | None"]


def _unbound_send(data: bytes | memoryview) -> int:
    raise RuntimeError("a frame sender sent with no subscriber bound")


class FrameSender:
    """Sends a bag player's frames as :meth:`Publication.publish_frame` does, on the engine thread.

    While the publication has exactly one subscriber and no same-process one, is not latched, and the link and
    its transport have nothing waiting, a frame goes to the subscriber's socket here (a file's region by
    ``sendfile``, a view of a chunk by ``send``), without the publication's and the link's general checks a
    message; what the socket does not take goes to the transport, as the link does it, and any other frame
    goes the publication's way.  A player sleeps before each message, so each call runs
    with cold caches: the calls and checks left out were about 5% of a quiet play's CPU (bench/README.md,
    "Bag play CPU", fifteenth pass).  The publication's links are a tuple it replaces when they change: one
    identity test a message sees a subscriber come or go.
    """

    __slots__ = ("_pub", "_links", "_link", "_transport", "_fd", "_send")

    def __init__(self, pub: Publication) -> None:
        self._pub = pub
        self._links: tuple[OutgoingLink, ...] | None = None
        self._link: OutgoingLink | None = None
        self._transport: asyncio.Transport | None = None
        self._fd = -1
        self._send: Callable[[bytes | memoryview], int] = _unbound_send

    def _bind(self, links: tuple[OutgoingLink, ...]) -> None:
        """Take the publication's links as they are now: the one link a frame can go to straight, or none."""
        self._links = links
        self._link = None
        if len(links) != 1 or self._pub.latch:
            return
        link = links[0]
        transport = link.conn.transport
        if link._sock is None or transport is None:
            return
        self._link, self._transport, self._fd, self._send = link, transport, link._sock.fileno(), link._sock.send

    def send(self, frame: bytes | memoryview | FileRegion) -> None:
        """Send one framed message to every subscriber (engine thread)."""
        pub = self._pub
        if pub.links is not self._links:
            self._bind(pub.links)
        link = self._link
        transport = self._transport
        if (link is None or pub.local or link.paused or link.remainder_pending or transport is None
                or transport.is_closing() or transport.get_write_buffer_size()):
            pub.publish_frame(frame)
            return
        length = frame.length if isinstance(frame, FileRegion) else len(frame)
        with pub.lock:  # OutgoingLink.send_frame's write, written out here: a call less a message
            try:
                sent = os.sendfile(self._fd, frame.fd, frame.offset, length) if isinstance(frame, FileRegion) \
                    else self._send(frame)
            except OSError:
                sent = 0  # a full socket, or a broken one (its transport sees that)
            if sent < length:
                link.conn.write(frame.read(sent) if isinstance(frame, FileRegion) else frame[sent:])
            link.messages_sent += 1
            link.bytes_sent += length
            pub.messages_published += 1


class _Gate:
    """One publisher's verdicts for a subscription: which registered callbacks hear it.

    Each check is asked once per gate (a connection, or a same-process
    publisher), when the header comes or when a callback is registered later.
    """

    __slots__ = ("sub", "header", "verdicts", "seen", "heard_by")

    def __init__(self, sub: "Subscription", header: dict[str, str] | None = None) -> None:
        self.sub = sub
        self.header = header
        self.verdicts: dict[HeaderCheck, str | None] = {}
        self.seen: tuple[Registration, ...] | None = None
        self.heard_by: tuple[tuple[Callback, Any], ...] = ()

    def refusal(self, header: dict[str, str]) -> ReportedRefusal | None:
        """Why no registered callback hears this publisher (its header), or None when one does (or none checks).

        The checks that refused it say so themselves (a check reports its refusals, see
        :class:`~rostui.core.node.header_check.RefusalLog`), so the connection drops it quietly.
        """
        self.header = header
        targets = self.targets()
        if targets or not self.sub.callbacks:
            return None
        reasons = (self.verdict(check) for _cb, _args, check in self.sub.callbacks if check is not None)
        return ReportedRefusal("; ".join(dict.fromkeys(why for why in reasons if why is not None)))

    def verdict(self, check: HeaderCheck) -> str | None:
        """What ``check`` says of the header (asked once)."""
        try:
            return self.verdicts[check]
        except KeyError:
            why = self.verdicts[check] = check(self.header or {})
            return why

    def targets(self) -> tuple[tuple[Callback, Any], ...]:
        """The callbacks (and their arguments) that hear this publisher now."""
        registered = self.sub.callbacks
        if registered is not self.seen:
            self.seen = registered
            self.heard_by = tuple((cb, args) for cb, args, check in registered
                                  if check is None or self.verdict(check) is None)
        return self.heard_by


class Subscription:
    """Every subscriber handle of one topic in one node shares this object.

    A subclass may open its own kind of connection to each publisher by
    overriding :meth:`publisher_connection`; :meth:`AsyncNode.add_subscription
    <rostui.core.node.node.AsyncNode.add_subscription>` registers such a
    subscription.
    """

    def __init__(self, node: TopicHost, topic: str, msg_class: Any, *, queue_size: int | None,
                 tcp_nodelay: bool) -> None:
        self.node = node
        self.topic = topic
        self.msg_class = msg_class
        self.raw = msg_class is AnyMsg
        self.queue_size = queue_size
        self.tcp_nodelay = tcp_nodelay
        self.callbacks: tuple[Registration, ...] = ()
        self.connections: dict[str, PublisherConnection | None] = {}
        self.refused: dict[str, str] = {}
        """Publishers (URI: why) whose header no callback accepted; not asked again while listed."""
        self.local_pubs: dict[str, Publication] = {}
        self._local_gates: dict[Publication, _Gate] = {}
        self.publisher_uris: list[str] = []
        self.handles = 0
        self.closed = False
        self.messages_received = 0
        self._retry: dict[str, asyncio.Task[None]] = {}

    @property
    def type_name(self) -> str:
        """The type registered with the master (``*`` for raw subscribers)."""
        name: str = self.msg_class._type
        return name

    def add_callback(self, cb: Callback, args: Any = None, check: HeaderCheck | None = None) -> None:
        """Register a callback ``cb(msg)`` or ``cb(msg, args)``; with ``check``, it hears only the publishers whose
        connection header ``check`` accepts (:mod:`rostui.core.node.header_check`).

        Publishers refused so far are asked again: the new callback may hear them.
        """
        self.callbacks = self.callbacks + ((cb, args, check),)
        if self.refused:
            self._ask_refused_again()

    def remove_callback(self, cb: Callback, args: Any = None) -> None:
        """Remove one registration of a callback."""
        items = list(self.callbacks)
        for i, item in enumerate(items):
            if item[0] is cb and item[1] is args:
                del items[i]
                break
        self.callbacks = tuple(items)

    def _ask_refused_again(self) -> None:
        for uri in list(self.refused):
            del self.refused[uri]
            if self.connections.get(uri, False) is None and uri not in self._retry and not self.closed:
                self._retry[uri] = self.node.loop.create_task(self._connect_loop(uri))

    def _dispatch(self, msg: Any, targets: Iterable[tuple[Callback, Any]]) -> None:
        self.messages_received += 1
        for cb, args in targets:
            try:
                result = cb(msg) if args is None else cb(msg, args)
                if result is not None and asyncio.iscoroutine(result):
                    self.node.loop.create_task(result)
            except Exception:  # a user callback must not kill the connection
                log.exception("error in subscriber callback for %s", self.topic)

    def deliver_local(self, msg: Any, pub: Publication) -> None:
        """A same-process publisher hands over a message object (to the callbacks whose checks accept it)."""
        gate = self._local_gates.get(pub)
        if gate is None:
            gate = self._local_gates[pub] = _Gate(self, {
                "type": pub.topic_type.type, "md5sum": pub.topic_type.md5sum,
                "message_definition": pub.topic_type.definition, "callerid": pub.node.name,
                "latching": "1" if pub.latch else "0"})
        targets = gate.targets()
        if not targets and self.callbacks:
            return
        if self.raw and not isinstance(msg, AnyMsg):
            raw = AnyMsg(msg.serialize())
            raw._connection_header = gate.header
            msg = raw
        self._dispatch(msg, targets)

    def publication_gone(self, pub: Publication) -> None:
        """A same-process publisher closed."""
        for uri, p in list(self.local_pubs.items()):
            if p is pub:
                del self.local_pubs[uri]
        self._local_gates.pop(pub, None)

    # -- connection management --------------------------------------------------
    def update_publishers(self, uris: list[str]) -> None:
        """Connect to new publishers and drop those no longer listed."""
        if self.closed:
            return
        self.publisher_uris = list(uris)
        wanted = set(uris)
        for uri in list(self.connections):
            if uri not in wanted:
                conn = self.connections.pop(uri)
                self.refused.pop(uri, None)
                if conn is not None:
                    conn.close()
                task = self._retry.pop(uri, None)
                if task:
                    task.cancel()
        for uri in list(self.local_pubs):
            if uri not in wanted:
                gone = self.local_pubs.pop(uri)
                gone.remove_local(self)
                self._local_gates.pop(gone, None)
        for uri in uris:
            if uri in self.connections or uri in self.local_pubs:
                continue
            local = self.node.local_publication(uri, self.topic)
            if local is not None:
                if self._types_match(local.topic_type.md5sum):
                    self.local_pubs[uri] = local
                    local.add_local(self)
                continue
            self.connections[uri] = None
            self._retry[uri] = self.node.loop.create_task(self._connect_loop(uri))

    def rejoin(self, uris: list[str]) -> None:
        """After registering with a new master: connect to the publishers it lists, keep the live connections.

        A new master may not know yet of publishers that are alive and
        connected (they register again by themselves, if they can); dropping
        them would lose messages for nothing.  Publishers not connected now
        and not listed are forgotten.
        """
        live = [uri for uri, conn in self.connections.items() if conn is not None and conn.header is not None]
        self.update_publishers(list(dict.fromkeys([*uris, *live, *self.local_pubs])))

    def publisher_names(self) -> set[str]:
        """Node names (callerids) of the connected publishers, remote and in-process."""
        remote = {str(conn.header.get("callerid", "")) for conn in self.connections.values()
                  if conn is not None and conn.header is not None}
        return remote | {pub.node.name for pub in self.local_pubs.values()}

    def _types_match(self, md5: str) -> bool:
        ours = self.msg_class._md5sum
        return ours == "*" or md5 == "*" or ours == md5

    async def _connect_loop(self, uri: str) -> None:
        """Connect to a publisher; retry while it is still listed."""
        delay = 0.1
        try:
            while not self.closed and uri in self.connections:
                lost = await self._connect_once(uri)
                if lost is None or self.closed or uri not in self.connections:
                    return
                await asyncio.sleep(delay)
                delay = min(delay * 2, 2.0)
        except asyncio.CancelledError:
            pass
        finally:
            if self._retry.get(uri) is asyncio.current_task():
                self._retry.pop(uri, None)

    async def _connect_once(self, uri: str) -> str | None:
        """One connection attempt; returns an error string to retry, None to stop."""
        try:
            host, port = await self.node.request_topic(uri, self.topic)
        except Exception as exc:  # publisher gone or refusing: retry while listed
            return str(exc)
        done: asyncio.Future[str | None] = self.node.loop.create_future()

        def on_lost(reason: str | None) -> None:
            if self.connections.get(uri) is proto:
                self.connections[uri] = None
            if not done.done():
                done.set_result(reason or "connection closed")

        proto = self.publisher_connection(on_lost)
        try:
            await self.node.loop.create_connection(lambda: proto, connect_host(host), port)
        except OSError as exc:
            return str(exc)
        if uri not in self.connections or self.closed:
            proto.close()
            return None
        self.connections[uri] = proto
        reason = await done
        if proto.refused:  # its header again would be refused again
            self.refused[uri] = proto.error or "refused"
            return None
        if proto.error and "md5" in proto.error.lower():
            return None
        return reason

    def publisher_connection(self, on_lost: Callable[[str | None], None]) -> PublisherConnection:
        """A new connection to one publisher; it must call ``on_lost(reason)`` once when it ends.

        By default a :class:`SubscriberConnection` that decodes each frame
        and hands it to the callbacks.  A subclass may return its own kind of
        :class:`PublisherConnection`; it should send :meth:`request_header`,
        refuse a publisher that :meth:`check_header` objects to, and count
        the messages it takes in ``messages_received``.
        """
        gate = _Gate(self)

        def on_header(header: dict[str, str]) -> str | None:
            return self.check_header(header) or gate.refusal(header)

        return SubscriberConnection(self.request_header(), on_header, self._frames_handler(gate), on_lost,
                                    self._frame_handler(gate), busy_poll=self.node.busy_poll)

    def request_header(self) -> dict[str, str]:
        """The connection header this subscription sends to a publisher."""
        header = {
            "callerid": self.node.name,
            "topic": self.topic,
            "md5sum": self.msg_class._md5sum,
            "type": self.msg_class._type,
            "tcp_nodelay": "1" if self.tcp_nodelay else "0",
        }
        if not self.raw:
            header["message_definition"] = self.msg_class._full_text
        return header

    def check_header(self, header: dict[str, str]) -> str | None:
        """Why a publisher's connection header is unacceptable (missing fields, other md5sum), or None."""
        missing = [k for k in ("md5sum", "type") if k not in header]
        if missing:
            return f"Publisher header did not have required element: {missing[0]}"
        if not self._types_match(header["md5sum"]):
            return (f"md5sum mismatch on {self.topic}: publisher has [{header['type']}/{header['md5sum']}], "
                    f"we want [{self.msg_class._type}/{self.msg_class._md5sum}]")
        return None

    def _frames_handler(self, gate: _Gate | None = None) -> Callable[[list[bytes], dict[str, str]], None]:
        """The per-connection frame callback; with a queue_size, only the newest frames of a backlog run.

        Messages go to the callbacks ``gate`` (the connection's verdicts) lets hear them.
        """
        dispatch = self._dispatch
        keep = self.queue_size if self.queue_size and self.queue_size > 0 else None
        the_gate = gate if gate is not None else _Gate(self)
        if self.raw:
            def on_raw(frames: list[bytes], header: dict[str, str]) -> None:
                if keep is not None and len(frames) > keep:
                    frames = frames[-keep:]
                if the_gate.header is None:
                    the_gate.header = header
                targets = the_gate.targets()
                for data in frames:
                    msg = AnyMsg(data)
                    msg._connection_header = header
                    dispatch(msg, targets)
            return on_raw
        on_frame = self._frame_handler(the_gate)

        def on_frames(frames: list[bytes], header: dict[str, str]) -> None:
            if keep is not None and len(frames) > keep:
                frames = frames[-keep:]
            for data in frames:
                on_frame(data, header)
        return on_frames

    def _frame_handler(self, gate: _Gate | None = None) -> Callable[[bytes, dict[str, str]], None]:
        """Decode one frame and dispatch it (also the callback for a read that holds exactly one frame)."""
        the_gate = gate if gate is not None else _Gate(self)
        if self.raw:
            frames_handler = self._frames_handler(the_gate)
            return lambda payload, header: frames_handler([payload], header)
        deserialize = self.msg_class.deserialize
        dispatch = self._dispatch
        topic = self.topic

        def on_frame(data: bytes, header: dict[str, str]) -> None:
            try:
                msg = deserialize(data)
            except Exception as exc:
                log.warning("dropping undecodable message on %s: %s", topic, exc)
                return
            msg._connection_header = header
            if the_gate.header is None:
                the_gate.header = header
            dispatch(msg, the_gate.targets())
        return on_frame

    def close(self) -> None:
        """Disconnect from every publisher."""
        self.closed = True
        for task in self._retry.values():
            task.cancel()
        self._retry.clear()
        for conn in self.connections.values():
            if conn is not None:
                conn.close()
        self.connections.clear()
        for pub in self.local_pubs.values():
            pub.remove_local(self)
        self.local_pubs.clear()
        self._local_gates.clear()
        self.refused.clear()
