"""ROS 1 message and service types: .msg/.srv loading, md5, (de)serialization, dict/YAML views.

Typical use::

    from rostui.core.msg import get_message_class
    String = get_message_class("std_msgs/String")
    data = String(data="hi").serialize()
    msg = String.deserialize(data)
"""

from __future__ import annotations

from ..rostime import Duration, Time
from .errors import (
    DefinitionMismatchError,
    DeserializationError,
    Md5MismatchError,
    MessageError,
    MessageSpecError,
    MessageValueError,
    SerializationError,
    UnknownMessageTypeError,
)
from .message import Message, Service, install_hooks
from .registry import (
    DEFINITION_SEPARATOR,
    TypeStore,
    clear_cache,
    full_text,
    get_message_class,
    get_message_spec,
    get_service_class,
    get_service_spec,
    list_message_types,
    list_service_types,
    md5sum,
)
from .received import connection_class, definition_md5, foreign_version, reconstruct, rostui_md5
from .spec import BUILTIN_TYPES, PRIMITIVE_TYPES, Constant, Field, MsgSpec, SrvSpec, parse_msg_text, parse_srv_text

__all__ = [
    "Time", "Duration",
    "MessageError", "UnknownMessageTypeError", "MessageSpecError", "SerializationError",
    "DeserializationError", "MessageValueError", "Md5MismatchError", "DefinitionMismatchError",
    "Message", "Service",
    "DEFINITION_SEPARATOR", "TypeStore", "clear_cache", "full_text", "get_message_class",
    "get_message_spec", "get_service_class", "get_service_spec", "list_message_types",
    "list_service_types", "md5sum", "connection_class", "definition_md5", "foreign_version", "rostui_md5",
    "BUILTIN_TYPES", "PRIMITIVE_TYPES", "Constant", "Field", "MsgSpec", "SrvSpec",
    "parse_msg_text", "parse_srv_text",
]


def _message_text(msg: Message) -> str:
    """``str(msg)``: the text ``rostopic echo`` prints for *msg*."""
    from .convert import message_to_yaml  # deferred: importing the package does not load yaml

    return message_to_yaml(msg)


install_hooks(text=_message_text, unpickle=reconstruct)
