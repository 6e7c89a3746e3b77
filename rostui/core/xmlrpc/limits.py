"""What one XML-RPC port grants a peer: timeouts and a connection cap, each settable from the environment.

Every port (the master's and each node's slave API) gets the same limits:

- ``ROSTUI_XMLRPC_IDLE_TIMEOUT`` (seconds, default 60): how long a connection may
  sit without starting a request, before its first one or between keep-alive
  requests.  rospy, roscpp and rostui clients reconnect when an idle
  keep-alive connection was closed, so nobody notices.
- ``ROSTUI_XMLRPC_REQUEST_TIMEOUT`` (seconds, default 60): how long a request's
  header and body may take to arrive once its first byte has.
- ``ROSTUI_XMLRPC_MAX_CONNECTIONS`` (default: half the open-file limit, at most
  4096): how many connections are served at once.  One more closes the
  connection that has been idle longest (then the oldest unfinished request),
  so a flood of idle sockets costs its sender, not the next client.

The listen queue holds 512 connections, or a quarter of a low open-file limit,
so that the cap plus one accept burst stays well under that limit.  A value that is missing, not a number or not positive means the default.
"""

from __future__ import annotations

import os

__all__ = [
    "DEFAULT_IDLE_TIMEOUT", "DEFAULT_REQUEST_TIMEOUT", "MAX_CONNECTIONS_CEILING",
    "default_max_connections", "idle_timeout_from_env", "listen_backlog", "max_connections_from_env",
    "open_file_limit", "request_timeout_from_env",
]

DEFAULT_IDLE_TIMEOUT = 60.0
DEFAULT_REQUEST_TIMEOUT = 60.0
#: The default connection cap never exceeds this, however high the open-file limit.
MAX_CONNECTIONS_CEILING = 4096
_MIN_CONNECTIONS = 16
_MAX_BACKLOG = 512


def _positive_float(name: str, default: float) -> float:
    raw = os.environ.get(name)
    try:
        value = float(raw) if raw else default
    except ValueError:
        return default
    return value if value > 0 and value != float("inf") else default


def idle_timeout_from_env() -> float:
    """Seconds a connection may wait without starting a request: ROSTUI_XMLRPC_IDLE_TIMEOUT, default 60."""
    return _positive_float("ROSTUI_XMLRPC_IDLE_TIMEOUT", DEFAULT_IDLE_TIMEOUT)


def request_timeout_from_env() -> float:
    """Seconds a request's header and body may take: ROSTUI_XMLRPC_REQUEST_TIMEOUT, default 60."""
    return _positive_float("ROSTUI_XMLRPC_REQUEST_TIMEOUT", DEFAULT_REQUEST_TIMEOUT)


def open_file_limit() -> int | None:
    """This process's soft RLIMIT_NOFILE, or None when unlimited or unknown."""
    try:
        import resource
    except ImportError:  # pragma: no cover - non-Unix
        return None
    soft, _hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    return None if soft == resource.RLIM_INFINITY else soft


def default_max_connections() -> int:
    """Half the open-file limit (the rest is for accept bursts, outgoing calls, TCPROS and files), capped."""
    limit = open_file_limit()
    if limit is None:
        return MAX_CONNECTIONS_CEILING
    return max(_MIN_CONNECTIONS, min(MAX_CONNECTIONS_CEILING, limit // 2))


def max_connections_from_env() -> int:
    """Connections one port serves at once: ROSTUI_XMLRPC_MAX_CONNECTIONS, default :func:`default_max_connections`."""
    raw = os.environ.get("ROSTUI_XMLRPC_MAX_CONNECTIONS")
    if raw and raw.isdigit() and int(raw) > 0:
        return int(raw)
    return default_max_connections()


def listen_backlog() -> int:
    """The listen queue: 512, or a quarter of a low open-file limit (an accept burst needs a descriptor each)."""
    limit = open_file_limit()
    if limit is None:
        return _MAX_BACKLOG
    return max(_MIN_CONNECTIONS, min(_MAX_BACKLOG, limit // 4))
