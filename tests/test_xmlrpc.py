"""rostui.core.xmlrpc: server, client, call_sync and ros_result, in-process and over real sockets."""

from __future__ import annotations

import asyncio
import socket
import xmlrpc.client
from typing import Any, Awaitable, Callable

import pytest

from conftest import free_port
from rostui.core.xmlrpc import (
    RosApiError, XmlRpcClient, XmlRpcConnectionError, XmlRpcFault, XmlRpcProtocolError,
    XmlRpcServer, call_sync, ros_result,
)


class Handler:
    """A tiny handler with plain and async methods."""

    def __init__(self) -> None:
        self.calls = 0

    def add(self, a: Any, b: Any) -> Any:
        self.calls += 1
        return a + b

    async def sleep(self, seconds: float) -> float:
        await asyncio.sleep(seconds)
        return seconds

    def big(self) -> int:
        return 2**40

    def nothing(self) -> None:
        return None

    def echo(self, value: Any) -> Any:
        return value

    def _private(self) -> str:
        return "secret"


def run_with_server(test: Callable[[XmlRpcServer], Awaitable[None]], handler: Any = None, **kwargs: Any) -> None:
    """Start a server on 127.0.0.1 (serving ``handler``, by default a :class:`Handler`), run ``test``, close it."""
    async def main() -> None:
        server = XmlRpcServer(handler if handler is not None else Handler(), "127.0.0.1", **kwargs)
        await server.start()
        try:
            await test(server)
        finally:
            await server.close()
    asyncio.run(main())


