"""Sensor messages that are small on the wire, or plain in shape, and huge once a careless view decodes them.

Each is built straight as ROS 1 bytes (numpy and struct; a class of rostui's would take seconds to build a
ten-million-range scan): a PointCloud2 of 5,000,000 rows of one point (10 MB), a LaserScan of 10,000,000
ranges (40 MB), and a CompressedImage holding a 1-bit PNG of 13000 x 13000 pixels (25 kB).
:func:`publish_raw` sends one of them at a rate from a rostui client process (tests/peers/rostui_raw_publisher.py).
"""

from __future__ import annotations

import io
import struct
import sys
from pathlib import Path

import numpy as np
from PIL import Image

from conftest import REPO
from interop_helpers import Peer, Spawn

CLOUD_ROWS = 5_000_000
SCAN_RANGES = 10_000_000
PNG_SIDE = 13_000

PUBLISHER = REPO / "tests" / "peers" / "rostui_raw_publisher.py"


def _string(text: str) -> bytes:
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def _header(frame: str) -> bytes:
    return struct.pack("<III", 0, 1, 0) + _string(frame)


def scan_bytes(ranges: int = SCAN_RANGES, frame: str = "base") -> bytes:
    """A sensor_msgs/LaserScan of ``ranges`` beams, each 2 m, all round the scanner."""
    values = np.full(ranges, 2.0, dtype="<f4")
    return (_header(frame) + struct.pack("<7f", -3.14, 3.14, 6.28 / ranges, 0.0, 0.1, 0.1, 30.0)
            + struct.pack("<I", ranges) + values.tobytes() + struct.pack("<I", 0))


def cloud_bytes(rows: int = CLOUD_ROWS, frame: str = "base") -> bytes:
    """A sensor_msgs/PointCloud2 of ``rows`` rows of one point each: x and y int8 (3 m, 4 m), 2 bytes a point."""
    fields = struct.pack("<I", 2) + _string("x") + struct.pack("<IBI", 0, 1, 1) + _string("y") \
        + struct.pack("<IBI", 1, 1, 1)
    data = np.tile(np.array([3, 4], dtype=np.int8), rows).tobytes()
    return (_header(frame) + struct.pack("<II", rows, 1) + fields + struct.pack("<BII", 0, 2, 2)
            + struct.pack("<I", len(data)) + data + b"\x01")


def png_bytes(side: int = PNG_SIDE, frame: str = "camera") -> bytes:
    """A sensor_msgs/CompressedImage: a black 1-bit PNG of ``side`` x ``side`` pixels (deflate shrinks it to kB)."""
    out = io.BytesIO()
    Image.new("1", (side, side)).save(out, "PNG")
    data = out.getvalue()
    return _header(frame) + _string("png") + struct.pack("<I", len(data)) + data


BOMBS = {
    "cloud": ("sensor_msgs/PointCloud2", cloud_bytes),
    "scan": ("sensor_msgs/LaserScan", scan_bytes),
    "png": ("sensor_msgs/CompressedImage", png_bytes),
}
"""name: (type, builder) of each bomb."""


def publish_raw(spawn: Spawn, tmp_path: Path, topic: str, type_name: str, data: bytes, hz: float) -> Peer:
    """A rostui client process publishing ``data`` as ``type_name`` on ``topic`` at ``hz``, once it sent one."""
    path = tmp_path / f"{topic.strip('/').replace('/', '_')}.msg"
    path.write_bytes(data)
    peer = spawn([sys.executable, str(PUBLISHER), topic, type_name, str(path), f"{hz:g}"], label=f"raw {topic}")
    peer.wait_for("publishing")
    return peer
