"""Async XML-RPC for ROS 1: server, client, blocking helper and ROS result unwrapping.

Marshalling is the standard library's (``xmlrpc.client.dumps``/``loads``);
transport is asyncio streams speaking HTTP/1.1 with keep-alive and
``Content-Length`` framing.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from .blocking import call_sync
    from .client import XmlRpcClient
    from .marshal import EncodedResponse
    from .server import DEFAULT_MAX_BODY, XmlRpcServer

from .errors import RosApiError, XmlRpcConnectionError, XmlRpcError, XmlRpcFault, XmlRpcProtocolError
from .result import ros_result

_LAZY = {"XmlRpcClient": "client", "XmlRpcServer": "server", "DEFAULT_MAX_BODY": "server",
         "call_sync": "blocking", "EncodedResponse": "marshal"}


def __getattr__(name: str) -> Any:
    """Import the asyncio client and server, http.client and xmlrpc.client only when used.

    A command-line query that only needs :mod:`.quick` then starts without them.
    """
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from importlib import import_module

    value = getattr(import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value

__all__ = [
    "DEFAULT_MAX_BODY",
    "EncodedResponse",
    "RosApiError",
    "XmlRpcClient",
    "XmlRpcConnectionError",
    "XmlRpcError",
    "XmlRpcFault",
    "XmlRpcProtocolError",
    "XmlRpcServer",
    "call_sync",
    "ros_result",
]
