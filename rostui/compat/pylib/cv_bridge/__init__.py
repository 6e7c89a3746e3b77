"""cv_bridge for unmodified ROS 1 scripts: ``CvBridge`` between ROS images and numpy arrays, and ``getCvType``.

Raw images need only numpy; colour conversions that compute (to mono, from yuv or bayer) and compressed
images need OpenCV (``pip install opencv-python-headless``, or ``rostui[cv]``). ``cvtColorForDisplay`` is
not provided (docs/rospy.md).
"""

from __future__ import annotations

from .core import CvBridge, CvBridgeError
from .encodings import EncodingError, cv_type

__all__ = ["CvBridge", "CvBridgeError", "getCvType"]


def getCvType(encoding: str) -> int:  # noqa: N802 (cv_bridge's name)
    """OpenCV's type code of an image encoding (``cv2.CV_8UC3`` for ``bgr8``)."""
    try:
        return cv_type(encoding)
    except EncodingError as exc:
        raise RuntimeError(str(exc)) from None
