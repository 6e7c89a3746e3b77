"""cv_bridge.core: ``CvBridge``, between sensor_msgs/Image (and CompressedImage) and numpy arrays.

Images are numpy arrays of shape (height, width[, channels]), as OpenCV's Python binding makes them.
Conversions between encodings follow cv_bridge's rules: the same encoding is a copy; between colour
encodings (rgb, bgr, rgba, bgra, mono, yuv422, bayer) the colour is converted, then the depth (8 and 16
bits are scaled into each other); a non-colour encoding (``32FC1``) converts only to one with the same
number of channels. Channel reordering, alpha and grey-to-colour are done here, exactly; conversions
that compute colour (to mono, from yuv or bayer) and the compressed formats use OpenCV
(``pip install opencv-python-headless``), which is imported only when one is asked for.
"""

from __future__ import annotations

import sys
from typing import Any

import numpy as np

from rostui.core.msg import get_message_class

from . import encodings as enc

__all__ = ["CvBridge", "CvBridgeError"]


class CvBridgeError(TypeError):
    """An image cv_bridge cannot convert."""


_SAME = "SAME_FORMAT"
_IDENTITY_FAMILIES = ("GRAY", "RGB", "BGR", "RGBA", "BGRA", "YUV422")
_TO = {
    "GRAY": {"RGB": "GRAY2RGB", "BGR": "GRAY2BGR", "RGBA": "GRAY2RGBA", "BGRA": "GRAY2BGRA"},
    "RGB": {"GRAY": "RGB2GRAY", "BGR": "RGB2BGR", "RGBA": "RGB2RGBA", "BGRA": "RGB2BGRA"},
    "BGR": {"GRAY": "BGR2GRAY", "RGB": "BGR2RGB", "RGBA": "BGR2RGBA", "BGRA": "BGR2BGRA"},
    "RGBA": {"GRAY": "RGBA2GRAY", "RGB": "RGBA2RGB", "BGR": "RGBA2BGR", "BGRA": "RGBA2BGRA"},
    "BGRA": {"GRAY": "BGRA2GRAY", "RGB": "BGRA2RGB", "BGR": "BGRA2BGR", "RGBA": "BGRA2RGBA"},
    "YUV422": {"GRAY": "YUV2GRAY_UYVY", "RGB": "YUV2RGB_UYVY", "BGR": "YUV2BGR_UYVY", "RGBA": "YUV2RGBA_UYVY",
               "BGRA": "YUV2BGRA_UYVY"},
    "BAYER_RGGB": {"GRAY": "BayerBG2GRAY", "RGB": "BayerBG2RGB", "BGR": "BayerBG2BGR"},
    "BAYER_BGGR": {"GRAY": "BayerRG2GRAY", "RGB": "BayerRG2RGB", "BGR": "BayerRG2BGR"},
    "BAYER_GBRG": {"GRAY": "BayerGR2GRAY", "RGB": "BayerGR2RGB", "BGR": "BayerGR2BGR"},
    "BAYER_GRBG": {"GRAY": "BayerGB2GRAY", "RGB": "BayerGB2RGB", "BGR": "BayerGB2BGR"},
}
"""OpenCV's colour conversion (``cv2.COLOR_<name>``) from one colour family to another, as cv_bridge pairs them."""

#: Conversions that only move, copy or add channels: (source channel order, destination order, adds alpha).
_EXACT = {
    "RGB2BGR": [2, 1, 0], "BGR2RGB": [2, 1, 0], "RGBA2BGRA": [2, 1, 0, 3], "BGRA2RGBA": [2, 1, 0, 3],
    "RGB2RGBA": [0, 1, 2, -1], "BGR2BGRA": [0, 1, 2, -1], "RGB2BGRA": [2, 1, 0, -1], "BGR2RGBA": [2, 1, 0, -1],
    "RGBA2RGB": [0, 1, 2], "BGRA2BGR": [0, 1, 2], "RGBA2BGR": [2, 1, 0], "BGRA2RGB": [2, 1, 0],
    "GRAY2RGB": [0, 0, 0], "GRAY2BGR": [0, 0, 0], "GRAY2RGBA": [0, 0, 0, -1], "GRAY2BGRA": [0, 0, 0, -1],
}


