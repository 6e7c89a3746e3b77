"""Message and service classes by type name, as genpy's and roslib's ``get_message_class`` give them."""

from __future__ import annotations

from rostui.core.msg import Message, MessageError, Service, UnknownMessageTypeError
from rostui.core.msg import get_message_class as _rostui_message_class
from rostui.core.msg import get_service_class as _rostui_service_class
from rostui.core.packages import PackageNotFoundError

__all__ = ["get_message_class", "get_service_class"]


def _module_class(type_name: str, kind: str) -> type | None:
    """The class ``<pkg>.<kind>`` exposes for *type_name*, when the import hook serves it."""
    import importlib

    package, _, name = type_name.partition("/")
    if not package.isidentifier() or not name.isidentifier():
        return None
    try:
        module = importlib.import_module(f"{package}.{kind}")
    except ImportError:
        return None
    found = getattr(module, name, None)
    return found if isinstance(found, type) else None


def get_message_class(message_type: str, reload_on_error: bool = False) -> type[Message] | None:
    """The class of message type ``pkg/Name`` (``Header`` alone means ``std_msgs/Header``); None if unknown."""
    if message_type == "Header":
        message_type = "std_msgs/Header"
    found = _module_class(message_type, "msg")
    if found is not None and issubclass(found, Message):
        return found
    try:
        return _rostui_message_class(message_type)
    except (UnknownMessageTypeError, PackageNotFoundError, MessageError, ValueError):
        return None


def get_service_class(service_type: str, reload_on_error: bool = False) -> type[Service] | None:
    """The class of service type ``pkg/Name`` (with ``_request_class`` and ``_response_class``); None if unknown."""
    found = _module_class(service_type, "srv")
    if found is not None and issubclass(found, Service):
        return found
    try:
        return _rostui_service_class(service_type)
    except (UnknownMessageTypeError, PackageNotFoundError, MessageError, ValueError):
        return None
