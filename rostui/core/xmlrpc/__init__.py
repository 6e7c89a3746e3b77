"""Async XML-RPC for ROS 1: server, client, blocking helper and ROS result unwrapping.

Marshalling is the standard library's (``xmlrpc.client.dumps``/``loads``);
transport is asyncio streams speaking HTTP/1.1 with keep-alive and
``Content-Length`` framing.
"""

from __future__ import annotations

from .client import XmlRpcClient, call_sync
from .errors import RosApiError, XmlRpcConnectionError, XmlRpcError, XmlRpcFault, XmlRpcProtocolError
from .marshal import EncodedResponse
from .result import ros_result
from .server import DEFAULT_MAX_BODY, XmlRpcServer

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
