"""The asyncio XML-RPC client: one persistent HTTP/1.1 connection per server."""

from __future__ import annotations

import asyncio
import socket
import sys
import zlib
from typing import Any

from ..localhost import connect_host
from .blocking import MAX_RESPONSE, call_sync, split_uri as _split_uri, unwrap_response as _unwrap
from .errors import XmlRpcConnectionError, XmlRpcFault, XmlRpcProtocolError
from .marshal import encode_call

__all__ = ["XmlRpcClient", "call_sync"]

if sys.version_info >= (3, 11):
    _timeout = asyncio.timeout
else:  # pragma: no cover - Python 3.10
    from .server import _timeout


def _request_head(host: str, port: int, path: str, length: int) -> bytes:
    return (
        f"POST {path} HTTP/1.1\r\nHost: {host}:{port}\r\nUser-Agent: rostui-xmlrpc\r\n"
        f"Content-Type: text/xml\r\nContent-Length: {length}\r\n\r\n"
    ).encode("latin-1")



class _Dropped(Exception):
    """The connection closed before any byte of the response arrived."""


class XmlRpcClient:
    """Call XML-RPC methods on one server over a persistent HTTP/1.1 connection.

    Concurrent :meth:`call` invocations are serialised on the connection.  A
    keep-alive connection the server dropped is reopened once, transparently.
    Every call must complete within ``timeout`` seconds.
    """

    def __init__(self, uri: str, timeout: float = 10.0) -> None:
        self.uri = uri
        self.timeout = timeout
        self._host, self._port, self._path = _split_uri(uri)
        self._reader: asyncio.StreamReader | None = None
        self._writer: asyncio.StreamWriter | None = None
        self._lock = asyncio.Lock()

    async def call(self, method: str, *args: Any) -> Any:
        """Call ``method(*args)`` and return its value.

        Raises :class:`XmlRpcFault` for a fault, :class:`XmlRpcConnectionError`
        when the server cannot be reached or does not answer in time, and
        :class:`XmlRpcProtocolError` for an answer that is not XML-RPC.
        """
        body = encode_call(method, args)
        request = _request_head(self._host, self._port, self._path, len(body)) + body
        async with self._lock:
            try:
                async with _timeout(self.timeout):
                    return await self._call_locked(request)
            except XmlRpcFault:
                raise
            except TimeoutError:
                self._drop()
                raise XmlRpcConnectionError(
                    self.uri, f"no answer to {method} within {self.timeout:g}s") from None
            except BaseException:
                # Cancelled or failed mid-exchange: the connection state is unknown.
                self._drop()
                raise

    async def _call_locked(self, request: bytes) -> Any:
        for attempt in (0, 1):
            fresh = self._writer is None
            if fresh:
                await self._connect()
            try:
                return await self._exchange(request)
            except (_Dropped, ConnectionResetError, BrokenPipeError) as exc:
                self._drop()
                if fresh or attempt:
                    raise XmlRpcConnectionError(self.uri, f"connection lost: {exc or 'closed'}") from None
            except OSError as exc:
                self._drop()
                raise XmlRpcConnectionError(self.uri, str(exc)) from None
        raise AssertionError("unreachable")

    async def _connect(self) -> None:
        try:
            self._reader, self._writer = await asyncio.open_connection(
                connect_host(self._host), self._port, limit=1 << 16)
        except OSError as exc:
            reason = exc.strerror or str(exc)
            if isinstance(exc, ConnectionRefusedError):
                reason = "connection refused"
            raise XmlRpcConnectionError(self.uri, reason) from None
        sock = self._writer.get_extra_info("socket")
        if sock is not None:
            try:
                sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            except OSError:
                pass

    async def _exchange(self, request: bytes) -> Any:
        reader, writer = self._reader, self._writer
        assert reader is not None and writer is not None
        writer.write(request)
        if writer.transport.get_write_buffer_size() > 65536:
            await writer.drain()
        try:
            head = await reader.readuntil(b"\r\n\r\n")
        except asyncio.IncompleteReadError as exc:
            if not exc.partial:
                raise _Dropped() from None
            raise XmlRpcProtocolError(self.uri, "connection closed inside the response header") from None
        except asyncio.LimitOverrunError:
            raise XmlRpcProtocolError(self.uri, "response header too large") from None
        status, reason, length, close, chunked, gz = self._parse_head(head)
        try:
            if chunked:
                body = await self._read_chunked(reader)
            elif length is not None:
                body = await reader.readexactly(length)
            else:
                body = await reader.read(MAX_RESPONSE + 1)
                close = True
        except asyncio.IncompleteReadError:
            raise XmlRpcProtocolError(self.uri, "connection closed inside the response body") from None
        if close:
            self._drop()
        if status != 200:
            raise XmlRpcProtocolError(self.uri, f"HTTP {status} {reason}")
        if gz:
            try:
                body = zlib.decompress(body, 16 + zlib.MAX_WBITS)
            except zlib.error as exc:
                raise XmlRpcProtocolError(self.uri, f"bad gzip body: {exc}") from None
        return _unwrap(self.uri, body)

    def _parse_head(self, head: bytes) -> tuple[int, str, int | None, bool, bool, bool]:
        lines = head[:-4].split(b"\r\n")
        parts = lines[0].split(None, 2)
        if len(parts) < 2 or not parts[0].startswith(b"HTTP/") or not parts[1].isdigit():
            raise XmlRpcProtocolError(self.uri, f"bad status line {lines[0][:80]!r}")
        status = int(parts[1])
        reason = parts[2].decode("latin-1") if len(parts) > 2 else ""
        close = parts[0] == b"HTTP/1.0"
        length: int | None = None
        chunked = gz = False
        for line in lines[1:]:
            name, _, value = line.partition(b":")
            name = name.strip().lower()
            value = value.strip().lower()
            if name == b"content-length":
                if not value.isdigit() or int(value) > MAX_RESPONSE:
                    raise XmlRpcProtocolError(self.uri, "bad or too large Content-Length")
                length = int(value)
            elif name == b"connection":
                if b"close" in value:
                    close = True
                elif b"keep-alive" in value:
                    close = False
            elif name == b"transfer-encoding":
                chunked = b"chunked" in value
            elif name == b"content-encoding":
                gz = value in (b"gzip", b"x-gzip")
        return status, reason, length, close, chunked, gz

    async def _read_chunked(self, reader: asyncio.StreamReader) -> bytes:
        chunks: list[bytes] = []
        total = 0
        while True:
            line = await reader.readuntil(b"\r\n")
            try:
                size = int(line.split(b";")[0].strip(), 16)
            except ValueError:
                raise XmlRpcProtocolError(self.uri, "bad chunk size") from None
            if size == 0:
                while (await reader.readuntil(b"\r\n")) != b"\r\n":
                    pass
                return b"".join(chunks)
            total += size
            if total > MAX_RESPONSE:
                raise XmlRpcProtocolError(self.uri, "response too large")
            chunks.append(await reader.readexactly(size))
            await reader.readexactly(2)

    def _drop(self) -> None:
        writer = self._writer
        self._reader = self._writer = None
        if writer is not None:
            writer.close()

    async def close(self) -> None:
        """Close the connection (a later :meth:`call` opens a new one)."""
        writer = self._writer
        self._drop()
        if writer is not None:
            try:
                await writer.wait_closed()
            except (OSError, asyncio.CancelledError):
                pass

    async def __aenter__(self) -> "XmlRpcClient":
        return self

    async def __aexit__(self, *exc: object) -> None:
        await self.close()
