"""Hostile XML-RPC input: DTDs in any encoding (server, clients, quick path), idle and surplus connections on a
port, and the Master API's ``shutdown`` call against the real `rostui core` command."""

from __future__ import annotations

import asyncio
import resource
import socket
import subprocess
import sys
import threading
from contextlib import contextmanager
from typing import Any, Awaitable, Callable, Iterator
from xml.parsers import expat

import pytest

from conftest import REPO, master_port, read_until_closed, wait_until
from test_xmlrpc import run_with_server as serve
from rostui.core.xmlrpc import XmlRpcClient, XmlRpcConnectionError, XmlRpcProtocolError, XmlRpcServer, call_sync
from rostui.core.xmlrpc.limits import (
    DEFAULT_IDLE_TIMEOUT, DEFAULT_REQUEST_TIMEOUT, idle_timeout_from_env, max_connections_from_env,
    request_timeout_from_env,
)
from rostui.core.xmlrpc.marshal import decode_call, decode_response
from rostui.core.xmlrpc.quick import quick_call
from rostui.core.xmlrpc.safexml import UnsafeXmlError

ENTITY = "expanded" * 8

#: (test id, Python codec, encoding named in the XML declaration or None for no declaration)
ENCODINGS = [
    ("utf-8", "utf-8", "UTF-8"),
    ("utf-8-bom", "utf-8-sig", None),
    ("utf-16-bom", "utf-16", "UTF-16"),
    ("utf-16-bom-nodecl", "utf-16", None),
    ("utf-16le", "utf-16-le", "UTF-16"),
    ("utf-16be", "utf-16-be", "UTF-16"),
    ("utf-32-bom", "utf-32", "UTF-32"),
    ("utf-32le", "utf-32-le", "UTF-32"),
    ("latin-1", "latin-1", "ISO-8859-1"),
    ("cp1252", "cp1252", "windows-1252"),
]
ENCODING_IDS = [e[0] for e in ENCODINGS]


def with_dtd(xml: str, codec: str, declared: str | None) -> bytes:
    """``xml`` (a document without declaration) behind a DTD declaring entity ``a``, encoded with ``codec``."""
    declaration = f'<?xml version="1.0" encoding="{declared}"?>' if declared else ""
    return (declaration + f'<!DOCTYPE d [<!ENTITY a "{ENTITY}">]>' + xml).encode(codec)


def call_doc(codec: str, declared: str | None) -> bytes:
    """A getPid call whose argument is ``&a;`` repeated, behind a DTD."""
    return with_dtd("<methodCall><methodName>getPid</methodName><params><param><value><string>"
                    + "&a;" * 16 + "</string></value></param></params></methodCall>", codec, declared)


def response_doc(codec: str, declared: str | None) -> bytes:
    """A methodResponse whose string value is ``&a;`` repeated, behind a DTD."""
    return with_dtd("<methodResponse><params><param><value><string>" + "&a;" * 16
                    + "</string></value></param></params></methodResponse>", codec, declared)


class Handler:
    """A handler with one plain and one slow method."""

    def add(self, a: Any, b: Any) -> Any:
        return a + b

    def getPid(self, caller_id: str) -> list[Any]:
        return [1, "", 42]

    async def sleep(self, seconds: float) -> float:
        await asyncio.sleep(seconds)
        return seconds


def run_with_server(test: Callable[[XmlRpcServer], Awaitable[None]], **kwargs: Any) -> None:
    """Start a server of this file's :class:`Handler` on 127.0.0.1, run ``test`` against it, close it."""
    serve(test, Handler(), **kwargs)


def post(body: bytes, keep_alive: bool = False) -> bytes:
    """A complete HTTP/1.1 POST carrying ``body``."""
    close = b"" if keep_alive else b"Connection: close\r\n"
    return b"POST / HTTP/1.1\r\nContent-Type: text/xml\r\nContent-Length: %d\r\n%s\r\n" % (len(body), close) + body


# -- DTDs in every encoding -------------------------------------------------------------------------------------


@pytest.mark.parametrize("codec, declared", [e[1:] for e in ENCODINGS], ids=ENCODING_IDS)
def test_dtd_is_refused_in_any_encoding(codec: str, declared: str | None) -> None:
    for document, decode in ((call_doc(codec, declared), decode_call), (response_doc(codec, declared),
                                                                         decode_response)):
        with pytest.raises((UnsafeXmlError, expat.ExpatError)):
            decode(document)


@pytest.mark.parametrize("codec, declared", [e[1:] for e in ENCODINGS], ids=ENCODING_IDS)
def test_server_answers_a_dtd_with_a_fault_and_drops_the_connection(codec: str, declared: str | None) -> None:
    async def t(server: XmlRpcServer) -> None:
        def exchange() -> bytes:
            with socket.create_connection(("127.0.0.1", server.port), timeout=10) as s:
                s.sendall(post(call_doc(codec, declared), keep_alive=True))
                return read_until_closed(s)  # closed by the server although the client asked keep-alive
        reply = await asyncio.to_thread(exchange)
        assert reply.startswith(b"HTTP/1.1 200 ") and b"<fault>" in reply, reply[:300]
        assert ENTITY.encode() not in reply
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t)


