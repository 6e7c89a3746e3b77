"""``rostui node machine [HOST]``: the hosts nodes run on, or the nodes of one host (like ``rosnode machine``).

A node's host is the host part of its XML-RPC URI.  Given a HOST, a node is
on it when its URI's host is HOST or resolves to one of HOST's addresses.
"""

from __future__ import annotations

import socket
from urllib.parse import urlsplit

from rostui.tools.node import Call, lookup_uris, system_state


class MachineError(Exception):
    """The HOST given cannot be resolved."""


def _host_of(uri: str) -> str | None:
    try:
        return urlsplit(uri).hostname
    except ValueError:
        return None


def _addresses(host: str) -> set[str]:
    try:
        from rostui.core.localhost import connect_host

        return {str(info[4][0]) for info in socket.getaddrinfo(connect_host(host), 0, 0, 0, socket.SOL_TCP)}
    except (OSError, UnicodeError):
        return set()


def machines(call: Call) -> list[str]:
    """Every host a registered node's URI names, sorted (rosnode sorts them as text)."""
    hosts = {_host_of(uri) for uri in lookup_uris(call, system_state(call).nodes()).values() if uri}
    return sorted(h for h in hosts if h)


def nodes_on(call: Call, machine: str) -> list[str]:
    """The registered nodes whose URI's host is ``machine`` or shares an address with it, sorted.

    Raises :class:`MachineError` when ``machine`` does not resolve.
    """
    wanted = _addresses(machine)
    if not wanted:
        raise MachineError(f"cannot resolve machine name [{machine}] to address")
    found: list[str] = []
    resolved: dict[str, set[str]] = {}
    for node, uri in lookup_uris(call, system_state(call).nodes()).items():
        host = _host_of(uri) if uri else None
        if host is None:
            continue
        if host == machine or host in wanted:
            found.append(node)
            continue
        if host not in resolved:
            resolved[host] = _addresses(host)
        if resolved[host] & wanted:
            found.append(node)
    return sorted(found)