def _conversion_steps(src: str, dst: str) -> list[str]:
    """cv_bridge's steps from encoding ``src`` to ``dst``: colour conversions, then a depth change."""
    src_colour, dst_colour = enc.is_colour_format(src), enc.is_colour_format(dst)
    for encoding in (src, dst):
        if encoding in enc.CV_DEPTHS:  # a bare depth ("8U"): sensor_msgs cannot count its channels
            raise CvBridgeError(f"Unknown encoding {encoding}")
    same_channels = enc.channels(src) == enc.channels(dst)
    if not src_colour:
        if dst_colour:
            raise CvBridgeError(f"[{src}] is not a color format. but [{dst}] is. The conversion does not make sense")
        if not same_channels:
            raise CvBridgeError(f"[{src}] and [{dst}] do not have the same number of channel")
        return [_SAME]
    if not dst_colour:
        if not same_channels:
            raise CvBridgeError(f"[{src}] is a color format but [{dst}] is not so they must have the same OpenCV "
                                "type, CV_8UC3, CV16UC1 ....")
        return [_SAME]
    src_family, dst_family = enc.colour_family(src), enc.colour_family(dst)
    assert src_family is not None and dst_family is not None
    if src_family == dst_family and src_family in _IDENTITY_FAMILIES:
        return [_SAME]
    code = _TO.get(src_family, {}).get(dst_family)
    if code is None:
        raise CvBridgeError(f"Unsupported conversion from [{src}] to [{dst}]")
    return [code, _SAME] if enc.bit_depth(src) != enc.bit_depth(dst) else [code]


def _alpha_max(dtype: np.dtype[Any]) -> Any:
    return np.iinfo(dtype).max if np.issubdtype(dtype, np.integer) else 1.0


def _opencv() -> Any:
    try:
        import cv2
    except ImportError:
        raise CvBridgeError("this conversion needs OpenCV, which is not installed: "
                            "pip install opencv-python-headless") from None
    return cv2


def _colour(image: np.ndarray, code: str) -> np.ndarray:
    order = _EXACT.get(code)
    if order is None:
        cv2 = _opencv()
        return np.asarray(cv2.cvtColor(image, getattr(cv2, "COLOR_" + code)))
    planes = image[..., np.newaxis] if image.ndim == 2 else image
    out = np.empty(planes.shape[:2] + (len(order),), dtype=image.dtype)
    for i, source in enumerate(order):
        out[..., i] = _alpha_max(image.dtype) if source < 0 else planes[..., source]
    return out


def _depth(image: np.ndarray, dst: str, scale: float | None) -> np.ndarray:
    """``image`` in ``dst``'s depth, keeping its channels: OpenCV's convertTo (rounded, saturated)."""
    target = np.dtype(enc.DEPTH_DTYPES[enc.depth_and_channels(dst)[0]])
    if scale is None and image.dtype == target:
        return image.copy()
    values = image.astype(np.float64) * scale if scale is not None else image
    if np.issubdtype(target, np.integer):
        info = np.iinfo(target)
        if not np.issubdtype(values.dtype, np.integer):
            values = np.rint(values)
        return np.asarray(np.clip(values, info.min, info.max).astype(target))
    return np.asarray(values.astype(target))


def convert(image: np.ndarray, src: str, dst: str) -> np.ndarray:
    """``image`` (encoded as ``src``) as encoding ``dst``; CvBridgeError when cv_bridge would refuse."""
    if src == dst:
        return image.copy()
    for step in _conversion_steps(src, dst):
        if step == _SAME:
            bits = (enc.bit_depth(src), enc.bit_depth(dst))
            scale = 65535.0 / 255.0 if bits == (8, 16) else 255.0 / 65535.0 if bits == (16, 8) else None
            image = _depth(image, dst, scale)
        else:
            image = _colour(image, step)
    if image.ndim == 3 and image.shape[2] == 1:
        image = image[:, :, 0]
    return image


