"""tf2_ros.buffer_interface: the lookup interface every tf2 buffer offers, and the registries ``transform`` uses.

``Buffer.transform(obj, frame)`` finds the function registered for ``type(obj)`` (tf2_geometry_msgs registers
the stamped geometry messages when it is imported), looks up the transform from ``obj.header.frame_id`` at
``obj.header.stamp`` and applies it.
"""

from __future__ import annotations

from copy import deepcopy
from typing import Any, Callable, ClassVar

import rospy

from rostui.core.msg import get_message_class

__all__ = ["BufferInterface", "ConvertRegistration", "NotImplementedException", "Stamped", "TransformRegistration",
           "TypeException", "convert"]


class TypeException(Exception):
    """A type no transform or conversion is registered for."""

    def __init__(self, errstr: str) -> None:
        super().__init__(errstr)
        self.errstr = errstr


class NotImplementedException(Exception):
    """A lookup asked of the abstract interface itself."""

    def __init__(self) -> None:
        super().__init__()
        self.errstr = "CanTransform or LookupTransform not implemented"


def _unknown(key: Any) -> TypeException:
    return TypeException(f"Type {key} if not loaded or supported")  # tf2_ros's words, typo included


class TransformRegistration:
    """Which function transforms which message class; one table shared by every instance."""

    _functions: ClassVar[dict[Any, Callable[[Any, Any], Any]]] = {}

    def add(self, key: Any, callback: Callable[[Any, Any], Any]) -> None:
        """Register ``callback(obj, transform_stamped)`` for objects of class ``key``."""
        TransformRegistration._functions[key] = callback

    def get(self, key: Any) -> Callable[[Any, Any], Any]:
        """The function registered for ``key``; TypeException if there is none."""
        try:
            return TransformRegistration._functions[key]
        except KeyError:
            raise _unknown(key) from None

    def print_me(self) -> None:
        """Print the table."""
        print(TransformRegistration._functions)


class ConvertRegistration:
    """Conversions between types: to and from messages, and direct ones; tables shared by every instance."""

    _to_msg: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _from_msg: ClassVar[dict[Any, Callable[[Any], Any]]] = {}
    _convert: ClassVar[dict[Any, Callable[[Any], Any]]] = {}

    def add_from_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        """Register how to make a ``key`` from a message."""
        ConvertRegistration._from_msg[key] = callback

    def add_to_msg(self, key: Any, callback: Callable[[Any], Any]) -> None:
        """Register how to make a message from a ``key``."""
        ConvertRegistration._to_msg[key] = callback

    def add_convert(self, key: Any, callback: Callable[[Any], Any]) -> None:
        """Register a direct conversion; ``key`` is ``(from_type, to_type)``."""
        ConvertRegistration._convert[key] = callback

    def get_from_msg(self, key: Any) -> Callable[[Any], Any]:
        """The from-message function of ``key``; TypeException if there is none."""
        return self._get(ConvertRegistration._from_msg, key)

    def get_to_msg(self, key: Any) -> Callable[[Any], Any]:
        """The to-message function of ``key``; TypeException if there is none."""
        return self._get(ConvertRegistration._to_msg, key)

    def get_convert(self, key: Any) -> Callable[[Any], Any]:
        """The direct conversion of ``key``; TypeException if there is none."""
        return self._get(ConvertRegistration._convert, key)

    @staticmethod
    def _get(table: dict[Any, Callable[[Any], Any]], key: Any) -> Callable[[Any], Any]:
        try:
            return table[key]
        except KeyError:
            raise _unknown(key) from None


def convert(a: Any, b_type: Any) -> Any:
    """``a`` as a ``b_type``: a direct conversion, a copy if it already is one, else through its message."""
    registry = ConvertRegistration()
    try:
        return registry.get_convert((type(a), b_type))(a)
    except TypeException:
        if type(a) == b_type:  # noqa: E721 (the exact class, as tf2_ros compares)
            return deepcopy(a)
        return registry.get_from_msg(b_type)(registry.get_to_msg(type(a))(a))


def Stamped(obj: Any, stamp: Any, frame_id: str) -> Any:  # noqa: N802 (tf2_ros's name)
    """``obj`` given a header with ``stamp`` and ``frame_id`` (returned, changed in place)."""
    obj.header = get_message_class("std_msgs/Header")(frame_id=frame_id, stamp=stamp)
    return obj


class BufferInterface:
    """What a tf2 buffer answers: lookups, can-transform questions and ``transform`` of stamped data."""

    def __init__(self) -> None:
        self.registration = TransformRegistration()

    def transform(self, object_stamped: Any, target_frame: str, timeout: Any = None, new_type: Any = None) -> Any:
        """``object_stamped`` expressed in ``target_frame`` (at its own stamp), as ``new_type`` if given."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(object_stamped, self.lookup_transform(target_frame, header.frame_id, header.stamp,
                                                                   _zero(timeout)))
        return convert(result, new_type) if new_type else result

    def transform_full(self, object_stamped: Any, target_frame: str, target_time: Any, fixed_frame: str,
                       timeout: Any = None, new_type: Any = None) -> Any:
        """:meth:`transform` at ``target_time``, through ``fixed_frame`` (the advanced form)."""
        do_transform = self.registration.get(type(object_stamped))
        header = object_stamped.header
        result = do_transform(object_stamped, self.lookup_transform_full(
            target_frame, target_time, header.frame_id, header.stamp, fixed_frame, _zero(timeout)))
        return convert(result, new_type) if new_type else result

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        """The transform from ``source_frame`` to ``target_frame`` (implemented by buffers)."""
        raise NotImplementedException()

    def lookup_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                              fixed_frame: str, timeout: Any = None) -> Any:
        """The advanced form of :meth:`lookup_transform` (implemented by buffers)."""
        raise NotImplementedException()

    def can_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        """Whether :meth:`lookup_transform` would answer (implemented by buffers)."""
        raise NotImplementedException()

    def can_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                           fixed_frame: str, timeout: Any = None) -> Any:
        """Whether :meth:`lookup_transform_full` would answer (implemented by buffers)."""
        raise NotImplementedException()


def _zero(timeout: Any) -> Any:
    """``timeout``, or a zero ``rospy.Duration`` (tf2_ros's default)."""
    return rospy.Duration(0.0) if timeout is None else timeout
