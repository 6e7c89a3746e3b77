"""A hostile client against a node's TCPROS publisher port and its rosrpc service port, on 127.0.0.1.

Each attack is bounded in size and time: requests pipelined on one persistent connection (the client reading
its answers or not), bytes streamed by a "subscriber" after its header, and garbage in place of a header or
after one.  Meanwhile the victim's memory is sampled and a legitimate subscriber or service client is served.

Against a rostui node the test asserts what a user sees: the victim alive, its memory bounded (generously),
the legitimate client served.  The same attacks run against rospy (Debian's, tests/peers/rospy_talker.py and
rospy_setbool_server.py); its figures are recorded with :func:`record` for comparison, never asserted.
No duration is asserted anywhere.
"""

from __future__ import annotations

import random
import socket
import struct
import sys
import textwrap
import threading
import time
from typing import Any, Callable, Iterator

import pytest

from hostile_helpers import LegitClient, RssSampler, attack_figures, record
from interop_helpers import Peer, Spawn, rospy_peer, rostui_peer, spawn  # noqa: F401  (spawn is a fixture)
from rostui.core.xmlrpc import call_sync

from conftest import have_rospy, need_peer
from test_node_hostile import (
    GROWTH_LIMIT_MB,
    PIPELINE,
    read_response,
    rosrpc_open,
    setbool_call,
    stream,
    subscribe_raw,
    take_one,
    topic_port,
    wait_for_answers,
)

#: Longest any one attack goes on.
ATTACK_SECONDS = 6.0

RANDOM = random.Random(1).randbytes(1 << 16)

ROSTUI_TALKER = textwrap.dedent("""
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
    ros.init_node("rostui_talker", anonymous=True)
    pub = ros.Publisher("/chatter", String, queue_size=10)
    print("ready", flush=True)
    rate = ros.Rate(100)
    n = 0
    while not ros.is_shutdown():
        pub.publish(String(data=f"hello {n}"))
        n += 1
        rate.sleep()
""")


class Victim:
    """A node under attack: its process, the port attacked and how a legitimate client uses it."""

    def __init__(self, library: str, peer: Peer, port: int, legit: Callable[[], Any]) -> None:
        self.library = library
        self.peer = peer
        self.port = port
        self.legit = legit

    @property
    def pid(self) -> int:
        """The victim's process id."""
        return self.peer.proc.pid

    def alive(self) -> bool:
        """True while the victim's process runs."""
        return self.peer.proc.poll() is None


@pytest.fixture(params=["rostui", "rospy"])
def library(request: pytest.FixtureRequest) -> str:
    """Which ROS library the victim is written with."""
    if request.param == "rospy":
        need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    return str(request.param)


def _wait_registered(master: str, check: Callable[[], bool], peer: Peer, what: str) -> None:
    deadline = time.monotonic() + 30
    while not check():
        assert peer.proc.poll() is None, f"{what} exited\n{peer.describe()}"
        assert time.monotonic() < deadline, f"{what} never registered\n{peer.describe()}"
        time.sleep(0.05)


def end_comparison_victim(peer: Peer, library: str) -> None:
    """Kill a rospy victim at once: nothing is asserted of it, and after an attack it can spend 10 s of a core
    on the junk it was sent before it notices the SIGINT that ends a rostui victim."""
    if library != "rostui" and peer.proc.poll() is None:
        peer.proc.kill()
        peer.proc.wait()


@pytest.fixture
def service_victim(library: str, rostui_core: Any, ros_env: dict[str, str], spawn: Spawn) -> Iterator[Victim]:
    """A std_srvs/SetBool server at /toggle."""
    argv = (rostui_peer("serve", "/toggle") if library == "rostui"
            else rospy_peer("rospy_setbool_server.py", "/toggle"))
    peer = spawn(argv, label=f"{library} SetBool server")
    peer.wait_for(r"^ready$")
    master = ros_env["ROS_MASTER_URI"]
    _wait_registered(master, lambda: call_sync(master, "lookupService", "/test", "/toggle")[0] == 1, peer,
                     "the SetBool server")
    port = int(call_sync(master, "lookupService", "/test", "/toggle")[2].rsplit(":", 1)[1])
    yield Victim(library, peer, port, lambda: setbool_call(port, "/toggle"))
    end_comparison_victim(peer, library)


@pytest.fixture
def topic_victim(library: str, rostui_core: Any, ros_env: dict[str, str], spawn: Spawn) -> Iterator[Victim]:
    """A std_msgs/String publisher on /chatter at 100 Hz."""
    argv = ([sys.executable, "-c", ROSTUI_TALKER] if library == "rostui"
            else rospy_peer("rospy_talker.py", "/chatter", "1000000", "100"))
    peer = spawn(argv, label=f"{library} talker")
    master = ros_env["ROS_MASTER_URI"]

    def published() -> bool:
        state = call_sync(master, "getSystemState", "/test")[2]
        return any(topic == "/chatter" for topic, _ in state[0])
    _wait_registered(master, published, peer, "the talker")
    port = topic_port(master, "/chatter")
    take_one(port, "/chatter")  # rospy_talker starts publishing once someone subscribes
    yield Victim(library, peer, port, lambda: take_one(port, "/chatter"))
    end_comparison_victim(peer, library)


def attack(name: str, victim: Victim, hit: Callable[[], dict[str, Any]]) -> tuple[RssSampler, LegitClient]:
    """Run ``hit`` (which returns its figures, ``tried`` among them) with the victim's memory sampled and a
    legitimate client served alongside; record the figures; return the sampler and the client."""
    legit = LegitClient(victim.legit)
    with RssSampler(victim.pid) as rss, legit:
        figures = hit()
        wait_for_answers(legit, 3)
    tried = figures.pop("tried")
    record(name, victim.library, **attack_figures(rss, legit, tried), **figures, alive=victim.alive())
    return rss, legit


