"""rospy.numpy_msg: ``numpy_msg(Floats)``, a message class whose numeric arrays are numpy arrays.

Publishing takes numpy arrays in array fields (``pub.publish(numpy.array(..., dtype=numpy.float32))``);
a subscriber of such a class receives its numeric arrays as numpy arrays of the field's type.
"""

from __future__ import annotations

from typing import Any

import numpy

from rostui.core.msg import Message
from rostui.core.msg.message import hybridmethod

__all__ = ["numpy_msg"]

_numpy_classes: dict[type, type] = {}


def _deserialize_numpy(cls: Any, data: Any) -> Any:
    """A *cls* message read from *data*, numeric arrays as numpy arrays."""
    plain = cls._plain_class()
    plain.deserialize_numpy(data, numpy)
    msg = cls.__new__(cls)
    for name in cls.__slots__:
        setattr(msg, name, getattr(plain, name))
    return msg


def numpy_msg(msg_type: type) -> type:
    """The numpy form of *msg_type* (one class per type, as rospy): same type, md5sum and wire format."""
    known = _numpy_classes.get(msg_type)
    if known is not None:
        return known
    if not (isinstance(msg_type, type) and issubclass(msg_type, Message)):
        raise TypeError(f"numpy_msg() needs a message class, not {msg_type!r}")
    body = {
        "__slots__": list(msg_type.__slots__),
        "__module__": __name__,
        "_plain_class": staticmethod(lambda: msg_type()),
        "deserialize": hybridmethod(_deserialize_numpy),
    }
    numpy_type = type("Numpy_" + msg_type._type.replace("/", "__"), (msg_type,), body)
    _numpy_classes[msg_type] = numpy_type
    return numpy_type
