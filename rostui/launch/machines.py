"""Which ``<machine>`` each node runs on, and whether that machine is this host, as roslaunch decides.

roslaunch calls a machine local when its address resolves to a loopback
address (``127.x``, ``::1``) or to an address of one of this host's
interfaces, and the machine names no ``user`` other than the one running
the launch; everything else is started over SSH.  ``--nodes``, ``--args``
and ``--dump-params`` never assign machines (roslaunch does not either), so
they work on files whose machines are far away or do not resolve at all.
"""

from __future__ import annotations

import getpass
import socket

from rostui.launch.errors import LaunchError
from rostui.launch.model import LaunchConfig, Machine
from rostui.tools.hosts import local_addresses

__all__ = ["assign_machines", "is_machine_local", "local_addresses", "resolve_address", "unknown_machine"]


def resolve_address(address: str) -> list[str]:
    """The IP addresses ``address`` resolves to; raises :class:`LaunchError` when it does not resolve."""
    try:
        infos = socket.getaddrinfo(address, 0, 0, 0, socket.SOL_TCP)
    except (socket.gaierror, UnicodeError):
        raise LaunchError(f"cannot resolve host address for machine [{address}]") from None
    return [str(info[4][0]) for info in infos if isinstance(info[4][0], str)]


def is_machine_local(machine: Machine, addresses: set[str] | None = None) -> bool:
    """True when ``machine`` is this host and needs no login as another user.

    Raises :class:`LaunchError` when the address does not resolve.
    """
    resolved = resolve_address(machine.address)
    mine = local_addresses() if addresses is None else addresses
    local = any(ip.startswith("127.") or ip == "::1" for ip in resolved) or bool(set(resolved) & mine)
    if local and machine.user:
        local = machine.user == getpass.getuser()
    return local


def unknown_machine(config: LaunchConfig) -> LaunchError | None:
    """The error for the first node naming a machine no ``<machine>`` declares, or None."""
    for node in config.all_nodes():
        if node.machine and node.machine not in config.machines:
            return LaunchError(f"unknown machine [{node.machine}] for node [{node.resolved_name}]",
                               node.filename, node.line)
    return None


def assign_machines(config: LaunchConfig) -> None:
    """Mark every machine ``local`` or not and every node and test ``remote`` or not.

    Raises :class:`LaunchError` (with the node's file and line) for a node
    naming an undeclared machine, or (with the ``<machine>``'s) for an
    address that does not resolve.
    """
    error = unknown_machine(config)
    if error is not None:
        raise error
    addresses = local_addresses()
    for node in config.all_nodes():
        machine = config.machine_of(node)
        if machine is None:
            node.remote = False
            continue
        if machine.local is None:
            try:
                machine.local = is_machine_local(machine, addresses)
            except LaunchError as exc:
                raise exc.located(machine.filename, machine.line) from None
        node.remote = not machine.local
