"""Hostile clients against XML-RPC ports: the master's and a node's slave API, rostui's and Debian's rosmaster.

Two attacks, each with the victim's memory sampled and a legitimate client calling ``getPid`` throughout:

- entity expansion behind a DTD, in UTF-8, UTF-16 and UTF-32 with and without a byte order mark: about 2 MB
  of request that expat would expand to 120 MB of text;
- a flood of idle connections, up to 1100, against a victim whose open-file limit is 1024.

rostui's victims must stay alive, stay within 100 MB of their memory before the attack and serve the
legitimate client without one failure.  rosmaster's figures are recorded for comparison, never asserted.
Everything runs on 127.0.0.1 with loops bounded in count and time.
"""

from __future__ import annotations

import resource
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from typing import Any, Iterator

import psutil
import pytest

from conftest import master_port, start_rostui_core, stop_process, wait_for_core, wait_until
from hostile_helpers import LegitClient, RssSampler, attack_figures, record
from rostui.core.xmlrpc import XmlRpcConnectionError, call_sync

VICTIM_NOFILE = 1024
FLOOD = 1100
OPEN_DEADLINE = 12.0  # seconds the flood may spend opening connections (rosmaster accepts slowly)
CONNECT_TIMEOUT = 3.0  # a SYN dropped on a full listen queue is sent again after 1 s
LEGIT_TIMEOUT = 3.5  # a legitimate call fails after this long (a dropped SYN is resent after 1 s and 3 s)
HOLD = 4.5  # seconds the flood holds its connections: longer than a legitimate call waits
RSS_BOUND_MB = 100

ENTITY = "A" * 240  # 80 times the 3 characters of "&a;": under expat's own amplification limit of 100
REFERENCES = 500_000  # 120 MB of expanded text
TRIES = 2

#: (test id, Python codec, encoding named in the XML declaration or None for no declaration)
BOMB_ENCODINGS = [
    ("utf-8", "utf-8", "UTF-8"),
    ("utf-8-bom", "utf-8-sig", None),
    ("utf-16-bom", "utf-16", "UTF-16"),
    ("utf-16le-nobom", "utf-16-le", "UTF-16"),
    ("utf-32-bom", "utf-32", "UTF-32"),
    ("utf-32le-nobom", "utf-32-le", "UTF-32"),
]


@dataclass
class Victim:
    """A process serving XML-RPC on ``port``: ``ours`` when rostui's, whose behaviour the tests assert."""

    name: str
    uri: str
    port: int
    pid: int
    ours: bool

    def alive(self) -> bool:
        """The process runs and answers getPid."""
        if not psutil.pid_exists(self.pid):
            return False
        try:
            return call_sync(self.uri, "getPid", "/hostile_check", timeout=10)[2] == self.pid
        except (XmlRpcConnectionError, OSError):
            return False


def lower_nofile() -> None:
    """preexec_fn: the victim gets a soft open-file limit of 1024 (the usual default)."""
    hard = resource.getrlimit(resource.RLIMIT_NOFILE)[1]
    resource.setrlimit(resource.RLIMIT_NOFILE, (VICTIM_NOFILE, hard))


NODE_SCRIPT = """
from rostui import client as ros
ros.init_node("xmlrpc_victim")
print(ros.get_node_uri(), flush=True)
ros.spin()
"""


def port_of(uri: str) -> int:
    """The port of an ``http://host:port/`` URI."""
    return int(uri.rstrip("/").rsplit(":", 1)[1])


@pytest.fixture(params=["rostui-master", "rostui-node", "rosmaster"])
def victim(request: pytest.FixtureRequest, ros_env: dict[str, str]) -> Iterator[Victim]:
    """rostui core's master port, a rostui node's slave API port (each at 1024 open files), or Debian's rosmaster."""
    port = master_port(ros_env)
    master_uri = f"http://127.0.0.1:{port}/"
    if request.param == "rosmaster":
        request.getfixturevalue("real_roscore")
        wait_until(lambda: _pid_answer(master_uri) > 0, "rosmaster to answer getPid")
        pid = _pid_answer(master_uri)
        hard = psutil.Process(pid).rlimit(psutil.RLIMIT_NOFILE)[1]
        psutil.Process(pid).rlimit(psutil.RLIMIT_NOFILE, (VICTIM_NOFILE, hard))
        yield Victim("rosmaster", master_uri, port, pid, ours=False)
        return
    if request.param == "rostui-master":
        core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=ros_env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=lower_nofile)
        try:
            wait_for_core(port, core)
            yield Victim("rostui-master", master_uri, port, core.pid, ours=True)
        finally:
            stop_process(core)
        return
    core = start_rostui_core(ros_env)
    node = subprocess.Popen([sys.executable, "-c", NODE_SCRIPT], env=ros_env, stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True, preexec_fn=lower_nofile)
    try:
        assert node.stdout is not None
        uri = node.stdout.readline().strip()
        assert uri.startswith("http://"), f"the victim node printed {uri!r}"
        yield Victim("rostui-node", uri, port_of(uri), node.pid, ours=True)
    finally:
        stop_process(node)
        stop_process(core)


def _pid_answer(uri: str) -> int:
    try:
        return int(call_sync(uri, "getPid", "/hostile_check", timeout=2)[2])
    except (XmlRpcConnectionError, OSError):
        return 0


def legit_client(victim: Victim) -> LegitClient:
    """A client calling getPid on the victim's port, with a fresh connection each time."""
    return LegitClient(lambda: call_sync(victim.uri, "getPid", "/legit", timeout=LEGIT_TIMEOUT))


