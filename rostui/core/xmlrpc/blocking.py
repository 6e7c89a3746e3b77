"""A blocking XML-RPC call for command-line tools: stdlib only, no event loop, no asyncio import."""

from __future__ import annotations

import socket
import zlib
from typing import Any
from urllib.parse import urlsplit

from ..localhost import connect_host
from .errors import XmlRpcConnectionError, XmlRpcFault, XmlRpcProtocolError
from .marshal import Fault, decode_response, encode_call

__all__ = ["MAX_RESPONSE", "call_sync", "split_uri", "unwrap_response"]

#: Largest response body the clients accept (256 MiB).
MAX_RESPONSE = 256 * 1024 * 1024


def split_uri(uri: str) -> tuple[str, int, str]:
    """Host, port and path of an ``http://`` URI; XmlRpcConnectionError if it is not one."""
    parts = urlsplit(uri)
    if parts.scheme not in ("http", "") or not parts.hostname:
        raise XmlRpcConnectionError(uri, "not an http:// URI")
    try:
        port = parts.port or 80
    except ValueError:
        raise XmlRpcConnectionError(uri, "bad port in URI") from None
    return parts.hostname, port, parts.path or "/"


def unwrap_response(uri: str, body: bytes) -> Any:
    """The value of an XML-RPC response body; XmlRpcFault or XmlRpcProtocolError otherwise."""
    try:
        return decode_response(body)
    except Fault as fault:
        raise XmlRpcFault(fault.faultCode, fault.faultString, uri) from None
    except Exception as exc:
        raise XmlRpcProtocolError(uri, f"unparseable XML-RPC response: {exc}") from None


def call_sync(uri: str, method: str, *args: Any, timeout: float = 10.0) -> Any:
    """Call ``method(*args)`` on ``uri`` and block for the answer (no event loop).

    Raises the same exceptions as :meth:`XmlRpcClient.call`.
    """
    import http.client  # here: it imports email and ssl, which a node that only uses quick_call never needs

    host, port, path = split_uri(uri)
    body = encode_call(method, args)
    conn = http.client.HTTPConnection(connect_host(host), port, timeout=timeout)
    try:
        try:
            conn.request("POST", path, body, {"Content-Type": "text/xml", "User-Agent": "rostui-xmlrpc"})
            response = conn.getresponse()
            data = response.read(MAX_RESPONSE + 1)
        except ConnectionRefusedError:
            raise XmlRpcConnectionError(uri, "connection refused") from None
        except (socket.timeout, TimeoutError):
            raise XmlRpcConnectionError(uri, f"no answer to {method} within {timeout:g}s") from None
        except http.client.HTTPException as exc:
            raise XmlRpcProtocolError(uri, f"{type(exc).__name__}: {exc}") from None
        except OSError as exc:
            raise XmlRpcConnectionError(uri, exc.strerror or str(exc)) from None
    finally:
        conn.close()
    if response.status != 200:
        raise XmlRpcProtocolError(uri, f"HTTP {response.status} {response.reason}")
    if response.getheader("Content-Encoding", "").lower() in ("gzip", "x-gzip"):
        try:
            data = zlib.decompress(data, 16 + zlib.MAX_WBITS)
        except zlib.error as exc:
            raise XmlRpcProtocolError(uri, f"bad gzip body: {exc}") from None
    return unwrap_response(uri, data)
