"""tf's maths and buffer, for every face of rostui (the tf CLI, the views, and the tf/tf2_ros modules scripts import).

:mod:`.transform` holds rigid transforms (quaternions, composition, inverse, RPY); :mod:`.buffer` the frames,
edges and lookups through the tree; :mod:`.transformations` ROS's ``tf.transformations`` on 4x4 matrices.
"""

from rostui.tools.tf.buffer import (
    ConnectivityError, DepthError, Edge, ExtrapolationError, FrameNotFoundError, LoopError, StampedTransform,
    TfBuffer, TfError,
)
from rostui.tools.tf.transform import Transform, quat_from_rpy, quat_to_rpy

__all__ = [
    "ConnectivityError", "DepthError", "Edge", "ExtrapolationError", "FrameNotFoundError", "LoopError",
    "StampedTransform", "TfBuffer", "TfError", "Transform", "quat_from_rpy", "quat_to_rpy",
]
