"""tf for unmodified ROS 1 scripts: tf's listener, broadcaster, transformer and ``tf.transformations``.

As in ROS Noetic, tf is a thin layer over tf2_ros (rostui's): ``tf.Exception`` is tf2's
``TransformException`` and the other exceptions are tf2's. ``tf.msg`` (tfMessage) and ``tf.srv`` are
rostui's message modules.
"""

from __future__ import annotations

from tf2_ros import ConnectivityException, ExtrapolationException, LookupException
from tf2_ros import TransformException as Exception  # noqa: A004 (tf's name)

from . import transformations
from .broadcaster import TransformBroadcaster
from .listener import Transformer, TransformerROS, TransformListener

__all__ = ["ConnectivityException", "Exception", "ExtrapolationException", "LookupException", "TransformBroadcaster",
           "TransformListener", "Transformer", "TransformerROS", "transformations"]
