"""Every buffer a peer fills has a bound; exceeding it drops that peer, never the process.

A rostui node in its own process (a publisher and a SetBool service, as a user writes them with the sync API)
is fed what a hostile or broken peer sends: requests pipelined on one persistent rosrpc connection faster than
they are answered (read or not), bytes streamed by a "subscriber" after its connection header, and a subscriber
that never reads what it is sent.  The node's memory is sampled throughout; a legitimate client is served
alongside; the victim stays alive.  No duration is asserted: the attacks are bounded in size and time, and only
what a user sees is checked.
"""

from __future__ import annotations

import asyncio
import socket
import struct
import subprocess
import sys
import textwrap
import threading
import time
from typing import Any, Iterator

import psutil
import pytest

from hostile.hostile_helpers import LegitClient, RssSampler
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node import AsyncNode
from rostui.core.tcpros import LEN, decode_header, encode_header, frame
from rostui.core.xmlrpc import call_sync

from conftest import stop_process
from test_node import run, until

String = get_message_class("std_msgs/String")
SetBool = get_service_class("std_srvs/SetBool")

#: Peak RSS growth allowed under attack: generous, far below what an unbounded buffer reaches.
GROWTH_LIMIT_MB = 100

VICTIM_SCRIPT = textwrap.dedent("""
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
    SetBool = ros.srv("std_srvs/SetBool")
    ros.init_node("victim")
    pub = ros.Publisher("chatter", String, queue_size=10)
    ros.Service("toggle", SetBool, lambda req: (True, "got true" if req.data else "got false"))
    print("ready", flush=True)
    rate = ros.Rate(50)
    while not ros.is_shutdown():
        pub.publish(String(data="alive"))
        rate.sleep()
""")


# -- raw TCPROS / rosrpc clients --------------------------------------------------------------------------
def recv_exactly(sock: socket.socket, size: int) -> bytes:
    """``size`` bytes from a socket; ConnectionError if it closes first."""
    chunks, left = [], size
    while left:
        chunk = sock.recv(min(left, 1 << 20))
        if not chunk:
            raise ConnectionError("peer closed the connection")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def read_header(sock: socket.socket) -> dict[str, str]:
    """One connection header from a socket."""
    (size,) = LEN.unpack(recv_exactly(sock, 4))
    return decode_header(recv_exactly(sock, size))


def rosrpc_open(port: int, service: str, *, persistent: bool) -> socket.socket:
    """A rosrpc connection to a SetBool service, past the header exchange."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=15)
    header = {"callerid": "/hostile", "service": service, "md5sum": SetBool._md5sum}
    if persistent:
        header["persistent"] = "1"
    sock.sendall(encode_header(header))
    reply = read_header(sock)
    assert "error" not in reply, reply
    return sock


def read_response(sock: socket.socket) -> Any:
    """One SetBool response from a rosrpc connection."""
    ok = recv_exactly(sock, 1)[0]
    (size,) = LEN.unpack(recv_exactly(sock, 4))
    body = recv_exactly(sock, size)
    assert ok == 1, body
    return SetBool._response_class.deserialize(body)


def setbool_call(port: int, service: str, data: bool = True) -> Any:
    """One SetBool call on a fresh connection, as rospy makes it."""
    with rosrpc_open(port, service, persistent=False) as sock:
        sock.sendall(frame(SetBool._request_class(data=data).serialize()))
        return read_response(sock)


def topic_port(master: str, topic: str) -> int:
    """The TCPROS port the (first) publisher of ``topic`` offers."""
    state = call_sync(master, "getSystemState", "/hostile")[2]
    node = dict((t, n) for t, n in state[0])[topic][0]
    uri = call_sync(master, "lookupNode", "/hostile", node)[2]
    return int(call_sync(uri, "requestTopic", "/hostile", topic, [["TCPROS"]])[2][2])


def subscribe_raw(port: int, topic: str) -> socket.socket:
    """A TCPROS connection subscribed to a std_msgs/String topic, past the header exchange."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=15)
    sock.sendall(encode_header({"callerid": "/hostile", "topic": topic, "md5sum": String._md5sum,
                                "type": "std_msgs/String"}))
    reply = read_header(sock)
    assert "error" not in reply, reply
    return sock