def raw_exchange(port: int, data: bytes, timeout: float = 5.0) -> bytes:
    """Send raw bytes, return everything the server sends back before closing."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(data)
        chunks = []
        while True:
            try:
                chunk = s.recv(65536)
            except socket.timeout:
                break
            if not chunk:
                break
            chunks.append(chunk)
    return b"".join(chunks)


def test_calls_values_and_uri() -> None:
    async def t(server: XmlRpcServer) -> None:
        assert server.uri == f"http://127.0.0.1:{server.port}/"
        async with XmlRpcClient(server.uri) as c:
            assert await c.call("add", 1, 2) == 3
            assert await c.call("add", "a", "b") == "ab"
            assert await c.call("nothing") is None
            assert await c.call("sleep", 0.01) == 0.01
            value = {"x": [1, 2.5, True, "s", {"y": b"\x00\x01"}]}
            assert await c.call("echo", value) == value
    run_with_server(t)


def test_advertise_host_in_uri() -> None:
    async def main() -> None:
        server = XmlRpcServer(Handler(), "127.0.0.1", advertise_host="myhost")
        await server.start()
        assert server.uri == f"http://myhost:{server.port}/"
        await server.close()
    asyncio.run(main())


def test_faults() -> None:
    async def t(server: XmlRpcServer) -> None:
        async with XmlRpcClient(server.uri) as c:
            with pytest.raises(XmlRpcFault) as err:
                await c.call("nope")
            assert err.value.code == 1
            assert err.value.string == '<class \'Exception\'>:method "nope" is not supported'
            with pytest.raises(XmlRpcFault, match="TypeError"):
                await c.call("add", 1)
            with pytest.raises(XmlRpcFault, match="OverflowError"):
                await c.call("big")
            with pytest.raises(XmlRpcFault, match="not supported"):
                await c.call("_private")
            with pytest.raises(XmlRpcFault, match="not supported"):
                await c.call("__init__")
            # the connection survives faults
            assert await c.call("add", 2, 3) == 5
    run_with_server(t)


def test_stdlib_client_and_multicall() -> None:
    async def t(server: XmlRpcServer) -> None:
        def sync_part() -> list[Any]:
            proxy = xmlrpc.client.ServerProxy(server.uri, allow_none=True)
            assert proxy.add(3, 4) == 7
            multi = xmlrpc.client.MultiCall(proxy)
            multi.add(1, 2)
            multi.nope()
            multi.nothing()
            return list(multi().results)
        results = await asyncio.to_thread(sync_part)
        assert results[0] == [3]
        assert results[1]["faultCode"] == 1 and "not supported" in results[1]["faultString"]
        assert results[2] == [None]
    run_with_server(t)


def test_call_sync_and_errors() -> None:
    async def t(server: XmlRpcServer) -> None:
        assert await asyncio.to_thread(call_sync, server.uri, "add", 1, 1) == 2
        with pytest.raises(XmlRpcFault):
            await asyncio.to_thread(call_sync, server.uri, "nope")
    run_with_server(t)
    dead = f"http://127.0.0.1:{free_port()}/"
    with pytest.raises(XmlRpcConnectionError, match="refused") as err:
        call_sync(dead, "getUri", "/x")
    assert dead in str(err.value)

    async def refused() -> None:
        with pytest.raises(XmlRpcConnectionError) as err:
            await XmlRpcClient(dead).call("getUri", "/x")
        assert dead in str(err.value)
    asyncio.run(refused())


def test_client_timeout_names_uri() -> None:
    async def t(server: XmlRpcServer) -> None:
        c = XmlRpcClient(server.uri, timeout=0.2)
        with pytest.raises(XmlRpcConnectionError, match="within") as err:
            await c.call("sleep", 2.0)
        assert server.uri in str(err.value)
        assert await c.call("add", 1, 1) == 2  # reconnects
        await c.close()
    run_with_server(t)


def test_concurrent_calls_on_one_client() -> None:
    async def t(server: XmlRpcServer) -> None:
        async with XmlRpcClient(server.uri) as c:
            results = await asyncio.gather(*(c.call("add", i, i) for i in range(50)))
            assert results == [2 * i for i in range(50)]
    run_with_server(t)


def test_client_reconnects_after_server_drops_idle_connection() -> None:
    async def t(server: XmlRpcServer) -> None:
        async with XmlRpcClient(server.uri) as c:
            assert await c.call("add", 1, 2) == 3
            await asyncio.sleep(0.4)  # server closes the idle keep-alive connection
            assert await c.call("add", 2, 2) == 4
    run_with_server(t, idle_timeout=0.1)


def test_huge_content_length_is_refused_without_allocating() -> None:
    async def t(server: XmlRpcServer) -> None:
        reply = await asyncio.to_thread(
            raw_exchange, server.port,
            b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999999\r\n\r\n<?xml")
        assert reply.startswith(b"HTTP/1.1 413 ")
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t, max_body=1024)


@pytest.mark.parametrize("data, status", [
    (b"garbage\r\n\r\n", b"400"),
    (b"\x00\xff\x13\x37 \x01\x02\r\n\r\n", b"400"),
    (b"GET / HTTP/1.1\r\nHost: x\r\n\r\n", b"501"),
    (b"POST / HTTP/1.1\r\nHost: x\r\n\r\n", b"411"),
    (b"POST / HTTP/1.1\r\nContent-Length: -5\r\n\r\n", b"400"),
    (b"POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n", b"411"),
    (b"POST / HTTP/1.1\r\nno colon here\r\n\r\n", b"400"),
    (b"POST / SPDY/9\r\nContent-Length: 1\r\n\r\nx", b"400"),
])
def test_bad_http_gets_an_error_and_server_survives(data: bytes, status: bytes) -> None:
    async def t(server: XmlRpcServer) -> None:
        reply = await asyncio.to_thread(raw_exchange, server.port, data)
        assert reply.split(b" ")[1] == status, reply
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t)


@pytest.mark.parametrize("body", [
    b"not xml at all",
    b"<?xml version='1.0'?><methodCall><methodName>add</methodName><params>",
    b"<?xml version='1.0'?><methodCall><params></params></methodCall>",
    b"<?xml version='1.0'?><!DOCTYPE x [<!ENTITY a 'aaaa'>]><methodCall><methodName>echo"
    b"</methodName><params><param><value>&a;</value></param></params></methodCall>",
    b"<?xml version='1.0'?><methodCall><methodName>add</methodName><params><param><value>"
    b"<int>notanint</int></value></param></params></methodCall>",
])
def test_bad_xml_is_a_fault(body: bytes) -> None:
    async def t(server: XmlRpcServer) -> None:
        request = b"POST / HTTP/1.1\r\nContent-Length: %d\r\nConnection: close\r\n\r\n" % len(body) + body
        reply = await asyncio.to_thread(raw_exchange, server.port, request)
        assert reply.startswith(b"HTTP/1.1 200 ")
        assert b"<fault>" in reply
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t)


def test_slow_loris_does_not_block_others() -> None:
    async def t(server: XmlRpcServer) -> None:
        _, writer = await asyncio.open_connection("127.0.0.1", server.port)
        writer.write(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n")  # never finished
        await writer.drain()
        # The unfinished request has 60 s before it times out; a server that
        # waited for it would miss this deadline.
        assert await asyncio.wait_for(XmlRpcClient(server.uri).call("add", 1, 1), 10) == 2
        writer.close()
    run_with_server(t, request_timeout=60)


def test_slow_loris_times_out_with_408() -> None:
    async def t(server: XmlRpcServer) -> None:
        reader, writer = await asyncio.open_connection("127.0.0.1", server.port)
        writer.write(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n")  # never finished
        await writer.drain()
        reply = await asyncio.wait_for(reader.read(), 10)
        assert reply.startswith(b"HTTP/1.1 408 ")
        writer.close()
        assert await XmlRpcClient(server.uri).call("add", 1, 1) == 2
    run_with_server(t, request_timeout=0.5)


def test_ros_result() -> None:
    assert ros_result([1, "ok", 42]) == 42
    with pytest.raises(RosApiError) as err:
        ros_result([-1, "no provider", ""])
    assert err.value.code == -1 and err.value.message == "no provider"
    with pytest.raises(RosApiError):
        ros_result((0, "failed", 0))
    with pytest.raises(XmlRpcProtocolError):
        ros_result("nonsense")


@pytest.mark.parametrize("params", [
    ("/n", "/t1", "std_msgs/String", "http://127.0.0.1:1/"),
    (),
    ("",),
    (0, -5, 2**31 - 1, "ünï", "x y\tz", "  "),
    ("a&b<c>",),
    ("l\r\nx",),
    (True, 1.5, None, [1, "x"], {"k": {"j": b"\x00"}}),
])
def test_decode_fast_path_agrees_with_stdlib(params: tuple[Any, ...]) -> None:
    from rostui.core.xmlrpc.marshal import decode_call, encode_call
    body = encode_call("someMethod", params)
    assert decode_call(body) == xmlrpc.client.loads(body, use_builtin_types=True)


@pytest.mark.parametrize("body", [
    b"<methodCall><methodName>m</methodName><params><param><value>bare</value></param></params></methodCall>",
    b"<?xml version='1.0'?>\n<methodCall>\n<methodName>m</methodName>\n<params>\n<param>\n"
    b"<value><i4>7</i4></value>\n</param>\n</params>\n</methodCall>\n",
    b"<methodCall><methodName>m</methodName><params><param><value><int>99999999999999999999</int>"
    b"</value></param></params></methodCall>",
])
def test_decode_raw_documents_agree_with_stdlib(body: bytes) -> None:
    from rostui.core.xmlrpc.marshal import decode_call
    assert decode_call(body) == xmlrpc.client.loads(body, use_builtin_types=True)


def test_decode_fast_path_refuses_what_expat_refuses() -> None:
    from rostui.core.xmlrpc.marshal import decode_call
    body = b"<methodCall>\x0c<methodName>m</methodName></methodCall>"
    with pytest.raises(Exception):
        xmlrpc.client.loads(body)
    with pytest.raises(Exception):
        decode_call(body)


@pytest.mark.parametrize("text", [b"a\x01b", b"a]]>b", b"\x00"])
def test_decode_fast_path_does_not_accept_invalid_characters(text: bytes) -> None:
    from rostui.core.xmlrpc.marshal import decode_call
    body = b"<methodCall><methodName>m</methodName><params><param><value><string>" + text + \
        b"</string></value></param></params></methodCall>"
    with pytest.raises(Exception):
        xmlrpc.client.loads(body)
    with pytest.raises(Exception):
        decode_call(body)
