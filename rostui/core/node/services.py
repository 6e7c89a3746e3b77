"""ROS services over rosrpc: servers inside a node, and client proxies.

Wire format: the client sends a header (callerid, service, md5sum, optional
persistent=1 or probe=1), the server answers with its header (callerid,
md5sum, request_type, response_type, type).  Each request is a length-prefixed
body; each response is an ok byte, a length, and the response body (ok=1) or
an error string (ok=0).
"""

from __future__ import annotations

import asyncio
import collections
import logging
from typing import Any, Callable, Protocol
from urllib.parse import urlparse

from rostui.core.localhost import connect_host
from rostui.core.node.transport import InboundConnection
from rostui.core.tcpros import LEN, MAX_HEADER, decode_header, encode_header, max_frame_from_env

log = logging.getLogger("rostui.services")


class ServiceException(Exception):
    """A service call failed: unavailable, refused, or the handler reported an error."""


Handler = Callable[[Any], Any]


class ServiceHost(Protocol):
    """What service servers and proxies need from their node (an AsyncNode is one)."""

    @property
    def name(self) -> str:
        """The node's name: the callerid in service headers."""

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        """The engine loop (threaded handlers run in its executor)."""

    async def lookup_service(self, name: str) -> str:
        """The rosrpc URI of a service, or ServiceException if none is registered."""


def make_response(srv_class: Any, result: Any) -> Any:
    """Turn what a handler returned into a response, as rospy accepts it.

    A response instance passes through; None is an error; a dict gives
    keyword fields; a tuple or list gives positional fields; any other single
    value fills a response with exactly one field.
    """
    resp_class = srv_class._response_class
    if isinstance(result, resp_class):
        return result
    if result is None:
        raise ServiceException("service handler returned None")
    if isinstance(result, dict):
        return resp_class(**result)
    if isinstance(result, (tuple, list)):
        return resp_class(*result)
    if len(resp_class.__slots__) == 1:
        return resp_class(result)
    raise ServiceException(f"service handler returned {type(result).__name__}, not {resp_class._type}")


class ServiceServer:
    """A service advertised by a node; answers rosrpc connections."""

    def __init__(self, node: ServiceHost, name: str, srv_class: Any, handler: Handler,
                 *, threaded: bool) -> None:
        self.node = node
        self.name = name
        self.srv_class = srv_class
        self.handler = handler
        self.threaded = threaded
        self.calls = 0
        self.header_fields: Callable[[], dict[str, str]] | None = None

    @property
    def type_name(self) -> str:
        """The service type, e.g. ``std_srvs/Empty``."""
        name: str = self.srv_class._type
        return name

    def reply_header(self) -> dict[str, str]:
        """The header this server sends to every client (``header_fields()`` when set, rospy's set for one)."""
        if self.header_fields is not None:
            return self.header_fields()
        return {
            "callerid": self.node.name,
            "md5sum": self.srv_class._md5sum,
            "request_type": self.srv_class._request_class._type,
            "response_type": self.srv_class._response_class._type,
            "type": self.srv_class._type,
        }

    def accept(self, header: dict[str, str], conn: InboundConnection) -> ServiceConnection | str:
        """Answer a client's header; return a connection handler or a refusal."""
        if header.get("probe") == "1":
            conn.write(encode_header(self.reply_header()))
            conn.close()
            return ServiceConnection(self, conn, persistent=False)
        md5 = header.get("md5sum")
        if md5 is None:
            return "header did not have required element: md5sum"
        if md5 not in ("*", self.srv_class._md5sum):
            return (f"request from [{header.get('callerid', '?')}]: md5sums do not match: "
                    f"[{md5}] vs. [{self.srv_class._md5sum}]")
        conn.write(encode_header(self.reply_header()))
        return ServiceConnection(self, conn, persistent=header.get("persistent") == "1", header=header)

    async def handle(self, body: bytes, header: dict[str, str] | None = None) -> bytes:
        """Run the handler on one request body; return the framed response.

        The request carries the client's connection *header* as ``_connection_header``.
        """
        try:
            request = self.srv_class._request_class.deserialize(body)
            request._connection_header = header or {}
            if self.threaded:
                result = await self.node.loop.run_in_executor(None, self.handler, request)
            else:
                result = self.handler(request)
                if asyncio.iscoroutine(result):
                    result = await result
            payload: bytes = make_response(self.srv_class, result).serialize()
            self.calls += 1
            return b"\x01" + LEN.pack(len(payload)) + payload
        except Exception as exc:
            text = str(exc) if isinstance(exc, ServiceException) else f"error processing request: {exc}"
            if not isinstance(exc, ServiceException):
                log.error("error processing request for service %s: %s", self.name, exc)
            data = text.encode()
            return b"\x00" + LEN.pack(len(data)) + data