def take_one(port: int, topic: str) -> str:
    """Subscribe afresh and return the first message's text."""
    with subscribe_raw(port, topic) as sock:
        (size,) = LEN.unpack(recv_exactly(sock, 4))
        return str(String.deserialize(recv_exactly(sock, size)).data)


def stream(sock: socket.socket, chunk: bytes, limit: int, seconds: float) -> tuple[int, str]:
    """Send ``chunk`` over and over: at most ``limit`` bytes, for at most ``seconds``.

    Returns the bytes the victim's side accepted and how it ended: ``closed`` (the victim dropped us),
    ``limit`` or ``time`` (it never did; ``time`` when it stopped taking bytes or took too long).
    """
    sock.settimeout(0.2)
    sent, deadline = 0, time.monotonic() + seconds
    while sent < limit:
        if time.monotonic() > deadline:
            return sent, "time"
        try:
            sent += sock.send(chunk)
        except socket.timeout:
            continue
        except (BrokenPipeError, ConnectionResetError):
            return sent, "closed"
    return sent, "limit"


# -- the victim ----------------------------------------------------------------------------------------------
@pytest.fixture
def victim(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[tuple[subprocess.Popen, int, int]]:
    """A rostui node publishing /chatter and serving /toggle: the process, its rosrpc port and its topic port."""
    proc = subprocess.Popen([sys.executable, "-c", VICTIM_SCRIPT], env=ros_env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    master = ros_env["ROS_MASTER_URI"]
    try:
        deadline = time.monotonic() + 30
        while True:
            code, _, uri = call_sync(master, "lookupService", "/test", "/toggle")
            if code == 1:
                break
            assert proc.poll() is None, "the victim exited"
            assert time.monotonic() < deadline, "the victim never registered /toggle"
            time.sleep(0.05)
        yield proc, int(uri.rsplit(":", 1)[1]), topic_port(master, "/chatter")
    finally:
        stop_process(proc)


def wait_for_answers(legit: LegitClient, count: int, patience: float = 30.0) -> None:
    """Keep the attack going until the legitimate client has had ``count`` answers (or ``patience`` ran out)."""
    deadline = time.monotonic() + patience
    while len(legit.latencies) < count and time.monotonic() < deadline:
        time.sleep(0.05)


# -- 1. pipelined service requests ---------------------------------------------------------------------------
PIPELINE = b"".join(frame(SetBool._request_class(data=i % 2 == 0).serialize()) for i in range(50_000))


def test_pipelined_requests_not_read_keep_the_server_flat(victim: tuple[subprocess.Popen, int, int]) -> None:
    """Millions of requests on one connection whose client never reads: the server stops reading, not grows."""
    proc, port, _ = victim
    legit = LegitClient(lambda: setbool_call(port, "/toggle"))
    hostile = rosrpc_open(port, "/toggle", persistent=True)
    with hostile, RssSampler(proc.pid) as rss, legit:
        sent, how = stream(hostile, PIPELINE, limit=5 * 4_000_000, seconds=8.0)
        wait_for_answers(legit, 3)
    assert proc.poll() is None
    print(f"pipelined {sent // 5} requests ({how}); peak RSS growth {rss.growth_mb:.1f} MB; "
          f"legit {len(legit.latencies)} calls, median {legit.median_ms:.1f} ms")
    assert rss.growth_mb < GROWTH_LIMIT_MB
    assert not legit.failures, legit.failures[:3]
    assert setbool_call(port, "/toggle", False).message == "got false"


def test_pipelined_requests_are_all_answered_in_order(victim: tuple[subprocess.Popen, int, int]) -> None:
    """Flow control loses nothing: every pipelined request is answered, in order, while memory stays bounded."""
    proc, port, _ = victim
    count = 50_000
    requests = PIPELINE
    answers: list[str] = []
    errors: list[BaseException] = []

    def read_all(sock: socket.socket) -> None:
        try:
            for _ in range(count):
                answers.append(read_response(sock).message)
        except BaseException as exc:
            errors.append(exc)

    hostile = rosrpc_open(port, "/toggle", persistent=True)
    hostile.settimeout(60)
    reader = threading.Thread(target=read_all, args=(hostile,), daemon=True)
    with hostile, RssSampler(proc.pid) as rss:
        reader.start()
        hostile.sendall(requests)
        reader.join(120)
    assert not errors, errors
    assert len(answers) == count
    assert answers[:4] == ["got true", "got false", "got true", "got false"]
    assert all(a == ("got true" if i % 2 == 0 else "got false") for i, a in enumerate(answers))
    assert rss.growth_mb < GROWTH_LIMIT_MB
    assert proc.poll() is None


def test_pipelined_requests_in_process_answered_in_order(rostui_core: Any) -> None:
    """The same with an async handler in this process: the batches the connection hands over keep their order."""
    async def scenario() -> None:
        node = await AsyncNode("pipelined_server").start()
        seen: list[bool] = []

        async def handle(req: Any) -> Any:
            seen.append(req.data)
            await asyncio.sleep(0)
            return True, f"n{len(seen)}"
        server = await node.advertise_service("pipe", SetBool, handle)
        port = int(node.service_uri.rsplit(":", 1)[1])
        count = 30_000

        def client() -> list[str]:
            with rosrpc_open(port, "/pipe", persistent=True) as sock:
                sock.sendall(PIPELINE[: 5 * count])
                return [read_response(sock).message for _ in range(count)]
        try:
            answers = await asyncio.to_thread(client)
            assert answers == [f"n{i + 1}" for i in range(count)]
            assert seen == [i % 2 == 0 for i in range(count)]
            assert server.calls == count
        finally:
            await node.shutdown()
    run(scenario(), timeout=90)


# -- 2. bytes a subscriber sends after its header ----------------------------------------------------------------
def test_subscriber_streaming_after_its_header_is_dropped(victim: tuple[subprocess.Popen, int, int]) -> None:
    """A huge frame announced after the subscriber header, then hundreds of MB: the publisher drops the peer."""
    proc, _, port = victim
    legit = LegitClient(lambda: take_one(port, "/chatter"))
    hostile = subscribe_raw(port, "/chatter")
    hostile.sendall(struct.pack("<I", (1 << 30) - 1))
    with hostile, RssSampler(proc.pid) as rss, legit:
        sent, how = stream(hostile, bytes(1 << 20), limit=400 << 20, seconds=8.0)
        wait_for_answers(legit, 3)
    print(f"streamed {sent >> 20} MB after the header ({how}); peak RSS growth {rss.growth_mb:.1f} MB")
    assert proc.poll() is None
    assert how == "closed", f"the publisher took {sent >> 20} MB from a subscriber without dropping it"
    assert rss.growth_mb < GROWTH_LIMIT_MB
    assert legit.latencies and not legit.failures, legit.failures[:3]
    assert take_one(port, "/chatter") == "alive"


def test_subscriber_sending_whole_frames_after_its_header_is_dropped(
        victim: tuple[subprocess.Popen, int, int]) -> None:
    """Small well-formed frames are no better: a subscriber has nothing to send, and one that keeps sending goes."""
    proc, _, port = victim
    hostile = subscribe_raw(port, "/chatter")
    with hostile:
        sent, how = stream(hostile, frame(b"x" * 100), limit=256 << 20, seconds=8.0)
    assert how == "closed", f"the publisher took {sent >> 20} MB of frames from a subscriber without dropping it"
    assert proc.poll() is None
    assert take_one(port, "/chatter") == "alive"


def test_subscriber_that_sends_nothing_stays_connected(victim: tuple[subprocess.Popen, int, int]) -> None:
    """The ordinary subscriber keeps receiving (the drop is for peers that send, nothing else)."""
    _, _, port = victim
    with subscribe_raw(port, "/chatter") as sock:
        for _ in range(20):
            (size,) = LEN.unpack(recv_exactly(sock, 4))
            assert String.deserialize(recv_exactly(sock, size)).data == "alive"


def test_in_process_publisher_drops_a_chatty_subscriber(rostui_core: Any) -> None:
    """The publisher's count of subscribers falls back once a chatty one is dropped; a quiet one stays."""
    async def scenario() -> None:
        node = await AsyncNode("chatty_victim").start()
        pub = await node.advertise("chatter", String)
        port = node.tcpros_port
        try:
            quiet = await asyncio.to_thread(subscribe_raw, port, "/chatter")
            chatty = await asyncio.to_thread(subscribe_raw, port, "/chatter")
            await until(lambda: pub.get_num_connections() == 2)
            sent, how = await asyncio.to_thread(stream, chatty, bytes(4096), 64 << 20, 10.0)
            assert how == "closed", f"{sent} bytes taken"
            await until(lambda: pub.get_num_connections() == 1)
            pub.publish(String(data="still"))
            quiet.settimeout(10)
            (size,) = LEN.unpack(await asyncio.to_thread(recv_exactly, quiet, 4))
            assert String.deserialize(await asyncio.to_thread(recv_exactly, quiet, size)).data == "still"
            quiet.close()
            chatty.close()
        finally:
            await node.shutdown()
    run(scenario(), timeout=60)


# -- 3. a subscriber that never reads ------------------------------------------------------------------------------
def test_subscriber_that_never_reads_is_dropped_before_the_publisher_grows(rostui_core: Any) -> None:
    """No queue_size means no message is dropped for a slow subscriber, but its backlog still has a bound."""
    async def scenario() -> None:
        node = await AsyncNode("backlog_victim").start()
        pub = await node.advertise("big", String)
        try:
            stuck = await asyncio.to_thread(subscribe_raw, node.tcpros_port, "/big")
            await until(lambda: pub.get_num_connections() == 1)
            big = String(data="x" * 100_000)
            me = psutil.Process()
            before = peak = me.memory_info().rss
            for i in range(3000):  # 300 MB if nothing stopped it
                pub.publish(big)
                if i % 50 == 0:
                    peak = max(peak, me.memory_info().rss)
                    await asyncio.sleep(0)
                if pub.get_num_connections() == 0:
                    break
            await until(lambda: pub.get_num_connections() == 0)
            assert (peak - before) / (1 << 20) < GROWTH_LIMIT_MB
            stuck.close()
        finally:
            await node.shutdown()
    run(scenario(), timeout=60)


def test_queue_size_drops_old_messages_for_a_slow_subscriber_not_the_subscriber(rostui_core: Any) -> None:
    """With a queue_size, a subscriber that falls behind loses old messages (as in ROS) and stays connected."""
    async def scenario() -> None:
        node = await AsyncNode("queued_victim").start()
        pub = await node.advertise("queued", String, queue_size=5)
        try:
            slow = await asyncio.to_thread(subscribe_raw, node.tcpros_port, "/queued")
            await until(lambda: pub.get_num_connections() == 1)
            for i in range(2000):
                pub.publish(String(data=f"{i:06d}" + "y" * 100_000))
                if i % 50 == 0:
                    await asyncio.sleep(0)
            await asyncio.sleep(0.2)
            assert pub.get_num_connections() == 1
            assert pub.impl.links[0].dropped > 0
            slow.settimeout(10)
            last = ""
            while not last.startswith("001999"):
                (size,) = LEN.unpack(await asyncio.to_thread(recv_exactly, slow, 4))
                last = str(String.deserialize(await asyncio.to_thread(recv_exactly, slow, size)).data)
            slow.close()
        finally:
            await node.shutdown()
    run(scenario(), timeout=60)
