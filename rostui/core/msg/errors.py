"""Exception types of the message layer."""

from __future__ import annotations

__all__ = [
    "MessageError",
    "UnknownMessageTypeError",
    "MessageSpecError",
    "SerializationError",
    "DeserializationError",
    "MessageValueError",
    "Md5MismatchError",
    "DefinitionMismatchError",
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


class Md5MismatchError(MessageError):
    """A peer or a file declares a type rostui knows under another md5sum: rostui's type wins, theirs is refused."""

    def __init__(self, sender: str, type_name: str, theirs: str, ours: str) -> None:
        """Say, in ROS's words, that *sender* has *type_name* as md5sum *theirs* where rostui's is *ours*."""
        super().__init__(f"{sender} has datatype/md5sum [{type_name}/{theirs}], "
                         f"but our version has [{type_name}/{ours}]")
        self.type_name = type_name
        self.theirs = theirs
        self.ours = ours


class DefinitionMismatchError(MessageError):
    """A received definition does not hash to the md5sum declared with it (or none was declared): not used."""
