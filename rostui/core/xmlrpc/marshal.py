"""XML-RPC (de)serialisation with the standard library, plus small guards.

Values round-trip as built-in Python types (``bytes`` for base64,
``datetime`` for dateTime.iso8601) and ``None`` is allowed as ``<nil/>``.
Documents with a DTD are refused whatever their encoding (UTF-8, UTF-16,
UTF-32, with or without a byte order mark): expat itself reports the
``<!DOCTYPE`` and parsing stops there, before any entity is declared, let
alone expanded.  XML-RPC never needs a DTD, and entity declarations are the
usual way to make an XML parser allocate without bound.
"""

from __future__ import annotations

import re
import xmlrpc.client as _xc
from typing import Any
from xml.parsers import expat

from .safexml import UnsafeXmlError, forbid_dtd

__all__ = ["EncodedResponse", "Fault", "UnsafeXmlError", "decode_call", "decode_response", "encode_call",
           "encode_fault", "encode_response", "exception_fault_string"]

Fault = _xc.Fault


def _loads(body: bytes) -> tuple[tuple[Any, ...], str | None]:
    """``xmlrpc.client.loads(body, use_builtin_types=True)`` on a parser that refuses DTDs."""
    target = _xc.Unmarshaller(use_builtin_types=True)
    parser = expat.ParserCreate()
    parser.StartElementHandler = target.start
    parser.EndElementHandler = target.end
    parser.CharacterDataHandler = target.data
    forbid_dtd(parser)
    target.xml("", None)  # what xmlrpc.client.ExpatParser tells it: expat already hands out str
    parser.Parse(body, True)
    return target.close(), target.getmethodname()


class EncodedResponse:
    """A complete, already serialised ``<methodResponse>``.

    A server method may return one to skip marshalling (e.g. a cached answer
    to a large, unchanged query); clients see an ordinary response.
    """

    __slots__ = ("body",)

    def __init__(self, value: Any) -> None:
        self.body = encode_response(value)


def encode_call(method: str, params: tuple[Any, ...]) -> bytes:
    """Serialise a ``<methodCall>`` document."""
    return _xc.dumps(params, method, allow_none=True).encode("utf-8")


# Fast path for the calls that dominate a master's load: every parameter a
# plain string or integer, no entities, no carriage returns.  Anything else
# (or anything this strict pattern does not match) goes to the full parser,
# so the fast path never accepts a document the standard parser would refuse.
# Compiled on the first call decoded (0.8 ms): a node that serves no call before its first publish skips it.
_FAST_CALL_PATTERN = (
    rb"(?:<\?xml version=['\"]1\.0['\"](?:[ \t\r\n]+encoding=['\"](?:utf-8|UTF-8)['\"])?[ \t\r\n]*\?>)?[ \t\r\n]*"
    rb"<methodCall>[ \t\r\n]*<methodName>([A-Za-z0-9_.]+)</methodName>[ \t\r\n]*"
    rb"(?:<params>((?:[ \t\r\n]*<param>[ \t\r\n]*<value>(?:<string>[^<&\]\x00-\x08\x0b-\x1f]*</string>|[^<&\]\x00-\x08\x0b-\x1f]*|"
    rb"<(?:int|i4|i8)>-?[0-9]{1,18}</(?:int|i4|i8)>)</value>[ \t\r\n]*</param>)*)[ \t\r\n]*</params>[ \t\r\n]*)?"
    rb"</methodCall>[ \t\r\n]*"
)
_FAST_PARAM_PATTERN = rb"<value>(?:<string>([^<]*)</string>|<(int|i4|i8)>([^<]*)</(?:int|i4|i8)>|([^<]*))</value>"
_fast: tuple[re.Pattern[bytes], re.Pattern[bytes]] | None = None


def _decode_fast(body: bytes) -> tuple[tuple[Any, ...], str] | None:
    global _fast
    if b"<array>" in body or b"<struct>" in body:  # never a match (requestTopic, publisherUpdate): no compiling
        return None
    if _fast is None:
        _fast = re.compile(_FAST_CALL_PATTERN), re.compile(_FAST_PARAM_PATTERN)
    fast_call, fast_param = _fast
    m = fast_call.fullmatch(body)
    if m is None:
        return None
    params: list[Any] = []
    if m.group(2):
        for s, kind, num, bare in fast_param.findall(m.group(2)):
            if kind:
                params.append(int(num))
            else:
                try:
                    params.append((s or bare).decode("utf-8"))
                except UnicodeDecodeError:
                    return None
    return tuple(params), m.group(1).decode("ascii")


def decode_call(body: bytes) -> tuple[tuple[Any, ...], str]:
    """Parse a ``<methodCall>``: return ``(params, method_name)``."""
    fast = _decode_fast(body)
    if fast is not None:
        return fast
    params, method = _loads(body)
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
    (value,) = _loads(body)[0]
    return value


def exception_fault_string(exc: BaseException) -> str:
    """The fault string Python's SimpleXMLRPCServer (and so rosmaster) sends for ``exc``."""
    return f"{type(exc)}:{exc}"
