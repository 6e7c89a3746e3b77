"""TCPROS and rosrpc framing: connection headers and length-prefixed frames.

A connection starts with a header (uint32 total length, then fields each
prefixed by a uint32 length, ``key=value``), followed by frames (uint32 length,
then the payload).  The :class:`FrameReader` enforces a cap on every length
prefix before it buffers anything, so a bogus length costs nothing.
"""

from __future__ import annotations

import os
import struct
from typing import Mapping

LEN = struct.Struct("<I")
DEFAULT_MAX_FRAME = 1 << 30
MAX_HEADER = 1 << 20


def max_frame_from_env() -> int:
    """The frame length cap: ROSTUI_TCPROS_MAX_FRAME bytes, default 1 GiB."""
    raw = os.environ.get("ROSTUI_TCPROS_MAX_FRAME")
    return int(raw) if raw and raw.isdigit() else DEFAULT_MAX_FRAME


DEFAULT_MAX_BACKLOG = 64 << 20


def max_backlog_from_env() -> int:
    """Bytes a publisher queues for one subscriber that does not keep up before dropping it.

    ROSTUI_TCPROS_MAX_BACKLOG bytes, default 64 MiB; one message always fits, however large.
    """
    raw = os.environ.get("ROSTUI_TCPROS_MAX_BACKLOG")
    return int(raw) if raw and raw.isdigit() else DEFAULT_MAX_BACKLOG


def stall_timeout_from_env() -> float:
    """Seconds a peer may stall mid-frame or mid-header before it is dropped."""
    raw = os.environ.get("ROSTUI_TCPROS_STALL_TIMEOUT")
    try:
        return float(raw) if raw else 30.0
    except ValueError:
        return 30.0


class TcprosError(Exception):
    """A peer broke the TCPROS protocol; its connection must be dropped."""


class HeaderError(TcprosError):
    """A connection header that cannot be decoded or lacks a required field."""


class FrameTooLargeError(TcprosError):
    """A length prefix beyond the configured cap."""


def encode_header(fields: Mapping[str, str]) -> bytes:
    """Encode a connection header, including its leading total length."""
    parts = []
    for key, value in fields.items():
        item = f"{key}={value}".encode()
        parts.append(LEN.pack(len(item)))
        parts.append(item)
    body = b"".join(parts)
    return LEN.pack(len(body)) + body


def decode_header(body: bytes | memoryview) -> dict[str, str]:
    """Decode a header body (without its total length prefix) into fields."""
    fields: dict[str, str] = {}
    pos, end = 0, len(body)
    while pos < end:
        if pos + 4 > end:
            raise HeaderError("header field length is cut short")
        (size,) = LEN.unpack_from(body, pos)
        pos += 4
        if pos + size > end:
            raise HeaderError(f"header field of {size} bytes runs past the header end")
        item = bytes(body[pos : pos + size])
        pos += size
        key, sep, value = item.partition(b"=")
        if not sep:
            raise HeaderError(f"header field without '=': {item[:40]!r}")
        try:
            fields[key.decode()] = value.decode()
        except UnicodeDecodeError as exc:
            raise HeaderError("header field is not UTF-8") from exc
    return fields


def require_fields(header: Mapping[str, str], *names: str) -> None:
    """Raise HeaderError naming the first required field the header lacks."""
    for name in names:
        if name not in header:
            raise HeaderError(f"header did not have required element: {name}")


def frame(payload: bytes) -> bytes:
    """Prefix a payload with its uint32 length."""
    return LEN.pack(len(payload)) + payload


class FrameReader:
    """Splits a byte stream into length-prefixed frames, checking each length.

    ``feed`` returns the complete frames found so far; a partial frame stays
    buffered.  Lengths over ``max_frame`` raise FrameTooLargeError before any
    payload is buffered.
    """

    __slots__ = ("_buf", "max_frame")

    def __init__(self, max_frame: int = DEFAULT_MAX_FRAME) -> None:
        self._buf = bytearray()
        self.max_frame = max_frame

    @property
    def pending(self) -> int:
        """Bytes buffered: a partial frame, and whole frames not yet taken (``feed`` with a ``limit``)."""
        return len(self._buf)

    def discard(self) -> int:
        """Forget everything buffered; return how many bytes that was."""
        size = len(self._buf)
        self._buf = bytearray()  # a fresh buffer: the old one's memory goes back at once
        return size

    def whole_frame(self, data: bytes) -> bytes | None:
        """The payload when nothing is buffered and ``data`` is exactly one frame within the cap, else None.

        The common case of a small message arriving in one read; callers feed
        anything else to :meth:`feed`.
        """
        if self._buf or len(data) < 4:
            return None
        (size,) = LEN.unpack_from(data)
        return data[4:] if size + 4 == len(data) and size <= self.max_frame else None

    def feed(self, data: bytes, limit: int | None = None) -> list[bytes]:
        """Add received bytes; return the frames now complete, in order.

        With ``limit``, at most that many frames are taken; the rest stays
        buffered for the next call (so a cap can change after a header).
        """
        buf = self._buf
        if not buf and limit is None and len(data) >= 4:
            (size,) = LEN.unpack_from(data)
            if size + 4 == len(data) and size <= self.max_frame:
                return [data[4:]]  # the usual case: one read, one whole frame
        if data:
            buf += data
        frames: list[bytes] = []
        pos, end = 0, len(buf)
        unpack_from, cap = LEN.unpack_from, self.max_frame
        while end - pos >= 4 and (limit is None or len(frames) < limit):
            (size,) = unpack_from(buf, pos)
            if size > cap:
                raise FrameTooLargeError(f"frame length {size} exceeds the cap of {cap} bytes")
            stop = pos + 4 + size
            if stop > end:
                break
            frames.append(bytes(buf[pos + 4 : stop]) if size < 65536 else bytes(memoryview(buf)[pos + 4 : stop]))
            pos = stop
        if pos:
            del buf[:pos]
        return frames
