"""roslib.message: message and service classes by type name (genpy's functions, as roslib re-exports them)."""

from __future__ import annotations

from rostui.compat.lookup import get_message_class, get_service_class
from rostui.core.msg import DeserializationError, Message, SerializationError

__all__ = ["Message", "SerializationError", "DeserializationError", "get_message_class", "get_service_class"]
