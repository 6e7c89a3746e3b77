"""genpy.message: the message base class, its errors and the type look-ups by name."""

from __future__ import annotations

import struct

from rostui.compat.lookup import get_message_class, get_service_class
from rostui.core.msg import DeserializationError, Message, MessageError, SerializationError

__all__ = ["Message", "MessageException", "SerializationError", "DeserializationError", "struct_I",
           "get_message_class", "get_service_class"]

MessageException = MessageError
"""genpy's base of message errors: rostui's :class:`MessageError` (SerializationError and friends derive from it)."""

struct_I = struct.Struct("<I")
"""The little-endian uint32 every generated genpy module shares (lengths on the wire)."""
