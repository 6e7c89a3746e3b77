"""sensor_msgs/Image encodings as cv_bridge reads them: OpenCV types, numpy dtypes and colour families."""

from __future__ import annotations

import re

__all__ = ["CV_DEPTHS", "DEPTH_DTYPES", "bit_depth", "channels", "colour_family", "cv_type", "cv_type_name",
           "is_colour_format"]

CV_DEPTHS = {"8U": 0, "8S": 1, "16U": 2, "16S": 3, "32S": 4, "32F": 5, "64F": 6}
"""OpenCV's depth codes."""
DEPTH_DTYPES = {"8U": "uint8", "8S": "int8", "16U": "uint16", "16S": "int16", "32S": "int32", "32F": "float32",
                "64F": "float64"}
"""The numpy dtype of each OpenCV depth."""

_NAMED = {
    "rgb8": ("8U", 3), "bgr8": ("8U", 3), "rgba8": ("8U", 4), "bgra8": ("8U", 4), "mono8": ("8U", 1),
    "rgb16": ("16U", 3), "bgr16": ("16U", 3), "rgba16": ("16U", 4), "bgra16": ("16U", 4), "mono16": ("16U", 1),
    "bayer_rggb8": ("8U", 1), "bayer_bggr8": ("8U", 1), "bayer_gbrg8": ("8U", 1), "bayer_grbg8": ("8U", 1),
    "bayer_rggb16": ("16U", 1), "bayer_bggr16": ("16U", 1), "bayer_gbrg16": ("16U", 1), "bayer_grbg16": ("16U", 1),
    "yuv422": ("8U", 2),
}
_GENERIC = re.compile(r"^(8U|8S|16U|16S|32S|32F|64F)(?:C([1-9]\d*))?$")

_FAMILIES = {"mono": "GRAY", "rgb": "RGB", "bgr": "BGR", "rgba": "RGBA", "bgra": "BGRA"}


class EncodingError(ValueError):
    """An encoding cv_bridge does not know."""


def depth_and_channels(encoding: str) -> tuple[str, int]:
    """``("8U", 3)`` for ``bgr8`` or ``8UC3``; EncodingError for an unknown encoding."""
    if encoding in _NAMED:
        return _NAMED[encoding]
    match = _GENERIC.match(encoding)
    if match is None:
        raise EncodingError(f"Unrecognized image encoding [{encoding}]")
    return match.group(1), int(match.group(2) or 1)


def cv_type(encoding: str) -> int:
    """OpenCV's type code of an encoding (``CV_8UC3`` is 16)."""
    depth, n = depth_and_channels(encoding)
    return CV_DEPTHS[depth] + ((n - 1) << 3)


def cv_type_name(encoding: str) -> str:
    """``8UC3`` for ``bgr8``."""
    depth, n = depth_and_channels(encoding)
    return f"{depth}C{n}"


def channels(encoding: str) -> int:
    """How many channels the encoding has."""
    return depth_and_channels(encoding)[1]


def bit_depth(encoding: str) -> int:
    """Bits per channel (8 for ``8S`` too)."""
    return int(depth_and_channels(encoding)[0][:-1])


def colour_family(encoding: str) -> str | None:
    """GRAY, RGB, BGR, RGBA, BGRA, YUV422 or BAYER_*; None for a generic encoding."""
    if encoding == "yuv422":
        return "YUV422"
    if encoding.startswith("bayer_"):
        return "BAYER_" + encoding[6:].rstrip("0123456789").upper()
    for prefix, family in sorted(_FAMILIES.items(), key=lambda kv: -len(kv[0])):
        if encoding in (prefix + "8", prefix + "16"):
            return family
    return None


def is_colour_format(encoding: str) -> bool:
    """Whether cv_bridge treats the encoding as colour (colour, mono, bayer or yuv)."""
    return colour_family(encoding) is not None
