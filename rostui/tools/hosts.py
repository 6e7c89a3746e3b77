"""Whether an address is this host: loopback, or an address of one of its interfaces (as roslaunch decides)."""

from __future__ import annotations

import socket

import psutil

__all__ = ["local_addresses", "is_local_host"]


def local_addresses() -> set[str]:
    """Every address of this host's interfaces, plus ``localhost``."""
    found = {"localhost"}
    for addresses in psutil.net_if_addrs().values():
        for address in addresses:
            if address.family in (socket.AF_INET, socket.AF_INET6):
                found.add(address.address.split("%", 1)[0])
    return found


def is_local_host(host: str, addresses: set[str] | None = None) -> bool:
    """Whether ``host`` (a name or an address) resolves to this host: a loopback address or one of ``addresses``
    (default :func:`local_addresses`). A name that does not resolve is not this host."""
    try:
        resolved = {str(info[4][0]) for info in socket.getaddrinfo(host, 0, 0, 0, socket.SOL_TCP)}
    except (OSError, UnicodeError):
        return False
    mine = local_addresses() if addresses is None else addresses
    return any(ip.startswith("127.") or ip == "::1" for ip in resolved) or bool(resolved & mine) or host in mine
