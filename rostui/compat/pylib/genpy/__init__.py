"""genpy for unmodified ROS 1 scripts, served by rostui: ``Message``, ``Time``, ``Duration`` and errors.

These are rostui's own classes (:mod:`rostui.core.msg`, :mod:`rostui.core.rostime`),
so a message built by a script is the very class rostui's runtime (de)serialises.
"""

from __future__ import annotations

from .message import DeserializationError, Message, MessageException, SerializationError, struct_I
from .rostime import Duration, Time, TVal

__all__ = ["Message", "SerializationError", "DeserializationError", "MessageException", "struct_I",
           "Time", "Duration", "TVal"]
