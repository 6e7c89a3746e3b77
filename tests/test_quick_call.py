"""The light `param get` path: quick_call agrees with call_sync, simple_value_text with PyYAML."""

from __future__ import annotations

import random
import socket
import threading
import xmlrpc.client
from typing import Any, Iterator

import pytest
import yaml

from conftest import free_port
from rostui.core.xmlrpc import XmlRpcConnectionError, XmlRpcFault, XmlRpcProtocolError, call_sync
from rostui.core.xmlrpc.quick import quick_call
from rostui.tools.param_quick import simple_value_text

ANSWERS: list[Any] = [
    [1, "ok", "bf238e12-e67f-11f1-aca0-02fc00000001"], [1, "", True], [-1, "Parameter [/x] is not set", 0],
    [1, "x", ["a", 1, [False, "z<&>"]]], [1, "x", 2.5], [1, "x", {"a": [1, {"b": "c"}]}], [1, "x", None],
    [1, "h\u00e9llo\n", "\u20ac"], [1, "x", []], [1, "x", ""], [1, "x", -2**31], [1, "x", b"\x00\x01"],
]


def http_answer(body: bytes, status: str = "200 OK", headers: str = "") -> bytes:
    return (f"HTTP/1.0 {status}\r\nContent-Type: text/xml\r\nContent-Length: {len(body)}\r\n{headers}\r\n"
            ).encode() + body


@pytest.fixture
def one_shot_server() -> Iterator[tuple[str, list[bytes], list[bytes]]]:
    """A server that answers each connection with the next queued bytes and records what it read."""
    listener = socket.create_server(("127.0.0.1", 0))
    replies: list[bytes] = []
    received: list[bytes] = []

    def serve() -> None:
        while True:
            try:
                conn, _ = listener.accept()
            except OSError:
                return
            with conn:
                data = b""
                while b"</methodCall>" not in data:
                    chunk = conn.recv(65536)
                    if not chunk:
                        break
                    data += chunk
                received.append(data)
                conn.sendall(replies.pop(0) if replies else b"")

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{listener.getsockname()[1]}/", replies, received
    listener.close()


@pytest.mark.parametrize("answer", ANSWERS)
def test_same_value_as_call_sync(one_shot_server: tuple[str, list[bytes], list[bytes]], answer: Any) -> None:
    uri, replies, received = one_shot_server
    body = xmlrpc.client.dumps((answer,), methodresponse=True, allow_none=True).encode()
    replies.extend([http_answer(body), http_answer(body)])
    quick = quick_call(uri, "getParam", "/rosparam", "/a&b<c>")
    full = call_sync(uri, "getParam", "/rosparam", "/a&b<c>")
    assert quick == full and type(quick[2]) is type(full[2])
    assert xmlrpc.client.loads(received[0].partition(b"\r\n\r\n")[2]) == (("/rosparam", "/a&b<c>"), "getParam")


@pytest.mark.parametrize("reply", [
    http_answer(b"<methodResponse><fault><value><struct><member><name>faultCode</name><value><int>1</int>"
                b"</value></member><member><name>faultString</name><value>no</value></member></struct>"
                b"</value></fault></methodResponse>"),
    http_answer(b"not xml"),
    http_answer(b"", status="500 Internal Server Error"),
    b"HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n",
    b"garbage",
])
def test_same_errors_as_call_sync(one_shot_server: tuple[str, list[bytes], list[bytes]], reply: bytes) -> None:
    uri, replies, _ = one_shot_server
    replies.extend([reply] * 3)  # quick_call may repeat the call through call_sync: once, then ours
    with pytest.raises((XmlRpcFault, XmlRpcProtocolError)) as quick:
        quick_call(uri, "getParam", "/rosparam", "/x")
    with pytest.raises((XmlRpcFault, XmlRpcProtocolError)) as full:
        call_sync(uri, "getParam", "/rosparam", "/x")
    assert (type(quick.value), str(quick.value)) == (type(full.value), str(full.value))


def test_refused_is_a_connection_error() -> None:
    dead = f"http://127.0.0.1:{free_port()}/"
    with pytest.raises(XmlRpcConnectionError, match="refused"):
        quick_call(dead, "getParam", "/rosparam", "/x")


def test_simple_value_text_is_what_yaml_prints() -> None:
    """Every value given a text dumps to exactly that text and loads back as the same value."""
    rng = random.Random(7)
    alphabet = "abcxyzYESNOTRUEonfFlLnu0123456789_./-:# '\"\u00e9"
    words = ["yes", "No", "ON", "off", "null", "Null", "y", "n", "~", "1e3", "0x1f", "0b11", "017", "1_000",
             "2024-01-01", "1.5", ".inf", ".nan", "-1", "+1", "12:30", "---", "...", "-", "/", "_", "/run_id",
             "0f6c1c5e-8a3b-11ee-9a6a-0242ac120002", "1a", "9_a", "", " x", "x "]
    strings = words + ["".join(rng.choice(alphabet) for _ in range(rng.randint(1, 10))) for _ in range(20000)]
    values: list[Any] = [True, False, 0, -7, 2**40, 2.5, None, [1], {"a": 1}, *strings]
    plain = 0
    for value in values:
        text = simple_value_text(value)
        if text is None:
            continue
        plain += 1
        dumped = yaml.dump(value)
        assert dumped == text + "\n...\n", value
        assert yaml.safe_load(dumped) == value
    assert simple_value_text("bf238e12-e67f-11f1-aca0-02fc00000001") is not None
    assert plain > 1000
