"""The lightest blocking XML-RPC call, for one-shot command-line queries.

``quick_call`` speaks HTTP/1.1 on a plain socket and reads the response with
pyexpat, so a command that asks the master one question starts without
``http.client``, ``xmlrpc.client`` or ``urllib`` (together more than the query
itself costs).  It only ever shortcuts the commonest case: string arguments, a
``200`` answer with a ``Content-Length`` body, and a reply made of arrays,
strings, integers and booleans.  Any other answer is handed to the standard
decoder (:func:`~rostui.core.xmlrpc.blocking.unwrap_response`), and any HTTP
surprise repeats the call through :func:`~rostui.core.xmlrpc.blocking.call_sync`,
so callers see exactly the values and exceptions ``call_sync`` gives.
"""

from __future__ import annotations

import socket

from ..localhost import connect_host
from .errors import XmlRpcConnectionError
from .safexml import forbid_dtd

__all__ = ["quick_call"]

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

_HEAD_LIMIT = 64 * 1024
_ESCAPES = {ord("&"): "&amp;", ord("<"): "&lt;", ord(">"): "&gt;"}
_INT_TAGS = ("int", "i4", "i8")
#: Where each element of a simple answer may sit ("" is the document itself).
_PARENTS = {"methodResponse": ("",), "params": ("methodResponse",), "param": ("params",),
            "value": ("param", "data"), "array": ("value",), "data": ("array",), "string": ("value",),
            "boolean": ("value",), "int": ("value",), "i4": ("value",), "i8": ("value",)}


class _NotSimple(Exception):
    """The answer holds something this module leaves to the standard decoder."""


def _split_http_uri(uri: str) -> tuple[str, int, str] | None:
    """Host, port and path of ``http://host:port/path`` with a plain host; None for anything else."""
    if not uri.startswith("http://"):
        return None
    netloc, _, path = uri[7:].partition("/")
    host, sep, port = netloc.rpartition(":")
    if not sep or not host or not port.isdigit() or any(c in host for c in "[]@%:"):
        return None
    number = int(port)
    if not 0 < number < 65536:
        return None
    return host, number, "/" + path


def _encode_call(method: str, args: tuple[str, ...]) -> bytes:
    params = "".join(f"<param><value><string>{a.translate(_ESCAPES)}</string></value></param>" for a in args)
    return (f"<?xml version='1.0'?>\n<methodCall><methodName>{method}</methodName>"
            f"<params>{params}</params></methodCall>\n").encode("utf-8")


def _decode_simple(body: bytes) -> Any:
    """The value of a ``<methodResponse>`` of arrays, strings, ints and booleans; _NotSimple otherwise."""
    if b"<!" in body:  # DTDs, entity declarations and CDATA: the standard decoder decides
        raise _NotSimple  # (a DTD in another encoding hides from this test: expat refuses it below)
    import pyexpat

    values: list[list[Any]] = [[]]  # open arrays; the outermost collects the response's params
    path: list[str] = [""]
    has_child: list[bool] = [False]
    text: list[str] = []

    def start(tag: str, attrs: dict[str, str]) -> None:
        if attrs or path[-1] not in _PARENTS.get(tag, ()):
            raise _NotSimple
        has_child[-1] = True
        path.append(tag)
        has_child.append(False)
        text.clear()
        if tag == "array":
            values.append([])

    def end(tag: str) -> None:
        path.pop()
        leaf = not has_child.pop()
        data = "".join(text)
        text.clear()
        if tag == "array":
            done = values.pop()
            values[-1].append(done)
        elif tag == "string" or (tag == "value" and leaf):  # an untyped <value> is a string
            values[-1].append(data)
        elif tag in _INT_TAGS:
            values[-1].append(int(data))
        elif tag == "boolean":
            if data not in ("0", "1"):
                raise _NotSimple
            values[-1].append(data == "1")

    parser = pyexpat.ParserCreate()
    parser.buffer_text = True
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = text.append
    forbid_dtd(parser)  # UnsafeXmlError, a ValueError: the standard decoder refuses it too
    try:
        parser.Parse(body, True)
    except (pyexpat.ExpatError, ValueError):
        raise _NotSimple from None
    if len(values) != 1 or len(values[0]) != 1:
        raise _NotSimple
    return values[0][0]


def _exchange(host: str, port: int, request: bytes, timeout: float) -> tuple[bytes, bytes] | None:
    """Send ``request``; the response head and body, or None when the answer is not a plain 200."""
    address = host.encode("ascii") if host.isascii() else host  # bytes: no idna codec import
    # typeshed wants a str host; getaddrinfo takes bytes as well
    with socket.create_connection((address, port), timeout=timeout) as sock:  # type: ignore[arg-type]
        sock.sendall(request)
        data = b""
        while b"\r\n\r\n" not in data:
            chunk = sock.recv(65536)
            if not chunk or len(data) > _HEAD_LIMIT:
                return None
            data += chunk
        head, _, body = data.partition(b"\r\n\r\n")
        lines = head.split(b"\r\n")
        status = lines[0].split(None, 2)
        if len(status) < 2 or not status[0].startswith(b"HTTP/1.") or status[1] != b"200":
            return None
        length = None
        for line in lines[1:]:
            name, _, value = line.partition(b":")
            name = name.strip().lower()
            if name == b"content-length" and value.strip().isdigit():
                length = int(value)
            elif name in (b"transfer-encoding", b"content-encoding"):
                return None
        if length is None or length > 16 * 1024 * 1024:
            return None
        while len(body) < length:
            chunk = sock.recv(max(65536, length - len(body)))
            if not chunk:
                return None
            body += chunk
        return head, body[:length]


def quick_call(uri: str, method: str, *args: str, timeout: float = 10.0) -> Any:
    """Call ``method(*args)`` (all strings) on ``uri``; same result and exceptions as ``call_sync``."""
    where = _split_http_uri(uri)
    if where is None:
        return _full_call(uri, method, args, timeout)
    host, port, path = where
    body = _encode_call(method, args)
    request = (f"POST {path} HTTP/1.1\r\nHost: {host}:{port}\r\nUser-Agent: rostui-xmlrpc\r\n"
               f"Content-Type: text/xml\r\nContent-Length: {len(body)}\r\nConnection: close\r\n\r\n"
               ).encode("latin-1") + body
    try:
        answer = _exchange(connect_host(host), port, request, timeout)
    except ConnectionRefusedError:
        raise XmlRpcConnectionError(uri, "connection refused") from None
    except (socket.timeout, TimeoutError):
        raise XmlRpcConnectionError(uri, f"no answer to {method} within {timeout:g}s") from None
    except OSError as exc:
        raise XmlRpcConnectionError(uri, exc.strerror or str(exc)) from None
    if answer is None:
        return _full_call(uri, method, args, timeout)
    try:
        return _decode_simple(answer[1])
    except _NotSimple:
        from .blocking import unwrap_response

        return unwrap_response(uri, answer[1])


def _full_call(uri: str, method: str, args: tuple[str, ...], timeout: float) -> Any:
    from .blocking import call_sync

    return call_sync(uri, method, *args, timeout=timeout)