#: Requests of one connection waiting for an answer before the connection stops reading from the client.
MAX_PENDING_REQUESTS = 32

#: Once paused, reading resumes when this few requests are left waiting.
RESUME_PENDING_REQUESTS = 8


class ServiceConnection:
    """One client connection to a ServiceServer; requests are answered in order.

    A client may pipeline requests on a persistent connection.  They wait in
    a short queue: past :data:`MAX_PENDING_REQUESTS` the connection stops
    reading until the worker has caught up, and the worker stops answering
    while the client does not read its answers (``pause_writing``), so a
    client that sends faster than it is served is held back by TCP instead
    of growing our memory.  Each connection has its own worker: others are
    served meanwhile.
    """

    takes_frames = True

    def __init__(self, server: ServiceServer, conn: InboundConnection, *, persistent: bool,
                 header: dict[str, str] | None = None) -> None:
        self.server = server
        self.header = header or {}
        self.conn = conn
        self.persistent = persistent
        self.pending: collections.deque[bytes] = collections.deque()
        self.task: asyncio.Task[None] | None = None
        self._arrived = asyncio.Event()
        self._writable = asyncio.Event()
        self._writable.set()

    def frames_received(self, frames: list[bytes]) -> None:
        """Queue requests for the worker; stop reading while too many wait."""
        self.pending.extend(frames)
        if len(self.pending) >= MAX_PENDING_REQUESTS:
            self.conn.pause_reading()
        if self.task is None:
            self.task = asyncio.get_running_loop().create_task(self._serve())
        else:
            self._arrived.set()

    async def _serve(self) -> None:
        arrived, writable, pending = self._arrived, self._writable, self.pending
        while True:
            while not pending:
                arrived.clear()
                await arrived.wait()
            response = await self.server.handle(pending.popleft(), self.header)
            await writable.wait()  # the client reads its answers before it gets more
            self.conn.write(response)
            if not self.persistent:
                self.pending.clear()
                self.conn.close()
                return
            if len(pending) <= RESUME_PENDING_REQUESTS:
                self.conn.resume_reading()

    def connection_lost(self) -> None:
        """Stop the worker and forget the requests that wait."""
        self.pending.clear()
        if self.task is not None:
            self.task.cancel()

    def pause_writing(self) -> None:
        """The client does not read its answers: answer no more until it does."""
        self._writable.clear()

    def resume_writing(self) -> None:
        """The client reads again."""
        self._writable.set()


def parse_rosrpc_uri(uri: str) -> tuple[str, int]:
    """Split ``rosrpc://host:port`` into host and port."""
    parsed = urlparse(uri)
    if parsed.scheme != "rosrpc" or not parsed.hostname or not parsed.port:
        raise ServiceException(f"invalid service URI [{uri}]")
    return parsed.hostname, parsed.port


async def read_header(reader: asyncio.StreamReader) -> dict[str, str]:
    """Read one connection header from a stream."""
    (size,) = LEN.unpack(await reader.readexactly(4))
    if size > MAX_HEADER:
        raise ServiceException(f"service header of {size} bytes is too large")
    return decode_header(await reader.readexactly(size))


