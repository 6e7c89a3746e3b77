"""Connecting to localhost names on a machine that cannot resolve them (a root with no /etc/hosts).

Imported by the fast command-line paths: the standard library's ``socket`` only, and only when asked.
"""

from __future__ import annotations

__all__ = ["LOCALHOST_NAMES", "connect_host"]

#: The names of this machine's loopback interface.
LOCALHOST_NAMES = ("localhost", "localhost.localdomain", "ip6-localhost")

_resolvable: dict[str, bool] = {}


def connect_host(host: str) -> str:
    """The host to connect to for ``host`` from a URI: itself, except a localhost name this machine cannot
    resolve, which is the loopback address it always means (RFC 6761)."""
    if host not in LOCALHOST_NAMES:
        return host
    known = _resolvable.get(host)
    if known is None:
        import socket

        try:
            socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
            known = True
        except OSError:
            known = False
        _resolvable[host] = known
    return host if known else ("::1" if host == "ip6-localhost" else "127.0.0.1")