class CvBridge:
    """Converts between ROS images and numpy arrays (OpenCV's image type in Python)."""

    def __init__(self) -> None:
        self.numpy_type_to_cvtype = {"uint8": "8U", "int8": "8S", "uint16": "16U", "int16": "16S", "int32": "32S",
                                     "float32": "32F", "float64": "64F"}
        self.numpy_type_to_cvtype.update({v: k for k, v in self.numpy_type_to_cvtype.items()})

    def dtype_with_channels_to_cvtype2(self, dtype: Any, n_channels: int) -> str:
        """``8UC3`` for ``(uint8, 3)``."""
        return "%sC%d" % (self.numpy_type_to_cvtype[np.dtype(dtype).name], n_channels)

    def cvtype2_to_dtype_with_channels(self, cvtype: int) -> tuple[str, int]:
        """``("uint8", 3)`` for OpenCV's type code 16 (CV_8UC3)."""
        depth = next(name for name, code in enc.CV_DEPTHS.items() if code == cvtype & 7)
        return enc.DEPTH_DTYPES[depth], (cvtype >> 3) + 1

    def encoding_to_cvtype2(self, encoding: str) -> int:
        """OpenCV's type code of an image encoding."""
        try:
            return enc.cv_type(encoding)
        except enc.EncodingError as exc:
            raise CvBridgeError(str(exc)) from None

    def encoding_to_dtype_with_channels(self, encoding: str) -> tuple[str, int]:
        """The numpy dtype name and channel count of an encoding."""
        return self.cvtype2_to_dtype_with_channels(self.encoding_to_cvtype2(encoding))

    def imgmsg_to_cv2(self, img_msg: Any, desired_encoding: str = "passthrough") -> np.ndarray:
        """The image of a ``sensor_msgs/Image``, in its own encoding (``passthrough``) or converted."""
        dtype_name, n_channels = self.encoding_to_dtype_with_channels(img_msg.encoding)
        dtype = np.dtype(dtype_name).newbyteorder(">" if img_msg.is_bigendian else "<")
        data = img_msg.data
        if n_channels > 1 and isinstance(data, str):
            data = data.encode()
        # rows are read back to back, as Debian's cv_bridge reads them: a step with padding is not honoured
        shape = (img_msg.height, img_msg.width) if n_channels == 1 else (img_msg.height, img_msg.width, n_channels)
        image = np.ndarray(shape=shape, dtype=dtype, buffer=data)
        if img_msg.is_bigendian == (sys.byteorder == "little"):
            image = image.byteswap().view(image.dtype.newbyteorder())
        if desired_encoding == "passthrough":
            return image
        return convert(image, img_msg.encoding, desired_encoding)

    def cv2_to_imgmsg(self, cvim: Any, encoding: str = "passthrough", header: Any = None) -> Any:
        """A ``sensor_msgs/Image`` of an array; a named ``encoding`` must fit the array's type."""
        if not isinstance(cvim, (np.ndarray, np.generic)):
            raise TypeError("Your input type is not a numpy array")
        msg: Any = get_message_class("sensor_msgs/Image")()
        shape: tuple[int, ...] = tuple(cvim.shape)
        msg.height, msg.width = shape[0], shape[1]
        if header is not None:
            msg.header = header
        cv_type = self.dtype_with_channels_to_cvtype2(cvim.dtype, 1 if len(shape) < 3 else shape[2])
        if encoding == "passthrough":
            msg.encoding = cv_type
        else:
            msg.encoding = encoding
            if _known(encoding) and enc.cv_type_name(encoding) != cv_type:
                raise CvBridgeError("encoding specified as %s, but image has incompatible type %s"
                                    % (encoding, cv_type))
        if cvim.dtype.byteorder == ">":
            msg.is_bigendian = True
        msg.data = cvim.tobytes()
        msg.step = len(msg.data) // msg.height
        return msg

    def compressed_imgmsg_to_cv2(self, cmprs_img_msg: Any, desired_encoding: str = "passthrough") -> np.ndarray:
        """The image of a ``sensor_msgs/CompressedImage`` (decoded by OpenCV, as bgr8 unless passthrough)."""
        cv2 = _opencv()
        data = bytes(cmprs_img_msg.data)
        image = cv2.imdecode(np.frombuffer(data, dtype=np.uint8).reshape(1, len(data)), cv2.IMREAD_UNCHANGED)
        if desired_encoding == "passthrough":
            return np.asarray(image)
        return convert(np.asarray(image), "bgr8", desired_encoding)

    def cv2_to_compressed_imgmsg(self, cvim: Any, dst_format: str = "jpg") -> Any:
        """A ``sensor_msgs/CompressedImage`` of an array, encoded by OpenCV as ``dst_format`` (jpg, png...)."""
        if not isinstance(cvim, (np.ndarray, np.generic)):
            raise TypeError("Your input type is not a numpy array")
        cv2 = _opencv()
        msg: Any = get_message_class("sensor_msgs/CompressedImage")()
        msg.format = dst_format
        msg.data = np.array(cv2.imencode("." + dst_format, cvim)[1]).tobytes()
        return msg


def _known(encoding: str) -> bool:
    try:
        enc.depth_and_channels(encoding)
    except enc.EncodingError:
        raise CvBridgeError(f"Unrecognized image encoding [{encoding}]") from None
    return True
