"""rosservice's Python functions that scripts call: the services there are, and a service's type and class.

A service's type is asked of the service itself (the probe rosservice sends), as rosservice does. The
command line is ``rostui service``.
"""

from __future__ import annotations

import asyncio
from typing import Any

import rospy

from rostui.compat.lookup import get_service_class
from rostui.core.node.services import probe_service

__all__ = ["ROSServiceException", "ROSServiceIOException", "get_service_class_by_name", "get_service_list",
           "get_service_type", "get_service_uri"]

_CALLER = "/rosservice"


class ROSServiceException(Exception):
    """rosservice's error."""


class ROSServiceIOException(ROSServiceException):
    """The master or the service could not be reached."""


def _master(method: str, *args: Any) -> Any:
    try:
        code, message, value = getattr(rospy.get_master(), method)(*args)
    except Exception as exc:  # noqa: BLE001 (any failure to reach the master is one error)
        raise ROSServiceIOException(f"Unable to communicate with master: {exc}") from None
    return value if code == 1 else None


def get_service_list(node: str | None = None, namespace: str | None = None) -> list[str]:
    """Every service name (of ``node``, under ``namespace``), sorted."""
    state = _master("getSystemState")
    if state is None:
        return []
    names = [name for name, providers in state[2] if node is None or node in providers]
    if namespace:
        names = [n for n in names if n.startswith(namespace.rstrip("/") + "/") or n == namespace]
    return sorted(names)


def get_service_uri(service_name: str) -> str | None:
    """The rosrpc URI of ``service_name``, or None."""
    uri = _master("lookupService", rospy.resolve_name(service_name))
    return None if uri is None else str(uri)


def get_service_type(service_name: str) -> str | None:
    """The type the service reports when probed, or None when it is not available."""
    name = rospy.resolve_name(service_name)
    uri = get_service_uri(name)
    if not uri:
        return None
    try:
        header = asyncio.run(probe_service(uri, name, _CALLER, 5.0))
    except Exception as exc:  # noqa: BLE001 (a dead or odd server: rosservice's I/O error)
        raise ROSServiceIOException(f"Unable to communicate with service [{name}], address [{uri}]: {exc}") from None
    return header.get("type")


def get_service_class_by_name(service_name: str) -> Any:
    """The service class of ``service_name``, found by asking the service its type."""
    kind = get_service_type(service_name)
    if not kind:
        if rospy.resolve_name(service_name) not in get_service_list():
            raise ROSServiceException("Service [%s] is not available." % service_name)
        raise ROSServiceException("Unable to determine type of service [%s]." % service_name)
    try:
        return get_service_class(kind)
    except Exception:  # noqa: BLE001
        raise ROSServiceException("Unable to load type [%s].\nHave you typed 'make' in [%s]?"
                                  % (kind, kind.split("/")[0])) from None
