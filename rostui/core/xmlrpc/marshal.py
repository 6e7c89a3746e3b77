"""XML-RPC (de)serialisation with the standard library, plus small guards.

Values round-trip as built-in Python types (``bytes`` for base64,
``datetime`` for dateTime.iso8601) and ``None`` is allowed as ``<nil/>``.
Documents with a DTD are refused: XML-RPC never needs one, and entity
declarations are the usual way to attack an XML parser.
"""

from __future__ import annotations

import xmlrpc.client as _xc
from typing import Any

Fault = _xc.Fault


class UnsafeXmlError(ValueError):
    """The document holds a DTD or entity declaration, which XML-RPC never needs."""


def _check_safe(body: bytes) -> None:
    if b"<!DOCTYPE" in body or b"<!ENTITY" in body:
        raise UnsafeXmlError("DTD and entity declarations are not allowed")


def encode_call(method: str, params: tuple[Any, ...]) -> bytes:
    """Serialise a ``<methodCall>`` document."""
    return _xc.dumps(params, method, allow_none=True).encode("utf-8")


def decode_call(body: bytes) -> tuple[tuple[Any, ...], str]:
    """Parse a ``<methodCall>``: return ``(params, method_name)``."""
    _check_safe(body)
    params, method = _xc.loads(body, use_builtin_types=True)
    if not isinstance(method, str) or not method:
        raise ValueError("methodCall without methodName")
    return params, method


def encode_response(value: Any) -> bytes:
    """Serialise a successful ``<methodResponse>`` holding ``value``."""
    return _xc.dumps((value,), methodresponse=True, allow_none=True).encode("utf-8")


def encode_fault(code: int, string: str) -> bytes:
    """Serialise a ``<methodResponse>`` holding a fault."""
    return _xc.dumps(_xc.Fault(code, string), methodresponse=True, allow_none=True).encode("utf-8")


def decode_response(body: bytes) -> Any:
    """Parse a ``<methodResponse>``; a fault raises :class:`xmlrpc.client.Fault`."""
    _check_safe(body)
    (value,) = _xc.loads(body, use_builtin_types=True)[0]
    return value


def exception_fault_string(exc: BaseException) -> str:
    """The fault string Python's SimpleXMLRPCServer (and so rosmaster) sends for ``exc``."""
    return f"{type(exc)}:{exc}"
