"""tf without a screen: rigid transforms and a transform buffer fed from /tf and /tf_static.

:mod:`.transform` holds the maths (quaternions, composition, inverse, RPY);
:mod:`.buffer` the frames, edges and lookups through the tree. No Textual here.
"""

from rostui.models.tf.buffer import (
    ConnectivityError, DepthError, Edge, ExtrapolationError, FrameNotFoundError, LoopError, StampedTransform,
    TfBuffer, TfError,
)
from rostui.models.tf.transform import Transform, quat_from_rpy, quat_to_rpy

__all__ = [
    "ConnectivityError", "DepthError", "Edge", "ExtrapolationError", "FrameNotFoundError", "LoopError",
    "StampedTransform", "TfBuffer", "TfError", "Transform", "quat_from_rpy", "quat_to_rpy",
]
