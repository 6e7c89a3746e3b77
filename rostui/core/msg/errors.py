"""Exception types of the message layer."""

from __future__ import annotations

__all__ = [
    "MessageError",
    "UnknownMessageTypeError",
    "MessageSpecError",
    "SerializationError",
    "DeserializationError",
    "MessageValueError",
]


class MessageError(Exception):
    """Base class of every error raised by :mod:`rostui.core.msg`."""


class UnknownMessageTypeError(MessageError, LookupError):
    """A message or service type name could not be resolved to a definition."""

    def __init__(self, type_name: str, detail: str = "") -> None:
        """Record the unresolved *type_name* and an optional *detail*."""
        text = type_name if isinstance(type_name, str) else repr(type_name)
        shown = text if text.isprintable() and len(text) <= 200 else repr(text[:200])
        msg = f"unknown message type [{shown}]"
        if detail:
            msg += f": {detail}"
        super().__init__(msg)
        self.type_name = type_name


class MessageSpecError(MessageError, ValueError):
    """A .msg/.srv text is malformed; carries the source file and line when known."""

    def __init__(self, message: str, source: str | None = None, line: int | None = None) -> None:
        """Build the error; str() reads ``source:line: message``."""
        where = ""
        if source is not None:
            where = f"{source}:{line}: " if line is not None else f"{source}: "
        elif line is not None:
            where = f"line {line}: "
        super().__init__(where + message)
        self.message = message
        self.source = source
        self.line = line


class SerializationError(MessageError):
    """A message's field values cannot be serialized (wrong type or out of range)."""


class DeserializationError(MessageError):
    """A buffer does not hold a valid serialized message (truncated or garbage)."""


class MessageValueError(MessageError, ValueError):
    """A dict/YAML value does not fit a message (unknown field, wrong type)."""
