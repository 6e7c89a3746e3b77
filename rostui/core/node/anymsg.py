"""AnyMsg: a message kept as its raw serialized bytes (md5sum ``*``)."""

from __future__ import annotations

from typing import Any


class AnyMsg:
    """A message of any type, kept serialized.

    Subscribing with AnyMsg accepts every publisher; each message carries the
    publisher's connection header in ``_connection_header`` (type, md5sum,
    message_definition, callerid, latching) so tools can decode or re-publish it.
    """

    _type = "*"
    _md5sum = "*"
    _full_text = ""
    _has_header = False
    __slots__ = ("_buff", "_connection_header")

    def __init__(self, buff: bytes = b"") -> None:
        self._buff = buff
        self._connection_header: dict[str, str] | None = None

    def serialize(self) -> bytes:
        """The raw bytes, unchanged."""
        return self._buff

    @classmethod
    def deserialize(cls, data: bytes | memoryview) -> "AnyMsg":
        """Wrap raw bytes."""
        return cls(bytes(data))

    def __eq__(self, other: Any) -> bool:
        return isinstance(other, AnyMsg) and other._buff == self._buff

    def __repr__(self) -> str:
        return f"AnyMsg({len(self._buff)} bytes)"
