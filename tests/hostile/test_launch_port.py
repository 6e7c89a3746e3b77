"""A hostile client against the launcher's XML-RPC port (the URI under ``/roslaunch/uris``).

Three bounded attacks, each from 127.0.0.1 only, while the launcher's memory is sampled and a legitimate
client keeps calling ``get_pid`` on the same port: garbage (broken HTTP, lying lengths, bad bodies), entity
expansion (billion laughs in UTF-8 and UTF-16, an external entity), and many idle or half-sent connections.
What a user would see is asserted (the launcher alive, its memory bounded, the legitimate client served);
times are recorded, never asserted.  The same attacks run against Debian's real roslaunch, whose figures
are recorded without assertions.
"""

from __future__ import annotations

import http.client
import random
import resource
import signal
import socket
import subprocess
import sys
import threading
import xmlrpc.client
from pathlib import Path
from typing import Callable, Iterator

import psutil
import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

from conftest import REPO, need_command, wait_until  # noqa: E402
from hostile_helpers import LegitClient, RssSampler, attack_figures, record  # noqa: E402
from launch_helpers import launch_env  # noqa: E402

HOST = "127.0.0.1"
MAX_GROWTH_MB = 100
SLEEPER = """#!/bin/sh
exec sleep 1000
"""
LAUNCH = """<launch>
  <node pkg="port_target" type="sleeper" name="sleeper"/>
</launch>
"""


def make_package(root: Path) -> None:
    pkg = root / "port_target"
    (pkg / "scripts").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text("<package format=\"2\"><name>port_target</name><version>0.0.0</version>"
                                     "<description>test</description><maintainer email=\"a@b.c\">t</maintainer>"
                                     "<license>BSD</license></package>\n")
    script = pkg / "scripts" / "sleeper"
    script.write_text(SLEEPER)
    script.chmod(0o755)
    (pkg / "launch" / "target.launch").write_text(LAUNCH)


class Victim:
    """A running launcher (rostui's or roslaunch) and the port of its XML-RPC server."""

    def __init__(self, label: str, argv: list[str], env: dict[str, str], tmp: Path) -> None:
        self.label = label
        self.env = env
        self.err_path = tmp / f"{label.replace(' ', '_')}.err"
        self.proc = subprocess.Popen(argv, env=env, cwd=REPO, stdout=subprocess.DEVNULL,
                                     stderr=self.err_path.open("w"), stdin=subprocess.DEVNULL,
                                     start_new_session=True)
        self.uri = ""
        wait_until(self._registered, f"{label} to register its XML-RPC server", timeout=90)
        self.port = int(self.uri.rstrip("/").rsplit(":", 1)[1])

    def _registered(self) -> bool:
        assert self.proc.poll() is None, f"{self.label} exited: {self.err_path.read_text()}"
        try:
            reply = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"]).getParam("/test", "/roslaunch/uris")
        except OSError:
            return False
        if reply[0] != 1 or not reply[2]:
            return False
        self.uri = str(next(iter(reply[2].values())))
        return True

    @property
    def alive(self) -> bool:
        try:
            return self.proc.poll() is None and psutil.Process(self.proc.pid).status() != psutil.STATUS_ZOMBIE
        except psutil.Error:
            return False

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=60)
            except subprocess.TimeoutExpired:
                pass
        try:
            group = [self.proc.pid, *(c.pid for c in psutil.Process(self.proc.pid).children(recursive=True))]
        except psutil.Error:
            group = []
        for pid in group:
            try:
                psutil.Process(pid).kill()
            except psutil.Error:
                pass
        self.proc.wait()


class _TimeoutTransport(xmlrpc.client.Transport):
    def make_connection(self, host: str) -> http.client.HTTPConnection:  # type: ignore[override]
        connection = super().make_connection(host)
        connection.timeout = 15.0
        return connection


def legit_call(port: int) -> Callable[[], None]:
    """One ``get_pid`` (roslaunch's API, which rostui's launcher answers too) on a new connection, checked."""
    def call() -> None:
        reply = xmlrpc.client.ServerProxy(f"http://{HOST}:{port}/", transport=_TimeoutTransport()).get_pid()
        if reply[0] != 1 or not isinstance(reply[2], int):
            raise AssertionError(f"bad get_pid reply {reply!r}")
    return call


# ----------------------------------------------------------------------------------------------- attacks

def _exchange(port: int, payload: bytes, wait: float = 2.0) -> bytes:
    """Send ``payload`` on a new connection and read what comes back within ``wait`` seconds."""
    with socket.create_connection((HOST, port), timeout=wait) as s:
        try:
            s.sendall(payload)
            s.shutdown(socket.SHUT_WR)
            chunks = []
            while sum(map(len, chunks)) < 1 << 20:
                chunk = s.recv(65536)
                if not chunk:
                    break
                chunks.append(chunk)
            return b"".join(chunks)
        except OSError:
            return b""