def probe_header(callerid: str, service: str) -> dict[str, str]:
    """The header of a probe: asks a service server for its header and makes no call (rospy's wait_for_service)."""
    return {"probe": "1", "md5sum": "*", "callerid": callerid, "service": service}


async def probe_service(uri: str, service: str, callerid: str, timeout: float = 5.0) -> dict[str, str]:
    """Ask a service server for its header (type, md5sum) without calling it."""
    host, port = parse_rosrpc_uri(uri)
    reader, writer = await asyncio.wait_for(asyncio.open_connection(connect_host(host), port), timeout)
    try:
        writer.write(encode_header({"callerid": callerid, "service": service, "md5sum": "*", "probe": "1"}))
        header = await asyncio.wait_for(read_header(reader), timeout)
    finally:
        writer.close()
    if "error" in header:
        raise ServiceException(header["error"])
    return header


class ServiceProxy:
    """A client handle for one service; optionally keeps its connection open."""

    def __init__(self, node: ServiceHost, name: str, srv_class: Any, *, persistent: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        self.node = node
        self.name = name
        self.srv_class = srv_class
        self.persistent = persistent
        self.headers = headers or {}
        self._stream: tuple[asyncio.StreamReader, asyncio.StreamWriter] | None = None
        self._lock: asyncio.Lock | None = None
        self._reply_header: dict[str, str] = {}

    def build_request(self, *args: Any, **kwargs: Any) -> Any:
        """A request from a request instance, positional fields or keywords."""
        req_class = self.srv_class._request_class
        if len(args) == 1 and not kwargs and isinstance(args[0], req_class):
            return args[0]
        return req_class(*args, **kwargs)

    async def _open(self) -> tuple[asyncio.StreamReader, asyncio.StreamWriter]:
        uri = await self.node.lookup_service(self.name)
        host, port = parse_rosrpc_uri(uri)
        try:
            reader, writer = await asyncio.open_connection(connect_host(host), port)
        except OSError as exc:
            raise ServiceException(f"unable to connect to service [{self.name}]: {exc}") from exc
        header = {"callerid": self.node.name, "service": self.name, "md5sum": self.srv_class._md5sum,
                  "type": self.srv_class._type, **self.headers}
        if self.persistent:
            header["persistent"] = "1"
        writer.write(encode_header(header))
        try:
            reply = await read_header(reader)
        except (asyncio.IncompleteReadError, ConnectionError) as exc:
            writer.close()
            raise ServiceException(f"service [{self.name}] closed the connection during the header exchange") from exc
        if "error" in reply:
            writer.close()
            raise ServiceException(f"service [{self.name}] refused the call: {reply['error']}")
        self._reply_header = reply
        return reader, writer

    async def call(self, *args: Any, **kwargs: Any) -> Any:
        """Call the service; raise ServiceException on any failure."""
        request = self.build_request(*args, **kwargs)
        if self._lock is None:
            self._lock = asyncio.Lock()
        async with self._lock:
            stream = self._stream or await self._open()
            reply_header = self._reply_header
            reader, writer = stream
            try:
                payload = request.serialize()
                writer.write(LEN.pack(len(payload)) + payload)
                ok = (await reader.readexactly(1))[0]
                (size,) = LEN.unpack(await reader.readexactly(4))
                if size > max_frame_from_env():
                    raise ServiceException(f"service [{self.name}] sent a response of {size} bytes, over the cap")
                body = await reader.readexactly(size)
            except (asyncio.IncompleteReadError, ConnectionError) as exc:
                writer.close()
                self._stream = None
                raise ServiceException(f"service [{self.name}] closed the connection before responding") from exc
            if self.persistent and ok:
                self._stream = stream
            else:
                writer.close()
                self._stream = None
        if not ok:
            raise ServiceException(
                f"service [{self.name}] responded with an error: {body.decode(errors='replace')}")
        response = self.srv_class._response_class.deserialize(body)
        response._connection_header = reply_header
        return response

    async def close(self) -> None:
        """Close a persistent connection."""
        if self._stream is not None:
            self._stream[1].close()
            self._stream = None