def make_room_for_the_flood() -> None:
    """This test process opens FLOOD sockets: make sure its own open-file limit allows them."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    need = FLOOD + 256
    if soft != resource.RLIM_INFINITY and soft < need:
        if hard != resource.RLIM_INFINITY and hard < need:
            pytest.skip(f"the open-file limit ({hard}) cannot hold {FLOOD} connections")
        resource.setrlimit(resource.RLIMIT_NOFILE, (need, hard))


# -- entity expansion -------------------------------------------------------------------------------------------


def entity_bomb(codec: str, declared: str | None) -> bytes:
    """An HTTP request: getPid whose caller_id is ``&a;`` REFERENCES times, ``a`` declared in a DTD."""
    declaration = f'<?xml version="1.0" encoding="{declared}"?>' if declared else ""
    xml = (declaration + f'<!DOCTYPE m [<!ENTITY a "{ENTITY}">]><methodCall><methodName>getPid</methodName>'
           "<params><param><value><string>" + "&a;" * REFERENCES + "</string></value></param></params>"
           "</methodCall>").encode(codec)
    return (b"POST / HTTP/1.1\r\nContent-Type: text/xml\r\nContent-Length: %d\r\nConnection: close\r\n\r\n"
            % len(xml) + xml)


def exchange(port: int, request: bytes, timeout: float = 120.0) -> bytes:
    """Send ``request`` on a new connection; everything answered until the victim closes."""
    chunks = []
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        try:
            s.sendall(request)
            while chunk := s.recv(65536):
                chunks.append(chunk)
        except (ConnectionError, socket.timeout):
            pass
    return b"".join(chunks)


def outcome(reply: bytes) -> str:
    """What the attacker got back: a fault, an answer (the entities were expanded), an HTTP error, or nothing."""
    if not reply:
        return "no reply"
    status = reply.split(b" ", 2)[1].decode("latin-1") if reply.startswith(b"HTTP/") else "?"
    if status != "200":
        return f"http {status}"
    return "fault" if b"<fault>" in reply else "answered"


@pytest.mark.parametrize("codec, declared", [e[1:] for e in BOMB_ENCODINGS], ids=[e[0] for e in BOMB_ENCODINGS])
def test_entity_expansion(victim: Victim, codec: str, declared: str | None) -> None:
    request = entity_bomb(codec, declared)
    legit = legit_client(victim)
    with RssSampler(victim.pid) as rss, legit:
        outcomes = [outcome(exchange(victim.port, request)) for _ in range(TRIES)]
        time.sleep(0.2)  # the legitimate client calls once more after the last attack
    alive = victim.alive()
    figures: dict[str, Any] = attack_figures(rss, legit, TRIES)
    record(f"xmlrpc_entity_expansion[{codec}{'' if declared else ',no-decl'}]", victim.name, **figures,
           request_mb=round(len(request) / 2**20, 1), outcomes=outcomes, alive_after=alive)
    if not victim.ours:
        return
    assert alive
    assert all(o == "fault" or o.startswith("http 4") for o in outcomes), outcomes
    assert rss.growth_mb < RSS_BOUND_MB, figures
    assert legit.latencies and not legit.failures, legit.failures[:5]


# -- idle connection flood --------------------------------------------------------------------------------------


def idle_flood(port: int, pid: int) -> dict[str, int]:
    """Open up to FLOOD idle connections (for at most OPEN_DEADLINE seconds), hold them, then close them all.

    Also counts the descriptors the victim ``pid`` has open while the flood holds.
    """
    socks: list[socket.socket] = []
    failed = 0
    deadline = time.monotonic() + OPEN_DEADLINE
    try:
        for _ in range(FLOOD):
            if time.monotonic() > deadline:
                break
            try:
                socks.append(socket.create_connection(("127.0.0.1", port), timeout=CONNECT_TIMEOUT))
            except OSError:
                failed += 1
        time.sleep(HOLD)
        closed = sum(closed_by_peer(s) for s in socks)
        try:
            victim_fds = psutil.Process(pid).num_fds()
        except psutil.Error:
            victim_fds = -1
    finally:
        for s in socks:
            s.close()
    return {"opened": len(socks), "connect_failures": failed, "closed_by_victim": closed,
            "victim_fds_held": victim_fds}


def closed_by_peer(sock: socket.socket) -> bool:
    """True when the other end has closed or reset ``sock``."""
    sock.setblocking(False)
    try:
        return sock.recv(1, socket.MSG_PEEK) == b""
    except BlockingIOError:
        return False
    except OSError:
        return True


def test_idle_connection_flood(victim: Victim) -> None:
    make_room_for_the_flood()
    legit = legit_client(victim)
    with RssSampler(victim.pid) as rss, legit:
        time.sleep(0.2)  # served before the flood
        flood = idle_flood(victim.port, victim.pid)
    alive = victim.alive()
    figures: dict[str, Any] = attack_figures(rss, legit, flood["opened"] + flood["connect_failures"])
    nofile = psutil.Process(victim.pid).rlimit(psutil.RLIMIT_NOFILE)[0]
    record("xmlrpc_idle_flood", victim.name, **figures, **flood, victim_nofile=nofile, alive_after=alive)
    if not victim.ours:
        return
    assert alive
    assert flood["opened"] > VICTIM_NOFILE  # more than the victim could hold without closing some
    assert flood["closed_by_victim"] >= flood["opened"] - VICTIM_NOFILE // 2  # the oldest idle ones went
    assert rss.growth_mb < RSS_BOUND_MB, figures
    assert legit.latencies and not legit.failures, legit.failures[:5]