def check_user_view(victim: Victim, rss: RssSampler, legit: LegitClient) -> None:
    """What a user of a rostui victim sees: still there, memory bounded, the legitimate client served.

    rospy's figures are only recorded."""
    if victim.library != "rostui":
        return
    assert victim.alive(), victim.peer.describe()
    assert rss.growth_mb < GROWTH_LIMIT_MB, f"peak RSS grew {rss.growth_mb:.1f} MB"
    assert legit.latencies, "the legitimate client was never served"
    assert not legit.failures, legit.failures[:3]
    victim.legit()


# -- the service port -----------------------------------------------------------------------------------------
def test_pipelined_requests_never_read(service_victim: Victim) -> None:
    """Up to four million requests on one persistent connection whose answers are never read."""
    def hit() -> dict[str, Any]:
        with rosrpc_open(service_victim.port, "/toggle", persistent=True) as sock:
            sent, how = stream(sock, PIPELINE, limit=5 * 4_000_000, seconds=ATTACK_SECONDS)
        return {"tried": sent // 5, "ended": how}
    check_user_view(service_victim, *attack("pipelined requests, answers not read", service_victim, hit))


def test_pipelined_requests_read(service_victim: Victim) -> None:
    """Requests pipelined as fast as the victim takes them, its answers read as fast as it sends them."""
    def hit() -> dict[str, Any]:
        answered = [0]
        stop = threading.Event()

        def drain(sock: socket.socket) -> None:
            try:
                while not stop.is_set():
                    read_response(sock)
                    answered[0] += 1
            except (OSError, ConnectionError):
                pass
        with rosrpc_open(service_victim.port, "/toggle", persistent=True) as sock:
            reader = threading.Thread(target=drain, args=(sock,), daemon=True)
            reader.start()
            sent, how = stream(sock, PIPELINE, limit=5 * 4_000_000, seconds=ATTACK_SECONDS)
            stop.set()
            sock.shutdown(socket.SHUT_RDWR)
            reader.join(10)
        return {"tried": sent // 5, "answered": answered[0], "ended": how}
    check_user_view(service_victim, *attack("pipelined requests, answers read", service_victim, hit))


def huge_header_length(victim: Victim, name: str) -> None:
    """A header length of 2 GiB on ``victim``'s port, then junk streamed as if to fill it."""
    def hit() -> dict[str, Any]:
        with socket.create_connection(("127.0.0.1", victim.port), timeout=15) as sock:
            sock.sendall(struct.pack("<I", 0x7FFFFFFF))
            sent, how = stream(sock, RANDOM, limit=64 << 20, seconds=ATTACK_SECONDS)
        return {"tried": 1, "sent_mb": sent >> 20, "ended": how}
    check_user_view(victim, *attack(name, victim, hit))


def test_service_header_length_far_over_any_header(service_victim: Victim) -> None:
    """A header length of 2 GiB, then junk streamed as if to fill it."""
    huge_header_length(service_victim, "service port: huge header length, then junk")


def test_junk_after_a_service_header(service_victim: Victim) -> None:
    """Random bytes (16 MB) after a valid persistent service header: junk lengths and junk requests."""
    def hit() -> dict[str, Any]:
        with rosrpc_open(service_victim.port, "/toggle", persistent=True) as sock:
            sent, how = stream(sock, RANDOM, limit=16 << 20, seconds=ATTACK_SECONDS)
        return {"tried": 1, "sent_mb": sent >> 20, "ended": how}
    check_user_view(service_victim, *attack("service port: junk after a valid header", service_victim, hit))


# -- the publisher port -------------------------------------------------------------------------------------------
def test_bytes_streamed_after_a_subscriber_header(topic_victim: Victim) -> None:
    """A "subscriber" announces a frame just under 1 GiB after its header and streams up to 400 MB."""
    def hit() -> dict[str, Any]:
        with subscribe_raw(topic_victim.port, "/chatter") as sock:
            sock.sendall(struct.pack("<I", (1 << 30) - 1))
            sent, how = stream(sock, bytes(1 << 20), limit=400 << 20, seconds=ATTACK_SECONDS)
        return {"tried": 1, "sent_mb": sent >> 20, "ended": how}
    rss, legit = attack("publisher port: bytes streamed after a subscriber header", topic_victim, hit)
    check_user_view(topic_victim, rss, legit)


def test_topic_header_length_far_over_any_header(topic_victim: Victim) -> None:
    """A header length of 2 GiB on the publisher port, then junk streamed as if to fill it."""
    huge_header_length(topic_victim, "publisher port: huge header length, then junk")


def test_many_connections_of_garbage(topic_victim: Victim) -> None:
    """Two hundred connections, each sending 64 KiB of random bytes and leaving (bounded in time)."""
    def hit() -> dict[str, Any]:
        deadline = time.monotonic() + ATTACK_SECONDS
        tried = 0
        for _ in range(200):
            if time.monotonic() > deadline:
                break
            try:
                with socket.create_connection(("127.0.0.1", topic_victim.port), timeout=2) as sock:
                    sock.settimeout(2)
                    sock.sendall(RANDOM)
            except OSError:
                pass
            tried += 1
        return {"tried": tried}
    check_user_view(topic_victim, *attack("publisher port: connections of random bytes", topic_victim, hit))
