"""tf2_ros for unmodified ROS 1 scripts: buffer, listener and broadcasters, on rostui's tf buffer and rospy.

The names tf2_ros exports: ``Buffer``, ``TransformListener``, ``TransformBroadcaster``,
``StaticTransformBroadcaster``, the ``BufferInterface`` and its registries, and tf2's exceptions
(``TransformException``, ``LookupException``, ``ConnectivityException``, ``ExtrapolationException``,
``InvalidArgumentException``, ``TimeoutException``). As in tf2_ros there is no ``tf2_ros.Exception``.
``BufferClient`` asks a tf2 buffer server (its ``LookupTransform`` action) instead of keeping a buffer.
"""

from __future__ import annotations

from tf2_py import (
    BufferCore, ConnectivityException, ExtrapolationException, InvalidArgumentException, LookupException,
    TimeoutException, TransformException,
)

from .buffer import DEFAULT_CAN_TRANSFORM_POLLING_SCALE, Buffer
from .buffer_client import BufferClient
from .buffer_interface import (
    BufferInterface, ConvertRegistration, NotImplementedException, Stamped, TransformRegistration, TypeException,
    convert,
)
from .static_transform_broadcaster import StaticTransformBroadcaster
from .transform_broadcaster import TransformBroadcaster
from .transform_listener import TransformListener

__all__ = [
    "Buffer", "BufferClient", "BufferCore", "BufferInterface", "ConnectivityException", "ConvertRegistration",
    "DEFAULT_CAN_TRANSFORM_POLLING_SCALE", "ExtrapolationException", "InvalidArgumentException", "LookupException",
    "NotImplementedException", "Stamped", "StaticTransformBroadcaster", "TimeoutException", "TransformBroadcaster",
    "TransformException", "TransformListener", "TransformRegistration", "TypeException", "convert",
]
