"""A peer sending garbage over TCPROS loses its connection, never our process.

Each bad input goes to a live rostui process; afterwards the same process
still serves a normal client.
"""

from __future__ import annotations

import asyncio
import socket
import struct
import subprocess
import sys
import textwrap
from typing import Any, Iterator

import pytest

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node import AsyncNode
from rostui.core.tcpros import FrameReader, FrameTooLargeError, HeaderError, decode_header, encode_header, frame
from rostui.core.xmlrpc import XmlRpcServer, call_sync

from conftest import read_until_closed, stop_process
from test_node import run, until

String = get_message_class("std_msgs/String")
SetBool = get_service_class("std_srvs/SetBool")

VICTIM_SCRIPT = textwrap.dedent("""
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
    SetBool = ros.srv("std_srvs/SetBool")
    ros.init_node("victim")
    pub = ros.Publisher("chatter", String, queue_size=10)
    ros.Service("toggle", SetBool, lambda req: (True, "fine"))
    ros.Subscriber("incoming", String, lambda m: print("got", m.data, flush=True))
    rate = ros.Rate(50)
    while not ros.is_shutdown():
        pub.publish(String(data="alive"))
        rate.sleep()
""")


@pytest.fixture
def victim(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[tuple[subprocess.Popen, int]]:
    """A rostui node (publisher, service, subscriber) and its TCPROS port."""
    env = dict(ros_env, ROSTUI_TCPROS_STALL_TIMEOUT="1")
    proc = subprocess.Popen([sys.executable, "-c", VICTIM_SCRIPT], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    master = ros_env["ROS_MASTER_URI"]
    try:
        uri = None
        for _ in range(200):
            code, _, value = call_sync(master, "lookupService", "/test", "/toggle")
            if code == 1:
                uri = value
                break
            if proc.poll() is not None:
                raise RuntimeError(proc.stdout.read() if proc.stdout else "victim died")
            run(asyncio.sleep(0.05))
        assert uri is not None, "victim never registered /toggle"
        yield proc, int(uri.rsplit(":", 1)[1])
    finally:
        stop_process(proc)


def exchange(port: int, data: bytes, pause: float = 0.0) -> bytes:
    """Send raw bytes to a TCPROS port; return all bytes until the peer closes."""
    with socket.create_connection(("127.0.0.1", port), timeout=15) as sock:
        sock.sendall(data)
        return read_until_closed(sock)


def error_of(reply: bytes) -> str:
    """The ``error`` field of a reply header (empty string if the peer just closed)."""
    if len(reply) < 4:
        return ""
    (size,) = struct.unpack_from("<I", reply)
    return decode_header(reply[4 : 4 + size]).get("error", "")


def still_serving() -> None:
    """A normal subscriber receives /chatter and a normal service call succeeds."""
    async def scenario() -> None:
        node = await AsyncNode("checker", anonymous=True).start()
        got: list[str] = []
        await node.subscribe("chatter", String, lambda m: got.append(m.data))
        await until(lambda: "alive" in got)
        resp = await node.service_proxy("toggle", SetBool).call(True)
        assert (resp.success, resp.message) == (True, "fine")
        await node.shutdown()
    run(scenario())


SUB_HEADER = {"callerid": "/evil", "topic": "/chatter", "type": "std_msgs/String",
              "md5sum": String._md5sum}

BAD_INPUTS = {
    "missing md5sum": (encode_header({k: v for k, v in SUB_HEADER.items() if k != "md5sum"}), "md5sum"),
    "md5 mismatch": (encode_header(dict(SUB_HEADER, md5sum="0" * 32)), "our version has"),
    "wrong topic": (encode_header(dict(SUB_HEADER, topic="/nope")), "unknown topic"),
    "no topic or service": (encode_header({"callerid": "/evil"}), "topic or service"),
    "header length over the cap": (b"\xff\xff\xff\xff", "exceeds the cap"),
    "http request": (b"GET / HTTP/1.1\r\nHost: x\r\n\r\n", "exceeds the cap"),
    "field runs past header": (struct.pack("<II", 8, 100) + b"abcd", "runs past"),
    "field without equals": (struct.pack("<II", 9, 5) + b"hello", "without '='"),
    "service md5 mismatch": (encode_header({"callerid": "/evil", "service": "/toggle", "md5sum": "bad"}),
                             "md5sums do not match"),
}


@pytest.mark.parametrize("case", list(BAD_INPUTS))
def test_bad_header_is_refused_and_process_keeps_serving(victim: tuple[subprocess.Popen, int], case: str) -> None:
    proc, port = victim
    data, expected = BAD_INPUTS[case]
    assert expected in error_of(exchange(port, data))
    assert proc.poll() is None
    still_serving()


def test_stalled_peer_is_dropped(victim: tuple[subprocess.Popen, int]) -> None:
    proc, port = victim
    reply = exchange(port, struct.pack("<I", 64) + b"callerid")
    assert reply == b""  # closed by the victim after the stall timeout, nothing sent
    assert proc.poll() is None
    still_serving()


def test_service_request_over_cap_drops_only_that_connection(victim: tuple[subprocess.Popen, int]) -> None:
    proc, port = victim
    header = encode_header({"callerid": "/evil", "service": "/toggle", "md5sum": SetBool._md5sum})
    reply = exchange(port, header + struct.pack("<I", 0xFFFFFFF0))
    assert "md5sum" in decode_header(reply[4:4 + struct.unpack_from("<I", reply)[0]])
    assert reply[4 + struct.unpack_from("<I", reply)[0]:] == b""
    assert proc.poll() is None
    still_serving()


class EvilPublisher:
    """A fake publisher: a slave API answering requestTopic, and a raw TCP server."""

    def __init__(self, behaviour: str) -> None:
        self.behaviour = behaviour
        self.connections = 0

    def requestTopic(self, caller_id: str, topic: str, protocols: list[Any]) -> list[Any]:
        """Point the subscriber at our raw server."""
        return [1, "", ["TCPROS", "127.0.0.1", self.port]]

    async def serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        """Misbehave according to ``behaviour``."""
        self.connections += 1
        good = encode_header({"callerid": "/evil", "md5sum": String._md5sum, "type": "std_msgs/String",
                              "latching": "0", "message_definition": String._full_text})
        payloads = {
            "huge frame": good + struct.pack("<I", 0xFFFFFFF0),
            "garbage header": b"\x05\x00\x00\x00garbage",
            "md5 mismatch": encode_header({"callerid": "/evil", "md5sum": "f" * 32, "type": "std_msgs/String"}),
            "missing type": encode_header({"callerid": "/evil", "md5sum": String._md5sum}),
            "stall mid-frame": good + struct.pack("<I", 100) + b"partial",
            "bad string": good + frame(struct.pack("<I", 1000) + b"short"),
        }
        writer.write(payloads[self.behaviour])
        await writer.drain()
        try:
            await reader.read()
        finally:
            writer.close()

    port = 0


LISTENER_SCRIPT = textwrap.dedent("""
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
    ros.init_node("listener")
    ros.Subscriber("chatter", String, lambda m: print("got", m.data, flush=True))
    ros.spin()
""")


@pytest.mark.parametrize("behaviour", ["huge frame", "garbage header", "md5 mismatch", "missing type",
                                       "stall mid-frame", "bad string"])
def test_subscriber_survives_a_garbage_publisher(rostui_core: Any, ros_env: dict[str, str], behaviour: str) -> None:
    env = dict(ros_env, ROSTUI_TCPROS_STALL_TIMEOUT="1")

    async def scenario() -> None:
        evil = EvilPublisher(behaviour)
        raw = await asyncio.start_server(evil.serve, "127.0.0.1", 0)
        evil.port = raw.sockets[0].getsockname()[1]
        slave = XmlRpcServer(evil, "127.0.0.1", 0)
        await slave.start()
        good = await AsyncNode("good_pub").start()
        pub = await good.advertise("chatter", String)
        listener = await asyncio.create_subprocess_exec(
            sys.executable, "-c", LISTENER_SCRIPT, env=env, stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.STDOUT)
        try:
            await until(lambda: pub.get_num_connections() == 1, timeout=15)
            await asyncio.to_thread(call_sync, ros_env["ROS_MASTER_URI"], "registerPublisher", "/evil",
                                    "/chatter", "std_msgs/String", slave.uri)
            await until(lambda: evil.connections >= 1, timeout=15)
            await asyncio.sleep(1.5)  # let the stall timeout and retries happen
            pub.publish(String(data="still here"))
            assert listener.stdout is not None
            while True:
                line = (await asyncio.wait_for(listener.stdout.readline(), 15)).decode()
                assert line, "listener exited"
                if "got still here" in line:
                    break
            assert listener.returncode is None
        finally:
            listener.terminate()
            await listener.wait()
            await good.shutdown()
            await slave.close()
            raw.close()
    run(scenario(), timeout=60)


def test_frame_reader_checks_length_before_buffering() -> None:
    reader = FrameReader(max_frame=1000)
    assert reader.feed(frame(b"abc") + frame(b"") + b"\x02\x00") == [b"abc", b""]
    assert reader.pending == 2
    assert reader.feed(b"\x00\x00hi") == [b"hi"]
    with pytest.raises(FrameTooLargeError):
        FrameReader(max_frame=1000).feed(struct.pack("<I", 1001))
    with pytest.raises(HeaderError):
        decode_header(struct.pack("<I", 50) + b"x")
