"""Shell tab-completion candidates for Typer arguments (``autocompletion=``).

Offline candidates (packages, executables, message and service types) come from
the package roots; live ones (topics, nodes, services, parameters) ask the
master with a short timeout and return an empty list on any failure, so a
missing master never breaks the shell.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterable, List

import typer

if TYPE_CHECKING:
    from rostui.tools.msgtypes import Kind

__all__ = [
    "complete_packages", "complete_executables", "complete_msg_types", "complete_srv_types",
    "complete_topics", "complete_nodes", "complete_services", "complete_params",
]

LIVE_TIMEOUT = 0.5
"""Seconds a live completion waits for the master."""


def _starting(candidates: Iterable[str], incomplete: str) -> List[str]:
    return sorted({c for c in candidates if c.startswith(incomplete)})


def complete_packages(incomplete: str) -> List[str]:
    """Package names (ROS_PACKAGE_PATH and built-in)."""
    try:
        from rostui.core.packages import list_packages

        return _starting(list_packages(), incomplete)
    except Exception:  # noqa: BLE001 - completion must never fail
        return []


def complete_executables(ctx: typer.Context, incomplete: str) -> List[str]:
    """Executables of the package given earlier on the command line."""
    try:
        from rostui.core.packages import list_executables

        package = (ctx.params or {}).get("package")
        return _starting(list_executables(package), incomplete) if package else []
    except Exception:  # noqa: BLE001
        return []


def _types(kind: Kind, incomplete: str) -> List[str]:
    try:
        from rostui.tools.msgtypes import list_types

        return _starting(list_types(kind), incomplete)
    except Exception:  # noqa: BLE001
        return []


def complete_msg_types(incomplete: str) -> List[str]:
    """Message types ``pkg/Name``."""
    return _types("msg", incomplete)


def complete_srv_types(incomplete: str) -> List[str]:
    """Service types ``pkg/Name``."""
    return _types("srv", incomplete)


def _master(method: str, *args: Any) -> Any:
    from rostui.core.network import master_uri_from_env
    from rostui.core.xmlrpc import call_sync, ros_result

    return ros_result(call_sync(master_uri_from_env(), method, "/rostui_complete", *args, timeout=LIVE_TIMEOUT))


def _state() -> list[Any]:
    try:
        return list(_master("getSystemState"))
    except Exception:  # noqa: BLE001
        return [[], [], []]


def complete_topics(incomplete: str) -> List[str]:
    """Topics that have a publisher or subscriber (live)."""
    pubs, subs, _ = _state()
    return _starting((t for t, _ in [*pubs, *subs]), incomplete)


def complete_nodes(incomplete: str) -> List[str]:
    """Registered node names (live)."""
    nodes: set[str] = set()
    for group in _state():
        for _, names in group:
            nodes.update(names)
    return _starting(nodes, incomplete)


def complete_services(incomplete: str) -> List[str]:
    """Service names (live)."""
    _, _, srvs = _state()
    return _starting((s for s, _ in srvs), incomplete)


def complete_params(incomplete: str) -> List[str]:
    """Parameter names (live)."""
    try:
        return _starting(_master("getParamNames"), incomplete)
    except Exception:  # noqa: BLE001
        return []
