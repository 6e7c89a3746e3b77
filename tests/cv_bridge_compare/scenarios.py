"""Random images through cv_bridge both ways, in every encoding pair; prints a digest of each answer.

Written against cv_bridge's public API only, so it runs unchanged under Debian's python3-cv-bridge and under
`rostui python`; tests/test_cv_bridge.py compares the two outputs. Usage: ``scenarios.py SEED``.
"""

import hashlib
import json
import sys

import numpy as np
from cv_bridge import CvBridge, CvBridgeError, getCvType

NAMED = ["rgb8", "bgr8", "rgba8", "bgra8", "mono8", "rgb16", "bgr16", "rgba16", "bgra16", "mono16",
         "bayer_rggb8", "bayer_bggr8", "bayer_gbrg8", "bayer_grbg8", "bayer_rggb16", "yuv422"]
GENERIC = ["8UC1", "8UC3", "8SC1", "16UC1", "16UC3", "16SC1", "32SC1", "32FC1", "32FC2", "32FC3", "64FC1", "8U",
           "32F"]
DTYPES = {"8U": np.uint8, "8S": np.int8, "16U": np.uint16, "16S": np.int16, "32S": np.int32, "32F": np.float32,
          "64F": np.float64}


def digest(value):
    if isinstance(value, np.ndarray):
        data = np.ascontiguousarray(value)
        if data.dtype.byteorder == ">":
            data = data.astype(data.dtype.newbyteorder("<"))
        return [list(value.shape), value.dtype.name, hashlib.sha1(data.tobytes()).hexdigest()[:16]]
    if hasattr(value, "__slots__"):
        return {s: digest(getattr(value, s)) for s in value.__slots__ if s != "header"}
    if isinstance(value, (bytes, bytearray)):
        return hashlib.sha1(bytes(value)).hexdigest()[:16]
    return value


def ask(out, label, call):
    try:
        out.append([label, "ok", digest(call())])
    except (CvBridgeError, TypeError, RuntimeError) as exc:
        out.append([label, "err", type(exc).__name__, str(exc)])


def image_for(rng, encoding, h, w):
    bridge = CvBridge()
    dtype_name, n = bridge.encoding_to_dtype_with_channels(encoding)
    dtype = np.dtype(dtype_name)
    shape = (h, w) if n == 1 else (h, w, n)
    if np.issubdtype(dtype, np.integer):
        info = np.iinfo(dtype)
        return rng.integers(info.min, info.max, size=shape, endpoint=True, dtype=dtype)
    return (rng.standard_normal(shape) * 100).astype(dtype)


def main():
    rng = np.random.default_rng(int(sys.argv[1]))
    bridge = CvBridge()
    out = []
    for encoding in NAMED + GENERIC + ["nope", "8UC", "9UC1", "yuv422_yuy2"]:
        ask(out, "getCvType " + encoding, lambda: getCvType(encoding))
    for dtype in ["uint8", "int8", "uint16", "int16", "int32", "float32", "float64"]:
        for n in (1, 3, 4):
            ask(out, "cvtype2 %s %d" % (dtype, n), lambda: bridge.dtype_with_channels_to_cvtype2(np.dtype(dtype), n))
    for src in NAMED + GENERIC:
        h, w = int(rng.integers(1, 6)) * 2, int(rng.integers(1, 6)) * 2
        image = image_for(rng, src, h, w)
        ask(out, "to msg %s" % src, lambda: bridge.cv2_to_imgmsg(image, src))
        ask(out, "to msg passthrough %s" % src, lambda: bridge.cv2_to_imgmsg(image))
        msg = bridge.cv2_to_imgmsg(image, src)
        for dst in ["passthrough"] + NAMED + GENERIC:
            ask(out, "from msg %s -> %s" % (src, dst), lambda: bridge.imgmsg_to_cv2(msg, dst))
    wide = image_for(rng, "bgr8", 3, 5)
    padded = bridge.cv2_to_imgmsg(wide, "bgr8")
    padded.step += 4
    padded.data = b"".join(bytes(padded.data[r * 15:(r + 1) * 15]) + b"\xaa" * 4 for r in range(3))
    ask(out, "padded rows", lambda: bridge.imgmsg_to_cv2(padded, "rgb8"))
    big = image_for(rng, "16UC3", 4, 4).astype(">u2")
    ask(out, "big-endian to msg", lambda: bridge.cv2_to_imgmsg(big))
    ask(out, "big-endian back", lambda: bridge.imgmsg_to_cv2(bridge.cv2_to_imgmsg(big), "passthrough"))
    ask(out, "not an array", lambda: bridge.cv2_to_imgmsg([[1, 2], [3, 4]]))
    ask(out, "rgba8 on 3 channels", lambda: bridge.cv2_to_imgmsg(image_for(rng, "bgr8", 2, 2), "rgba8"))
    ask(out, "unknown encoding", lambda: bridge.cv2_to_imgmsg(image_for(rng, "bgr8", 2, 2), "fancy"))
    listed = bridge.cv2_to_imgmsg(image_for(rng, "mono8", 2, 3), "mono8")
    listed.data = list(bytes(listed.data))
    ask(out, "data as a list", lambda: bridge.imgmsg_to_cv2(listed))
    photo = image_for(rng, "bgr8", 6, 8)
    ask(out, "png round trip", lambda: bridge.compressed_imgmsg_to_cv2(bridge.cv2_to_compressed_imgmsg(photo, "png")))
    ask(out, "png as rgb8", lambda: bridge.compressed_imgmsg_to_cv2(bridge.cv2_to_compressed_imgmsg(photo, "png"),
                                                                    "rgb8"))
    ask(out, "png format", lambda: bridge.cv2_to_compressed_imgmsg(photo, "png").format)
    for line in out:
        print(json.dumps(line))


if __name__ == "__main__":
    main()
