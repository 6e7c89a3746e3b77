"""Where servers bind and which address a node advertises (ROS_IP, ROS_HOSTNAME).

Safe by default: when the master URI points at a loopback host and neither
ROS_IP nor ROS_HOSTNAME is set, every server binds 127.0.0.1 only.  Otherwise
servers bind all interfaces and advertise ROS_IP, ROS_HOSTNAME or the host name,
as ROS 1 does.
"""

from __future__ import annotations

import os
from typing import NamedTuple
from urllib.parse import urlparse

from .localhost import LOCALHOST_NAMES, connect_host
from .masteruri import DEFAULT_MASTER_URI, master_uri_from_env

__all__ = ["DEFAULT_MASTER_URI", "Addressing", "connect_host", "is_loopback_host", "master_uri_from_env",
           "resolve_addressing"]



def _dotted_quad_loopback(host: str) -> bool | None:
    """Whether a strict dotted-quad IPv4 address (as :func:`ipaddress.ip_address` takes one: four decimal
    octets up to 255, no leading zeros) is in 127.0.0.0/8; None for anything else."""
    parts = host.split(".")
    if len(parts) != 4:
        return None
    for part in parts:
        if not (part.isascii() and part.isdigit() and len(part) <= 3 and int(part) <= 255) or (
                len(part) > 1 and part[0] == "0"):
            return None
    return parts[0] == "127"


def is_loopback_host(host: str) -> bool:
    """True for localhost names and 127.0.0.0/8 or ::1 addresses."""
    if host in LOCALHOST_NAMES:
        return True
    quad = _dotted_quad_loopback(host)  # the common case, without importing ipaddress (1.3 ms of a node's start)
    if quad is not None:
        return quad
    import ipaddress

    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


class Addressing(NamedTuple):
    """The interface servers bind to and the host name they advertise in URIs."""

    bind_host: str
    advertise_host: str


def resolve_addressing(
    master_uri: str | None = None, ip: str | None = None, hostname: str | None = None
) -> Addressing:
    """Decide bind and advertised addresses from arguments and the environment.

    ``ip`` and ``hostname`` are the ``__ip:=`` / ``__hostname:=`` overrides;
    when absent ROS_IP and ROS_HOSTNAME are read.  ROS_HOSTNAME wins over
    ROS_IP, as in rospy.
    """
    ip = ip or os.environ.get("ROS_IP") or None
    hostname = hostname or os.environ.get("ROS_HOSTNAME") or None
    master_host = urlparse(master_uri_from_env(master_uri)).hostname or "localhost"
    if hostname is None and ip is None and is_loopback_host(master_host):
        return Addressing(bind_host="127.0.0.1", advertise_host="127.0.0.1")
    if hostname is None and ip is None:
        import socket

        hostname = socket.gethostname()
    advertise = hostname or ip or ""
    if is_loopback_host(advertise):
        return Addressing(bind_host="127.0.0.1" if ":" not in advertise else "::1",
                          advertise_host=advertise)
    return Addressing(bind_host="0.0.0.0", advertise_host=advertise)
