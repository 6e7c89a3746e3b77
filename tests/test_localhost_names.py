"""A machine that cannot resolve "localhost" (a Debian root made by debootstrap has no /etc/hosts) still reaches
its own master: localhost names mean the loopback address (RFC 6761), as the default ROS_MASTER_URI assumes."""

from __future__ import annotations

import asyncio
import socket
from typing import Any

import pytest

from conftest import free_port
from rostui.core import localhost
from rostui.core.master.embedded import ensure_master
from rostui.core.xmlrpc import XmlRpcClient, call_sync
from rostui.core.xmlrpc.quick import quick_call


@pytest.fixture
def no_hosts_file(monkeypatch: pytest.MonkeyPatch) -> None:
    """getaddrinfo knows no localhost name, as with no /etc/hosts."""
    real = socket.getaddrinfo

    def getaddrinfo(host: Any, *args: Any, **kwargs: Any) -> Any:
        if (host.decode() if isinstance(host, bytes) else host) in ("localhost", "ip6-localhost"):
            raise socket.gaierror(socket.EAI_NONAME, "Name or service not known")
        return real(host, *args, **kwargs)

    monkeypatch.setattr(socket, "getaddrinfo", getaddrinfo)
    monkeypatch.setattr(localhost, "_resolvable", {})


def test_a_master_at_localhost_starts_and_answers_every_client(no_hosts_file: None) -> None:
    uri = f"http://localhost:{free_port()}/"
    with pytest.raises(socket.gaierror):
        socket.getaddrinfo("localhost", None)

    async def scenario() -> tuple[Any, Any]:
        embedded = await ensure_master(uri)
        assert embedded is not None
        try:
            client = XmlRpcClient(uri)
            try:
                pid = await client.call("getPid", "/test")
            finally:
                await client.close()
            blocking = await asyncio.to_thread(call_sync, uri, "getPid", "/test")
            quick = await asyncio.to_thread(quick_call, uri, "getPid", "/test")
            return pid, (blocking, quick)
        finally:
            await embedded.stop()

    pid, (blocking, quick) = asyncio.run(scenario())
    assert pid[0] == 1 and blocking == pid and quick == pid


def test_a_resolvable_localhost_is_left_to_the_resolver(monkeypatch: pytest.MonkeyPatch) -> None:
    """Where /etc/hosts names localhost (perhaps as ::1 only), the resolver's answer stands."""
    monkeypatch.setattr(socket, "getaddrinfo", lambda *a, **k: [(socket.AF_INET6, socket.SOCK_STREAM, 6, "", ("::1", 0))])
    monkeypatch.setattr(localhost, "_resolvable", {})
    assert localhost.connect_host("localhost") == "localhost"
    assert localhost.connect_host("robot.example") == "robot.example"


@pytest.mark.parametrize("host", ["127.0.0.1", "127.0.0.255", "127.255.1.2", "10.0.0.1", "0.0.0.0", "192.168.1.1",
                                  "255.255.255.255", "127.1", "127.000.0.1", "127.0.0.01", "256.0.0.1", "1.2.3",
                                  "127.0.0.", "127.0.0.1 ", "\u0661\u0662\u0667.0.0.1", "::1", "::ffff:127.0.0.1",
                                  "fe80::1", "localhost", "robot.local"])
def test_loopback_hosts_as_ipaddress_says(host: str) -> None:
    """is_loopback_host reads dotted quads itself (no ipaddress import at a node's start) and agrees with
    ipaddress on every address, and on names (localhost's, or none of them)."""
    import ipaddress

    from rostui.core.network import is_loopback_host

    try:
        expected = ipaddress.ip_address(host).is_loopback
    except ValueError:
        expected = host in localhost.LOCALHOST_NAMES
    assert is_loopback_host(host) is expected