@contextmanager
def canned_http(body: bytes) -> Iterator[str]:
    """An HTTP server on 127.0.0.1 answering every request with ``body`` (a 200, then close); yields its URI."""
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.1)
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = listener.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            with conn:
                conn.settimeout(5)
                data = b""
                try:
                    while b"\r\n\r\n" not in data:
                        data += conn.recv(65536)
                    head, _, rest = data.partition(b"\r\n\r\n")
                    length = next(int(line.split(b":")[1]) for line in head.split(b"\r\n")
                                  if line.lower().startswith(b"content-length:"))
                    while len(rest) < length:
                        rest += conn.recv(65536)
                    conn.sendall(b"HTTP/1.1 200 OK\r\nContent-Type: text/xml\r\nContent-Length: %d\r\n"
                                 b"Connection: close\r\n\r\n" % len(body) + body)
                except OSError:
                    pass

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{listener.getsockname()[1]}/"
    finally:
        stop.set()
        thread.join(5)
        listener.close()


@pytest.mark.parametrize("codec, declared", [e[1:] for e in ENCODINGS], ids=ENCODING_IDS)
def test_clients_refuse_a_dtd_in_any_encoding(codec: str, declared: str | None) -> None:
    with canned_http(response_doc(codec, declared)) as uri:
        with pytest.raises(XmlRpcProtocolError):
            quick_call(uri, "getPid", "/x", timeout=5)
        with pytest.raises(XmlRpcProtocolError):
            call_sync(uri, "getPid", "/x", timeout=5)

        async def async_client() -> None:
            async with XmlRpcClient(uri, timeout=5) as client:
                await client.call("getPid", "/x")
        with pytest.raises(XmlRpcProtocolError):
            asyncio.run(async_client())


def test_documents_without_a_dtd_still_parse_in_other_encodings() -> None:
    xml = "<methodCall><methodName>echo</methodName><params><param><value><string>h\u00e9</string></value>" \
          "</param></params></methodCall>"
    for codec, declared in (("utf-16", "UTF-16"), ("latin-1", "ISO-8859-1"), ("utf-8-sig", None)):
        declaration = f'<?xml version="1.0" encoding="{declared}"?>' if declared else ""
        assert decode_call((declaration + xml).encode(codec)) == (("h\u00e9",), "echo")
    with canned_http("<methodResponse><params><param><value><string>ok</string></value></param></params>"
                     "</methodResponse>".encode("utf-16")) as uri:
        assert quick_call(uri, "getPid", "/x", timeout=5) == "ok"


# -- idle connections, slow requests, and the connection cap ----------------------------------------------------


def test_limits_come_from_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROSTUI_XMLRPC_IDLE_TIMEOUT", "12.5")
    monkeypatch.setenv("ROSTUI_XMLRPC_REQUEST_TIMEOUT", "7")
    monkeypatch.setenv("ROSTUI_XMLRPC_MAX_CONNECTIONS", "33")
    server = XmlRpcServer(Handler(), "127.0.0.1")
    assert (server.idle_timeout, server.request_timeout, server.max_connections) == (12.5, 7.0, 33)
    for bad in ("", "soon", "-1", "0", "inf"):
        monkeypatch.setenv("ROSTUI_XMLRPC_IDLE_TIMEOUT", bad)
        monkeypatch.setenv("ROSTUI_XMLRPC_REQUEST_TIMEOUT", bad)
        monkeypatch.setenv("ROSTUI_XMLRPC_MAX_CONNECTIONS", bad)
        assert idle_timeout_from_env() == DEFAULT_IDLE_TIMEOUT
        assert request_timeout_from_env() == DEFAULT_REQUEST_TIMEOUT
        assert max_connections_from_env() >= 16


def test_default_cap_leaves_room_under_a_low_open_file_limit() -> None:
    def lower() -> None:
        resource.setrlimit(resource.RLIMIT_NOFILE, (1024, resource.getrlimit(resource.RLIMIT_NOFILE)[1]))
    out = subprocess.run(
        [sys.executable, "-c", "from rostui.core.xmlrpc.limits import max_connections_from_env as m, "
         "listen_backlog as b; print(m(), b())"],
        preexec_fn=lower, capture_output=True, text=True, check=True, cwd=str(REPO)).stdout.split()
    cap, backlog = int(out[0]), int(out[1])
    assert cap + backlog < 1024 - 64, (cap, backlog)
    assert cap >= 256


