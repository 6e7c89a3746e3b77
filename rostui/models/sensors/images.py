"""sensor_msgs/Image and sensor_msgs/CompressedImage as RGB pixels (numpy + Pillow), shrunk to what is drawn.

:func:`decode_image` turns a message into a :class:`Picture`: an RGB
``uint8`` array of at most ``max_size`` pixels (aspect kept), so a 640x480
frame shown in a 100x40 terminal is cut down before anything else touches
it.  Raw images are subsampled by striding the array (no copy of the full
frame), then resized by Pillow (box filter); JPEGs are decoded at a reduced scale
(Pillow's ``draft``).  A compressed image's size is read from its header
first: one that would still take more than :data:`MAX_DECODE_PIXELS` pixels
to decode (a PNG cannot be decoded smaller) is refused before any pixel is
inflated, so a 25 kB PNG cannot claim a gigabyte.  Depth images (16UC1 in
millimetres, 32FC1 in metres) are coloured with a blue-to-red map over their
finite non-zero range; zero and NaN are black.  Bad input raises
:class:`ImageDecodeError` with one line.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import Any

import numpy as np
from PIL import Image as PILImage

from rostui.core.msg import foreign_version

__all__ = ["Picture", "ImageDecodeError", "ENCODINGS", "COMPRESSED_FORMATS", "MAX_DECODE_PIXELS", "decode_image",
           "raw_pixels_read", "fit", "colour_map"]

#: Raw encodings shown, with (channels, numpy dtype).
ENCODINGS: dict[str, tuple[int, str]] = {
    "rgb8": (3, "u1"), "bgr8": (3, "u1"), "rgba8": (4, "u1"), "bgra8": (4, "u1"),
    "mono8": (1, "u1"), "8UC1": (1, "u1"), "mono16": (1, "u2"), "16UC1": (1, "u2"), "32FC1": (1, "f4"),
}
#: Compressed formats shown (the first word of CompressedImage.format, or after "compressed").
COMPRESSED_FORMATS = ("jpeg", "jpg", "png")
#: Most pixels a compressed image may take once decoded (a JPEG after its reduced-scale decoding): 4096 x 4096.
MAX_DECODE_PIXELS = 1 << 24

# Pillow's own cap counts the pixels before a JPEG's reduced-scale decoding (and warns on stderr, under the
# terminal app, below it); :data:`MAX_DECODE_PIXELS`, checked before any pixel is decoded, takes its place.
PILImage.MAX_IMAGE_PIXELS = None

#: Anchors of the depth colour map, near to far: dark blue, cyan, green, yellow, red.
_MAP = np.array([[0, 0, 160], [0, 200, 255], [40, 220, 40], [255, 230, 0], [220, 20, 20]], dtype=np.float32)


class ImageDecodeError(ValueError):
    """An image message that cannot be shown (unknown encoding, too little data); the text is one line."""


@dataclass(frozen=True)
class Picture:
    """Pixels ready to draw: ``rgb`` (H x W x 3 uint8), the message's own size and encoding, a depth range."""

    rgb: np.ndarray
    width: int
    height: int
    encoding: str
    depth_range: tuple[float, float] | None = None


def fit(width: int, height: int, max_w: int, max_h: int) -> tuple[int, int]:
    """The largest size inside ``max_w`` x ``max_h`` with the aspect of ``width`` x ``height`` (at least 1x1)."""
    if width <= 0 or height <= 0 or max_w <= 0 or max_h <= 0:
        return 1, 1
    scale = min(max_w / width, max_h / height)
    return max(1, round(width * scale)), max(1, round(height * scale))


def colour_map(values: np.ndarray) -> tuple[np.ndarray, tuple[float, float] | None]:
    """Depth values (any float array) as RGB: finite non-zero ones from blue (near) to red (far); others black."""
    valid = np.isfinite(values) & (values != 0)
    rgb = np.zeros(values.shape + (3,), dtype=np.uint8)
    if not valid.any():
        return rgb, None
    lo, hi = float(values[valid].min()), float(values[valid].max())
    t = np.zeros(values.shape, dtype=np.float32)
    t[valid] = (values[valid] - lo) / (hi - lo) if hi > lo else 0.0
    x = t * (len(_MAP) - 1)
    stops = np.arange(len(_MAP), dtype=np.float32)
    for c in range(3):
        channel = np.interp(x, stops, _MAP[:, c])
        rgb[..., c] = np.where(valid, channel, 0).astype(np.uint8)
    return rgb, (lo, hi)


def decode_image(msg: Any, max_size: tuple[int, int] = (4096, 4096)) -> Picture:
    """``msg`` (sensor_msgs/Image or CompressedImage) as a :class:`Picture` no larger than ``max_size`` (w, h).

    :class:`ImageDecodeError` (one line) for a message that is not rostui's version of its type (a bag's own
    version, without the fields read here).
    """
    other = foreign_version(msg)
    if other is not None:
        raise ImageDecodeError(f"{other}: not drawn")
    if hasattr(msg, "format"):
        return _decode_compressed(msg, max_size)
    return _decode_raw(msg, max_size)