def _post(body: bytes, extra: bytes = b"", length: int | None = None) -> bytes:
    size = len(body) if length is None else length
    return (b"POST / HTTP/1.1\r\nHost: x\r\nContent-Type: text/xml\r\n" + extra
            + b"Content-Length: %d\r\n\r\n" % size + body)


def garbage_payloads() -> list[bytes]:
    rng = random.Random(7)
    call = b"<?xml version='1.0'?><methodCall><methodName>getPid</methodName><params>" \
           b"<param><value><string>/x</string></value></param></params></methodCall>"
    nested = b"<value><array><data>" * 5000 + b"</data></array></value>" * 5000
    return [
        bytes(rng.getrandbits(8) for _ in range(4096)),
        b"GET / HTTP/1.1\r\nHost: x\r\n\r\n",
        b"POST / HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\nabc",
        b"POST / HTTP/1.1\r\nContent-Length: -5\r\n\r\n",
        b"POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\nffffffff\r\nabc",
        b"POST / HTTP/1.1\r\nX-Long: " + b"a" * 200_000 + b"\r\n\r\n",
        b"\r\n" * 10_000,
        _post(b"this is not xml"),
        _post(b"\x1f\x8b" + bytes(64), extra=b"Content-Encoding: gzip\r\n"),
        _post(call.replace(b"getPid", b"no_such_method")),
        _post(call.replace(b"getPid", b"_private")),
        _post(b"<?xml version='1.0'?><methodCall><methodName>getPid</methodName><params><param>"
              + nested + b"</param></params></methodCall>"),
        _post(call, length=len(call) + 1000),  # the body never comes: the connection is closed under it
        _post(call)[: len(_post(call)) // 2],
    ]


def attack_garbage(port: int) -> int:
    tried = 0
    payloads = garbage_payloads()
    for _round in range(40):
        for payload in payloads:
            _exchange(port, payload, wait=2.0)
            tried += 1
    return tried


def entity_payloads() -> list[bytes]:
    laughs = ["<!ENTITY lol0 'lol'>"] + [f"<!ENTITY lol{i} '{('&lol%d;' % (i - 1)) * 10}'>" for i in range(1, 10)]
    # The entity is the method's name: a server that expanded it would say so in its "not supported" fault.
    text = ("<?xml version='1.0' encoding='{enc}'?><!DOCTYPE m [" + "".join(laughs) + "]>"
            "<methodCall><methodName>&lol9;</methodName><params></params></methodCall>")
    external = ("<?xml version='1.0'?><!DOCTYPE m [<!ENTITY x SYSTEM 'file:///etc/passwd'>]>"
                "<methodCall><methodName>&x;</methodName><params></params></methodCall>")
    # 10**5 "lol" (300 kB): small enough to pass expat's own amplification guard.
    medium = text.replace("&lol9;", "&lol5;")
    return [_post(text.format(enc="utf-8").encode("utf-8")),
            _post(text.format(enc="utf-16").encode("utf-16")),
            _post(medium.format(enc="utf-8").encode("utf-8")),
            _post(medium.format(enc="utf-16").encode("utf-16")),  # no b"<!DOCTYPE" in its bytes
            _post(external.encode())]


def attack_entities(port: int, expanded: list[bytes]) -> int:
    """Send the entity documents; a reply showing an expanded entity (or /etc/passwd) goes to ``expanded``."""
    tried = 0
    for _round in range(25):
        for payload in entity_payloads():
            reply = _exchange(port, payload, wait=10.0)
            if b"root:" in reply or b"lollollol" in reply:
                expanded.append(reply[:200])
            tried += 1
    return tried


def idle_budget() -> int:
    soft, _hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    return max(10, min(400, soft - 200))


def attack_idle(port: int, hold: threading.Event) -> int:
    """Open many connections (half of them mid-request) and keep them until ``hold`` is set."""
    sockets: list[socket.socket] = []
    try:
        for i in range(idle_budget()):
            try:
                s = socket.create_connection((HOST, port), timeout=5)
            except OSError:
                continue
            sockets.append(s)
            if i % 2:
                try:
                    s.sendall(b"POST / HTTP/1.1\r\nContent-Le")
                except OSError:
                    pass
        hold.wait(timeout=60)
        return len(sockets)
    finally:
        for s in sockets:
            s.close()


# ------------------------------------------------------------------------------------------------ runs

def run_attack(victim: Victim, name: str, attack: Callable[[], int]) -> dict[str, object]:
    """One attack with memory sampled and the legitimate client alongside; figures recorded and returned."""
    legit_call(victim.port)()  # served before
    with RssSampler(victim.proc.pid) as rss, LegitClient(legit_call(victim.port)) as legit:
        tried = attack()
        # A short attack may end before the first legitimate answer: let one come (or fail) inside the window.
        wait_until(lambda: bool(legit.latencies or legit.failures), "a legitimate call to end", timeout=60)
    final_failure = ""
    try:
        legit_call(victim.port)()  # and after
    except Exception as exc:  # the finding, whatever it is
        final_failure = f"{type(exc).__name__}: {exc}"
    figures = attack_figures(rss, legit, tried)
    figures.update(alive=victim.alive, served_after=not final_failure)
    if legit.failures:
        figures["first_legit_failure"] = legit.failures[0]
    record(f"launch_port_{name}", victim.label, **figures)
    figures["_failures"] = list(legit.failures) + ([final_failure] if final_failure else [])
    return figures


def run_idle(victim: Victim) -> dict[str, object]:
    hold = threading.Event()
    done: list[int] = []
    opener = threading.Thread(target=lambda: done.append(attack_idle(victim.port, hold)), daemon=True)

    def attack() -> int:
        opener.start()
        wait_until(lambda: len(psutil.Process(victim.proc.pid).net_connections(kind="tcp")) > idle_budget() // 2
                   or not opener.is_alive(), "the idle connections to be open", timeout=60)
        threading.Event().wait(3.0)  # the legitimate client runs while they are held
        hold.set()
        opener.join(timeout=60)
        return done[0] if done else 0

    return run_attack(victim, "idle", attack)


def assert_user_sees_nothing_wrong(figures: dict[str, object]) -> None:
    assert figures["alive"], "the launcher died"
    assert isinstance(figures["peak_rss_growth_mb"], float) and figures["peak_rss_growth_mb"] < MAX_GROWTH_MB
    assert figures["legit_calls"], "the legitimate client was never served during the attack"
    assert figures["served_after"], figures["_failures"]
    assert not figures["_failures"], figures["_failures"]


@pytest.fixture
def target_env(ros_env: dict[str, str], tmp_path: Path) -> dict[str, str]:
    """A local master, no ROS_IP (so rostui's server is on 127.0.0.1 only) and the target package."""
    env = launch_env(ros_env)
    env.pop("ROS_IP", None)
    env.pop("ROS_HOSTNAME", None)
    root = tmp_path / "pkgs"
    make_package(root)
    env["ROS_PACKAGE_PATH"] = f"{root}:{env['ROS_PACKAGE_PATH']}"
    return env


@pytest.fixture
def rostui_launch(target_env: dict[str, str], tmp_path: Path) -> Iterator[Victim]:
    victim = Victim("rostui launch", [sys.executable, "-m", "rostui", "launch", "port_target", "target.launch"],
                    target_env, tmp_path)
    yield victim
    victim.stop()


@pytest.fixture
def real_roslaunch(target_env: dict[str, str], tmp_path: Path) -> Iterator[Victim]:
    need_command("roslaunch")
    port = target_env["ROSTUI_TEST_MASTER_PORT"]
    victim = Victim("roslaunch", ["roslaunch", "-p", port, "port_target", "target.launch"], target_env, tmp_path)
    yield victim
    victim.stop()


def test_rostui_launch_port_survives_garbage(rostui_launch: Victim) -> None:
    assert_user_sees_nothing_wrong(run_attack(rostui_launch, "garbage", lambda: attack_garbage(rostui_launch.port)))


def test_rostui_launch_port_survives_entity_expansion(rostui_launch: Victim) -> None:
    expanded: list[bytes] = []
    figures = run_attack(rostui_launch, "entities", lambda: attack_entities(rostui_launch.port, expanded))
    assert_user_sees_nothing_wrong(figures)
    assert not expanded, expanded[0]  # a DTD is refused before any entity is declared


def test_rostui_launch_port_survives_idle_connections(rostui_launch: Victim) -> None:
    assert_user_sees_nothing_wrong(run_idle(rostui_launch))


def test_real_roslaunch_port_figures(real_roslaunch: Victim) -> None:
    """The same attacks against Debian's roslaunch: figures recorded, nothing asserted about them."""
    expanded: list[bytes] = []
    for name, attack in (("garbage", lambda: attack_garbage(real_roslaunch.port)),
                         ("entities", lambda: attack_entities(real_roslaunch.port, expanded))):
        if real_roslaunch.alive:
            run_attack(real_roslaunch, name, attack)
    if real_roslaunch.alive:
        run_idle(real_roslaunch)
    record("launch_port_entities_expanded", "roslaunch", replies_with_expansion=len(expanded))
