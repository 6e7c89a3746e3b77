"""Bad input against a live rostui master process: it answers or drops the peer, and keeps serving."""

from __future__ import annotations

import signal
import socket
import subprocess
import sys
from typing import Iterator

import pytest

from conftest import REPO, free_port, stop_process, wait_for_port
from rostui.core.xmlrpc import XmlRpcFault, call_sync


@pytest.fixture
def master(ros_env: dict[str, str]) -> Iterator[tuple[str, int, subprocess.Popen]]:
    """``python -m rostui.core.master`` in a subprocess: (uri, port, process)."""
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "rostui.core.master", "-p", str(port)], env=ros_env,
                            cwd=str(REPO), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        wait_for_port(port, proc=proc)
        yield f"http://127.0.0.1:{port}/", port, proc
    finally:
        stop_process(proc)


def still_alive(uri: str, proc: subprocess.Popen) -> None:
    """The master process runs and answers getUri."""
    assert proc.poll() is None
    assert call_sync(uri, "getUri", "/check", timeout=5) == [1, "", uri]


def send_raw(port: int, data: bytes, wait: float = 3.0) -> bytes:
    """Send ``data``, return what comes back until close or ``wait`` seconds of silence."""
    with socket.create_connection(("127.0.0.1", port), timeout=wait) as s:
        s.sendall(data)
        out = []
        try:
            while chunk := s.recv(65536):
                out.append(chunk)
        except socket.timeout:
            pass
    return b"".join(out)


def post(body: bytes) -> bytes:
    """A complete one-shot HTTP POST carrying ``body``."""
    return b"POST / HTTP/1.1\r\nContent-Type: text/xml\r\nContent-Length: %d\r\nConnection: close\r\n\r\n" % (
        len(body)) + body


def test_prints_run_id_and_uri(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, _, proc = master
    still_alive(uri, proc)
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=10)
    assert proc.returncode == 0
    assert f"ROS_MASTER_URI={uri}" in out
    assert "setting /run_id to " in out


@pytest.mark.parametrize("body", [
    b"<?xml version='1.0'?><methodCall><methodName>getUri</methodName><params><param>",
    b"\x00\x01\x02 definitely not xml \xff\xfe",
    b"<?xml version='1.0'?><!DOCTYPE lol [<!ENTITY a 'aaaaaaaaaa'><!ENTITY b '&a;&a;&a;&a;'>]>"
    b"<methodCall><methodName>getUri</methodName><params><param><value>&b;</value></param></params>"
    b"</methodCall>",
])
def test_malformed_xml_is_a_fault(master: tuple[str, int, subprocess.Popen], body: bytes) -> None:
    uri, port, proc = master
    reply = send_raw(port, post(body))
    assert reply.startswith(b"HTTP/1.1 200 ") and b"<fault>" in reply
    still_alive(uri, proc)


def test_ints_beyond_32_bits(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, port, proc = master
    body = (b"<methodCall><methodName>setParam</methodName><params>"
            b"<param><value><string>/x</string></value></param>"
            b"<param><value><string>/big</string></value></param>"
            b"<param><value><int>99999999999999999999</int></value></param></params></methodCall>")
    reply = send_raw(port, post(body))
    assert b"parameter /big set" in reply
    with pytest.raises(XmlRpcFault, match="OverflowError"):  # as rosmaster answers
        call_sync(uri, "getParam", "/x", "/big")
    with pytest.raises(OverflowError):  # refused on our side before sending
        call_sync(uri, "setParam", "/x", "/big2", 2**40)
    still_alive(uri, proc)


def test_wrong_types_and_counts(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, _, proc = master
    assert call_sync(uri, "registerPublisher", ["/list"], {}, 3.5, None) == [
        -1, "caller_id must be a string", []]
    assert call_sync(uri, "registerPublisher", "/n")[:2] == [-1, "Error: bad call arity"]
    assert call_sync(uri, "setParam", "/n", {"not": "a key"}, 1)[:2] == [
        -1, "ERROR: parameter [key] must be a string"]
    assert call_sync(uri, "getSystemState", "/n", b"\x00bytes")[:2] == [-1, "Error: bad call arity"]
    still_alive(uri, proc)


def test_unknown_method(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, _, proc = master
    for name in ("noSuchMethod", "_private", "__class__", "system.listMethods", "handler.getUri"):
        with pytest.raises(XmlRpcFault, match="is not supported"):
            call_sync(uri, name, "/n")
    still_alive(uri, proc)


def test_huge_content_length(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, port, proc = master
    reply = send_raw(port, b"POST / HTTP/1.1\r\nContent-Length: 999999999999999\r\n\r\n<?xml")
    assert reply.startswith(b"HTTP/1.1 413 ")
    still_alive(uri, proc)


def test_slow_loris(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, port, proc = master
    stalled = [socket.create_connection(("127.0.0.1", port)) for _ in range(20)]
    try:
        for i, s in enumerate(stalled):
            s.sendall(b"POST / HTTP/1.1\r\nContent-Length: 500\r\n\r\n<?xml" if i % 2 else b"POS")
        still_alive(uri, proc)  # answered within its 5 s call timeout while the stalled requests hang
    finally:
        for s in stalled:
            s.close()
    still_alive(uri, proc)


@pytest.mark.parametrize("junk", [
    bytes(range(256)) * 4,
    b"\r\n\r\n",
    b"GET / HTTP/1.1\r\n\r\n",
    b"POST / HTTP/1.1\r\n" + b"X-Long: " + b"a" * 200_000 + b"\r\n\r\n",
    b"POST / HTTP/1.1\r\nContent-Length: 5\r\n\r\n",  # then hang up
], ids=["all-bytes", "blank-lines", "get", "200k-header", "short-body"])  # short ids: pytest puts them in the env
def test_raw_garbage(master: tuple[str, int, subprocess.Popen], junk: bytes) -> None:
    uri, port, proc = master
    with socket.create_connection(("127.0.0.1", port), timeout=3) as s:
        try:
            s.sendall(junk)
            s.recv(1024)
        except OSError:
            pass
    still_alive(uri, proc)


def test_many_connections_at_once(master: tuple[str, int, subprocess.Popen]) -> None:
    uri, port, proc = master
    socks = []
    try:
        for _ in range(200):
            socks.append(socket.create_connection(("127.0.0.1", port)))
        still_alive(uri, proc)
    finally:
        for s in socks:
            s.close()
    still_alive(uri, proc)