def test_connection_that_never_sends_is_closed(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROSTUI_XMLRPC_IDLE_TIMEOUT", "0.3")

    async def t(server: XmlRpcServer) -> None:
        def silent() -> bytes:
            with socket.create_connection(("127.0.0.1", server.port), timeout=15) as s:
                return read_until_closed(s)
        assert await asyncio.to_thread(silent) == b""
    run_with_server(t)


def test_idle_keep_alive_connection_is_closed(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROSTUI_XMLRPC_IDLE_TIMEOUT", "0.3")
    body = b"<methodCall><methodName>add</methodName><params><param><value><int>1</int></value></param>" \
           b"<param><value><int>2</int></value></param></params></methodCall>"

    async def t(server: XmlRpcServer) -> None:
        def one_call_then_idle() -> bytes:
            with socket.create_connection(("127.0.0.1", server.port), timeout=15) as s:
                s.sendall(post(body, keep_alive=True))
                return read_until_closed(s)
        reply = await asyncio.to_thread(one_call_then_idle)
        assert reply.startswith(b"HTTP/1.1 200 ") and b"<int>3</int>" in reply
        assert b"Connection: close" not in reply
    run_with_server(t)


def test_slow_request_gets_408_with_the_environment_timeout(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROSTUI_XMLRPC_REQUEST_TIMEOUT", "0.3")

    async def t(server: XmlRpcServer) -> None:
        def slow() -> bytes:
            with socket.create_connection(("127.0.0.1", server.port), timeout=15) as s:
                s.sendall(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n")  # never finished
                return read_until_closed(s)
        assert (await asyncio.to_thread(slow)).startswith(b"HTTP/1.1 408 ")
    run_with_server(t)


async def open_idle(port: int, count: int) -> list[tuple[asyncio.StreamReader, asyncio.StreamWriter]]:
    """``count`` connections that send nothing, opened one after the other."""
    return [await asyncio.open_connection("127.0.0.1", port) for _ in range(count)]


async def closed_by_server(reader: asyncio.StreamReader) -> bool:
    """True when the server has closed this connection (EOF or reset within a moment)."""
    try:
        return await asyncio.wait_for(reader.read(1), 0.2) == b""
    except ConnectionError:
        return True
    except TimeoutError:
        return False


def test_connection_cap_closes_the_oldest_idle_connections() -> None:
    async def t(server: XmlRpcServer) -> None:
        idle = await open_idle(server.port, 20)
        async with XmlRpcClient(server.uri) as legit:
            assert await legit.call("add", 1, 1) == 2  # one more connection: the oldest idle one goes
        closed = [await closed_by_server(reader) for reader, _ in idle]
        assert closed == [True] * 13 + [False] * 7
        for _, writer in idle:
            writer.close()
    run_with_server(t, max_connections=8)


def test_connection_cap_closes_stalled_requests_when_none_is_idle() -> None:
    async def t(server: XmlRpcServer) -> None:
        stalled = await open_idle(server.port, 4)
        for _, writer in stalled:
            writer.write(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n")  # never finished
            await writer.drain()
        await asyncio.sleep(0.2)
        assert await XmlRpcClient(server.uri).call("add", 2, 2) == 4
        closed = [await closed_by_server(reader) for reader, _ in stalled]
        assert closed == [True, False, False, False]
        for _, writer in stalled:
            writer.close()
    run_with_server(t, max_connections=4)


def test_connection_beyond_the_cap_is_refused_when_every_one_is_busy() -> None:
    async def t(server: XmlRpcServer) -> None:
        clients = [XmlRpcClient(server.uri) for _ in range(2)]
        busy = [asyncio.ensure_future(c.call("sleep", 1.0)) for c in clients]
        await asyncio.sleep(0.3)

        def extra() -> bytes:
            with socket.create_connection(("127.0.0.1", server.port), timeout=15) as s:
                return read_until_closed(s)
        assert (await asyncio.to_thread(extra)).startswith(b"HTTP/1.1 503 ")
        assert await asyncio.gather(*busy) == [1.0, 1.0]
        for c in clients:
            await c.close()
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t, max_connections=2)


# -- the Master API's shutdown call ------------------------------------------------------------------------------


def test_rostui_core_exits_cleanly_on_the_shutdown_call(rostui_core: subprocess.Popen,
                                                        ros_env: dict[str, str]) -> None:
    uri = f"http://127.0.0.1:{master_port(ros_env)}/"
    assert call_sync(uri, "shutdown", "/hostile_test", "bye") == [1, "shutdown", 0]
    assert rostui_core.wait(timeout=30) == 0
    out = rostui_core.stdout.read() if rostui_core.stdout else ""
    assert "Traceback" not in out, out
    with pytest.raises(XmlRpcConnectionError):
        call_sync(uri, "getPid", "/hostile_test", timeout=2)


def test_shutdown_call_stops_either_master(any_master: str, ros_env: dict[str, str]) -> None:
    uri = f"http://127.0.0.1:{master_port(ros_env)}/"
    assert call_sync(uri, "shutdown", "/hostile_test", "bye") == [1, "shutdown", 0]

    def gone() -> bool:
        try:
            call_sync(uri, "getPid", "/hostile_test", timeout=1)
        except (XmlRpcConnectionError, XmlRpcProtocolError):  # refused, or closed unanswered while stopping
            return True
        return False
    wait_until(gone, f"the {any_master} master to stop after shutdown")
