"""genpy.message: the message base class, its errors, the type look-ups by name and ``fill_message_args``."""

from __future__ import annotations

import re
import struct
from typing import Any, Mapping, Sequence

from rostui.compat.lookup import get_message_class, get_service_class
from rostui.core.msg import DeserializationError, Message, MessageError, SerializationError
from rostui.core.msg.convert import fill_message
from rostui.core.msg.errors import MessageValueError

__all__ = ["Message", "MessageException", "SerializationError", "DeserializationError", "struct_I",
           "fill_message_args", "get_message_class", "get_service_class"]

MessageException = MessageError
"""genpy's base of message errors: rostui's :class:`MessageError` (SerializationError and friends derive from it)."""

struct_I = struct.Struct("<I")
"""The little-endian uint32 every generated genpy module shares (lengths on the wire)."""


def fill_message_args(msg: Message, msg_args: Sequence[Any], keys: Mapping[str, Any] | None = None) -> Message:
    """Fill ``msg`` from ``rostopic pub``-style arguments, as genpy does.

    One dict in ``msg_args`` sets fields by name; otherwise the list gives every field in order (nested
    messages as lists or dicts, too many or too few is a MessageException). A string in a time or message
    field is looked up in ``keys`` (``{'now': rospy.Time.now(), 'auto': header}``); an int in a time field is
    nanoseconds.
    """
    if not isinstance(msg_args, (list, tuple)):
        raise ValueError("msg_args must be a list")
    values: Any = msg_args[0] if len(msg_args) == 1 and isinstance(msg_args[0], dict) else list(msg_args)
    try:
        return fill_message(msg, values, keys=keys)
    except MessageValueError as exc:
        raise _FillException(_GENPY_WORDS.sub("", str(exc))) from None


class _FillException(MessageError):
    """What genpy raises when arguments do not fit a message: a MessageException (by name, too)."""


_FillException.__name__ = _FillException.__qualname__ = "MessageException"
#: rostui names the message type in these errors; genpy does not.
_GENPY_WORDS = re.compile(r"(?<=\]) in [\w/]+$| for [\w/.]+(?=:\n)")
