"""An asyncio XML-RPC server: HTTP/1.1 keep-alive, Content-Length framing.

Each connection is served by its own task, so a slow or stalled client never
holds up another.  A connection may wait ``idle_timeout`` seconds for a request
to begin (its first, or the next on a keep-alive connection); a request must
then arrive completely within ``request_timeout`` seconds of its first byte.
At most ``max_connections`` are served at once: one more closes the connection
idle longest, else the oldest unfinished request (see :mod:`.limits`).  A
client that sends garbage, an oversized body, malformed XML or a DTD gets an
HTTP error or an XML-RPC fault and loses its connection, never the server.

Faults follow Python's SimpleXMLRPCServer, which rosmaster and rospy use:
code 1 and the string ``"<class 'X'>:message"``.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import sys
import zlib
from collections.abc import Awaitable
from typing import Any, AsyncIterator, Callable
from xml.parsers.expat import ExpatError

from .limits import idle_timeout_from_env, listen_backlog, max_connections_from_env, request_timeout_from_env
from .marshal import EncodedResponse, Fault, decode_call, encode_fault, encode_response, exception_fault_string
from .safexml import UnsafeXmlError

__all__ = ["XmlRpcServer", "DEFAULT_MAX_BODY"]

_log = logging.getLogger("rostui.xmlrpc.server")

#: Largest request body accepted by default (64 MiB).
DEFAULT_MAX_BODY = 64 * 1024 * 1024
_MAX_HEADER = 64 * 1024

_REASONS = {
    200: "OK", 400: "Bad Request", 404: "Not Found", 408: "Request Timeout",
    411: "Length Required", 413: "Content Too Large", 415: "Unsupported Media Type",
    431: "Request Header Fields Too Large", 501: "Not Implemented", 503: "Service Unavailable",
    505: "HTTP Version Not Supported",
}

if sys.version_info >= (3, 11):
    _timeout = asyncio.timeout
else:  # pragma: no cover - Python 3.10
    @contextlib.asynccontextmanager
    async def _timeout(delay: float | None) -> AsyncIterator[None]:
        task = asyncio.current_task()
        loop = asyncio.get_running_loop()
        handle = loop.call_later(delay, task.cancel) if delay is not None and task else None
        try:
            yield
        except asyncio.CancelledError as exc:
            raise TimeoutError from exc
        finally:
            if handle is not None:
                handle.cancel()


class _HttpError(Exception):
    """An HTTP-level error: answer ``status`` and close the connection."""

    def __init__(self, status: int, detail: str) -> None:
        super().__init__(detail)
        self.status = status


def _fault_string(exc: BaseException) -> str:
    return exception_fault_string(exc)


class _Conn:
    """One accepted connection, as the connection cap sees it."""

    __slots__ = ("transport", "open")

    def __init__(self, transport: asyncio.WriteTransport) -> None:
        self.transport = transport
        self.open = True


class XmlRpcServer:
    """Serve the public methods of ``handler`` over XML-RPC.

    Methods are looked up by name on ``handler``; names starting with ``_``
    are never exposed.  A method may be a plain function or ``async def``.
    ``system.multicall`` is answered by the server itself, as Python's
    SimpleXMLRPCServer does for rosmaster and rospy.

    ``host`` is the interface to bind; ``advertise_host`` (default: ``host``)
    is the host name put in :attr:`uri`.  ``request_timeout``,
    ``idle_timeout`` and ``max_connections`` default to the environment's
    (:mod:`rostui.core.xmlrpc.limits`).
    """

    def __init__(
        self,
        handler: object,
        host: str,
        port: int = 0,
        *,
        advertise_host: str | None = None,
        max_body: int = DEFAULT_MAX_BODY,
        request_timeout: float | None = None,
        idle_timeout: float | None = None,
        max_connections: int | None = None,
    ) -> None:
        self.handler = handler
        self.host = host
        self.advertise_host = advertise_host or host
        self.max_body = max_body
        self.request_timeout = request_timeout_from_env() if request_timeout is None else request_timeout
        self.idle_timeout = idle_timeout_from_env() if idle_timeout is None else idle_timeout
        self.max_connections = max_connections_from_env() if max_connections is None else max_connections
        self._requested_port = port
        self._port: int | None = None
        self._server: asyncio.AbstractServer | None = None
        self._connections: set[asyncio.Task[None]] = set()
        self._open = 0  # connections counted against max_connections
        # Connections waiting for a request, and those reading one, oldest first.
        self._idle: dict[_Conn, None] = {}
        self._reading: dict[_Conn, None] = {}
        self._warned_full = False
        self._methods: dict[str, Callable[..., Any] | None] = {}

    # -- lifecycle ---------------------------------------------------------

    async def start(self) -> None:
        """Bind and start accepting connections (raises ``OSError`` if the port is taken)."""
        self._server = await asyncio.start_server(
            self._on_connection, self.host, self._requested_port,
            limit=_MAX_HEADER, reuse_address=True, backlog=listen_backlog(),
        )
        self._port = self._server.sockets[0].getsockname()[1]

    @property
    def port(self) -> int:
        """The TCP port the server listens on (valid after :meth:`start`)."""
        if self._port is None:
            raise RuntimeError("XmlRpcServer not started")
        return self._port

    @property
    def uri(self) -> str:
        """``http://<advertise_host>:<port>/`` (valid after :meth:`start`)."""
        host = self.advertise_host
        if ":" in host and not host.startswith("["):
            host = f"[{host}]"
        return f"http://{host}:{self.port}/"

    async def close(self) -> None:
        """Stop listening and drop every open connection."""
        if self._server is not None:
            self._server.close()
        tasks = list(self._connections)
        for task in tasks:
            task.cancel()
        if tasks:
            await asyncio.gather(*tasks, return_exceptions=True)
        if self._server is not None:
            with contextlib.suppress(Exception):
                await self._server.wait_closed()
            self._server = None

    # -- dispatch ----------------------------------------------------------

    def _lookup(self, name: str) -> Callable[..., Any] | None:
        try:
            return self._methods[name]
        except KeyError:
            pass
        found: Callable[..., Any] | None = None
        if name and not name.startswith("_") and "." not in name:
            fn = getattr(self.handler, name, None)
            if callable(fn):
                found = fn
        if len(self._methods) < 4096:
            self._methods[name] = found
        return found

    async def _invoke(self, method: str, params: tuple[Any, ...] | list[Any]) -> Any:
        """Call ``method``, awaiting what it returns when that is awaitable (a coroutine method's call); exceptions
        propagate (turned into faults by the caller)."""
        if method == "system.multicall":
            if len(params) != 1 or not isinstance(params[0], list):
                raise TypeError("system.multicall expects one array of calls")
            return await self._multicall(params[0])
        fn = self._lookup(method)
        if fn is None:
            raise Exception(f'method "{method}" is not supported')
        result = fn(*params)
        if isinstance(result, Awaitable):
            result = await result
        return result

    async def _multicall(self, calls: list[Any]) -> list[Any]:
        results: list[Any] = []
        for call in calls:
            try:
                if not isinstance(call, dict):
                    raise TypeError("multicall entry must be a struct")
                name = call["methodName"]
                params = call.get("params", [])
                if name == "system.multicall":
                    raise Exception("Recursive system.multicall forbidden")
                if not isinstance(params, list):
                    raise TypeError("params must be an array")
                results.append([await self._invoke(name, params)])
            except Fault as fault:
                results.append({"faultCode": fault.faultCode, "faultString": fault.faultString})
            except asyncio.CancelledError:
                raise
            except Exception as exc:
                results.append({"faultCode": 1, "faultString": _fault_string(exc)})
        return results

    async def _respond_body(self, body: bytes) -> bytes:
        try:
            params, method = decode_call(body)
        except (UnsafeXmlError, ExpatError):
            raise  # not XML, or a DTD: the caller answers a fault and closes the connection
        except Exception as exc:  # well-formed XML with bad values
            return encode_fault(1, _fault_string(exc))
        try:
            result = await self._invoke(method, params)
        except Fault as fault:
            return encode_fault(fault.faultCode, fault.faultString)
        except asyncio.CancelledError:
            raise
        except Exception as exc:
            if not isinstance(exc, TypeError):
                _log.debug("XML-RPC method %s raised", method, exc_info=True)
            return encode_fault(1, _fault_string(exc))
        if type(result) is EncodedResponse:
            return result.body
        try:
            return encode_response(result)
        except Exception as exc:  # e.g. int beyond 32 bits: a fault, as rosmaster sends
            return encode_fault(1, _fault_string(exc))

    # -- HTTP --------------------------------------------------------------

    def _on_connection(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        if self._open >= self.max_connections and not self._evict_one():
            self._refuse(writer)
            return
        conn = _Conn(writer.transport)
        self._open += 1
        task = asyncio.get_running_loop().create_task(self._serve(reader, writer, conn))
        self._connections.add(task)
        task.add_done_callback(self._connections.discard)

    def _evict_one(self) -> bool:
        """Close the connection idle longest, else the oldest unfinished request; False if all are busy."""
        for pool in (self._idle, self._reading):
            if pool:
                victim = next(iter(pool))
                self._forget(victim)
                victim.transport.abort()
                if not self._warned_full:
                    self._warned_full = True
                    _log.warning("XML-RPC port %s reached its limit of %d connections: closing the one idle "
                                 "longest (ROSTUI_XMLRPC_MAX_CONNECTIONS sets the limit)",
                                 self._port, self.max_connections)
                return True
        return False

    def _refuse(self, writer: asyncio.StreamWriter) -> None:
        body = b"503 Service Unavailable: too many connections\n"
        writer.write(b"HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\nContent-Length: %d\r\n"
                     b"Connection: close\r\n\r\n" % len(body) + body)
        writer.close()

    def _forget(self, conn: _Conn) -> None:
        if conn.open:
            conn.open = False
            self._open -= 1
            self._idle.pop(conn, None)
            self._reading.pop(conn, None)

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, conn: _Conn) -> None:
        try:
            while conn.open:
                if not await self._serve_one(reader, writer, conn):
                    break
        except (ConnectionError, asyncio.IncompleteReadError, TimeoutError, OSError):
            pass
        except asyncio.CancelledError:
            pass
        except Exception:  # never let one client take the server down
            _log.exception("unexpected error serving an XML-RPC connection")
        finally:
            self._forget(conn)
            writer.close()
            with contextlib.suppress(Exception):
                await writer.wait_closed()

    async def _send_error(self, writer: asyncio.StreamWriter, status: int, detail: str) -> None:
        body = f"{status} {_REASONS.get(status, 'Error')}: {detail}\n".encode()
        writer.write(
            b"HTTP/1.1 %d %s\r\nContent-Type: text/plain\r\nContent-Length: %d\r\n"
            b"Connection: close\r\n\r\n" % (status, _REASONS.get(status, "Error").encode(), len(body))
            + body
        )
        with contextlib.suppress(Exception):
            async with _timeout(5.0):
                await writer.drain()

    async def _serve_one(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, conn: _Conn) -> bool:
        """Serve one request; return False when the connection must close."""
        self._idle[conn] = None
        async with _timeout(self.idle_timeout):
            first = await reader.read(1)
        if not first or not conn.open:
            return False
        del self._idle[conn]
        self._reading[conn] = None
        try:
            async with _timeout(self.request_timeout):
                try:
                    head = first + await reader.readuntil(b"\r\n\r\n")
                except asyncio.LimitOverrunError:
                    raise _HttpError(431, "request header too large") from None
                except asyncio.IncompleteReadError:
                    return False
                method, keep_alive, length, encoding, expect = self._parse_head(head)
                if expect:
                    writer.write(b"HTTP/1.1 100 Continue\r\n\r\n")
                body = await reader.readexactly(length) if length else b""
        except TimeoutError:
            await self._send_error(writer, 408, "request not received in time")
            return False
        except _HttpError as err:
            await self._send_error(writer, err.status, str(err))
            return False
        if not conn.open:
            return False
        del self._reading[conn]
        if encoding:
            try:
                body = self._decode_body(body, encoding)
            except _HttpError as err:
                await self._send_error(writer, err.status, str(err))
                return False
        try:
            response = await self._respond_body(body)
        except (UnsafeXmlError, ExpatError) as exc:  # garbage or a DTD: answer, then drop the peer
            response = encode_fault(1, _fault_string(exc))
            keep_alive = False
        writer.write(
            b"HTTP/1.1 200 OK\r\nServer: rostui-xmlrpc\r\nContent-Type: text/xml\r\n"
            b"Content-Length: %d\r\n%s\r\n" % (
                len(response), b"" if keep_alive else b"Connection: close\r\n")
            + response
        )
        transport = writer.transport
        if transport.get_write_buffer_size() > 65536:
            await writer.drain()
        return keep_alive

    def _parse_head(self, head: bytes) -> tuple[bytes, bool, int, str, bool]:
        lines = head[:-4].split(b"\r\n")
        parts = lines[0].split()
        if len(parts) != 3:
            raise _HttpError(400, "malformed request line")
        method, _target, version = parts
        if version == b"HTTP/1.1":
            keep_alive = True
        elif version == b"HTTP/1.0":
            keep_alive = False
        elif version.startswith(b"HTTP/"):
            raise _HttpError(505, "only HTTP/1.0 and HTTP/1.1 are supported")
        else:
            raise _HttpError(400, "malformed request line")
        if method != b"POST":
            raise _HttpError(501, "only POST is supported")
        length: int | None = None
        encoding = ""
        expect = False
        for line in lines[1:]:
            name, sep, value = line.partition(b":")
            if not sep:
                raise _HttpError(400, "malformed header line")
            name = name.strip().lower()
            value = value.strip()
            if name == b"content-length":
                if not value.isdigit() or len(value) > 18:
                    raise _HttpError(400, "bad Content-Length")
                length = int(value)
            elif name == b"connection":
                token = value.lower()
                if b"close" in token:
                    keep_alive = False
                elif b"keep-alive" in token:
                    keep_alive = True
            elif name == b"transfer-encoding":
                raise _HttpError(411, "chunked requests are not supported; send Content-Length")
            elif name == b"content-encoding":
                encoding = value.lower().decode("latin-1")
            elif name == b"expect" and value.lower() == b"100-continue":
                expect = True
        if length is None:
            raise _HttpError(411, "Content-Length required")
        if length > self.max_body:
            raise _HttpError(413, f"request body of {length} bytes exceeds {self.max_body}")
        return method, keep_alive, length, encoding, expect

    def _decode_body(self, body: bytes, encoding: str) -> bytes:
        if encoding in ("identity", ""):
            return body
        if encoding not in ("gzip", "x-gzip"):
            raise _HttpError(415, f"unsupported Content-Encoding {encoding}")
        decomp = zlib.decompressobj(16 + zlib.MAX_WBITS)
        try:
            out = decomp.decompress(body, self.max_body + 1)
        except zlib.error as exc:
            raise _HttpError(400, f"bad gzip body: {exc}") from None
        if len(out) > self.max_body or decomp.unconsumed_tail:
            raise _HttpError(413, "decompressed body too large")
        return out