def _stride(width: int, height: int, target: tuple[int, int]) -> int:
    """The step between two source pixels read: a whole number of them per shown pixel, twice the size shown."""
    return max(1, min(width // (2 * target[0]), height // (2 * target[1])))


def raw_pixels_read(msg: Any, max_size: tuple[int, int]) -> int | None:
    """How many pixels :func:`decode_image` reads of raw image ``msg`` to fit ``max_size`` (what its cost grows
    with), or None for a compressed image (its cost is only known once decoded) or a message with no such size."""
    if hasattr(msg, "format"):
        return None
    try:
        width, height = int(msg.width), int(msg.height)
    except (AttributeError, TypeError, ValueError):
        return None
    if width <= 0 or height <= 0:
        return 0
    stride = _stride(width, height, fit(width, height, *max_size))
    return -(-width // stride) * -(-height // stride)


def _decode_raw(msg: Any, max_size: tuple[int, int]) -> Picture:
    encoding = str(msg.encoding)
    if encoding not in ENCODINGS:
        raise ImageDecodeError(f"encoding {encoding!r} is not shown; rostui view shows "
                               + ", ".join(ENCODINGS))
    channels, kind = ENCODINGS[encoding]
    width, height, step = int(msg.width), int(msg.height), int(msg.step)
    itemsize = np.dtype(kind).itemsize
    if width <= 0 or height <= 0:
        raise ImageDecodeError(f"an image of {width}x{height} pixels has nothing to show")
    row_bytes = width * channels * itemsize
    if step < row_bytes:
        raise ImageDecodeError(f"step {step} is less than a row of {width} {encoding} pixels ({row_bytes} bytes)")
    data = msg.data if isinstance(msg.data, (bytes, bytearray, memoryview, np.ndarray)) else bytes(msg.data)
    data = np.frombuffer(data, dtype=np.uint8)
    if data.size < step * (height - 1) + row_bytes:
        raise ImageDecodeError(f"{data.size} bytes of data for {height} rows of {step} bytes ({width}x{height} {encoding})")
    dtype = np.dtype(kind).newbyteorder(">" if msg.is_bigendian else "<") if itemsize > 1 else np.dtype(kind)
    # the rows in place (a row every ``step`` bytes), whether or not the last row has its padding
    grid = np.ndarray((height, row_bytes), dtype=np.uint8, buffer=data, strides=(step, 1))
    pixels = grid.view(dtype).reshape(height, width, channels) if itemsize > 1 else grid.reshape(height, width, channels)
    # keep a whole number of source pixels per shown pixel, twice the size shown (Pillow smooths the rest)
    target = fit(width, height, *max_size)
    stride = _stride(width, height, target)
    pixels = pixels[::stride, ::stride]
    depth = None
    if encoding in ("rgb8", "rgba8"):
        rgb = pixels[..., :3]
    elif encoding in ("bgr8", "bgra8"):
        rgb = pixels[..., 2::-1]
    elif encoding in ("mono8", "8UC1"):
        rgb = np.repeat(pixels, 3, axis=2)
    elif encoding == "mono16":
        rgb = np.repeat((pixels >> 8).astype(np.uint8), 3, axis=2)
    else:
        values = pixels[..., 0].astype(np.float32)
        if encoding == "16UC1":
            values = values / 1000.0
        rgb, depth = colour_map(values)
    return Picture(_shrink(np.ascontiguousarray(rgb, dtype=np.uint8), target), width, height, encoding, depth)


def _decode_compressed(msg: Any, max_size: tuple[int, int]) -> Picture:
    fmt = str(msg.format)
    words = fmt.replace(";", " ").split()
    kind = next((w for w in words if w.lower() in COMPRESSED_FORMATS), None)
    if kind is None or "compressedDepth" in words:
        raise ImageDecodeError(f"compressed format {fmt!r} is not shown; rostui view shows jpeg and png")
    try:
        opened = PILImage.open(io.BytesIO(bytes(msg.data)), formats=("JPEG", "PNG"))
        width, height = opened.size
        target = fit(width, height, *max_size)
        if opened.format == "JPEG":
            opened.draft("RGB", (target[0] * 2, target[1] * 2))
        decoded_w, decoded_h = opened.size  # a JPEG's reduced scale; anything else decodes whole
        if decoded_w * decoded_h > MAX_DECODE_PIXELS:
            raise ImageDecodeError(f"{kind} of {width}x{height} pixels not drawn: more than {MAX_DECODE_PIXELS} "
                                   "pixels to decode")
        image = _reduced(opened, target)
    except (OSError, ValueError) as exc:
        if isinstance(exc, ImageDecodeError):
            raise
        raise ImageDecodeError(f"{kind} data cannot be decoded: {str(exc).splitlines()[0] if str(exc) else exc!r}") from None
    return Picture(np.asarray(image), width, height, kind.lower())


def _reduced(image: PILImage.Image, target: tuple[int, int]) -> PILImage.Image:
    """``image`` as RGB at ``target`` (w, h), shrunk in its own mode first: no full-size RGB copy is made."""
    if image.mode == "1":
        image = image.convert("L")
    elif image.mode in ("P", "PA"):
        if image.size != target:
            image = image.resize(target, PILImage.Resampling.NEAREST)  # palette indices cannot be averaged
        image = image.convert("RGBA" if "transparency" in image.info or image.mode == "PA" else "RGB")
    elif image.mode not in ("L", "LA", "RGB", "RGBA"):
        image = image.convert("RGB")
    if image.size != target:
        image = image.resize(target, _filter(image.size, target), reducing_gap=2.0)
    return image.convert("RGB")


def _shrink(rgb: np.ndarray, target: tuple[int, int]) -> np.ndarray:
    """``rgb`` resized to ``target`` (w, h) by Pillow."""
    if (rgb.shape[1], rgb.shape[0]) == target:
        return rgb
    image = PILImage.fromarray(rgb, "RGB").resize(target, _filter((rgb.shape[1], rgb.shape[0]), target))
    return np.asarray(image)


def _filter(size: tuple[int, int], target: tuple[int, int]) -> PILImage.Resampling:
    """Box (the mean of the pixels each one covers) when shrinking; nearest when enlarging, so edges stay sharp."""
    return PILImage.Resampling.BOX if target[0] < size[0] else PILImage.Resampling.NEAREST
