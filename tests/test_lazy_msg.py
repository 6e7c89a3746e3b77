"""Messages read lazily for the views (rostui/models/sensors/lazy_msg.py): the same values as the generated
classes give, numeric arrays as numpy views over the received bytes, damaged bytes refused in one line."""

from __future__ import annotations

import tracemalloc
from typing import Any

import numpy as np
import pytest

from rostui.core.msg import Duration, Time, get_message_class, get_message_spec, md5sum
from rostui.core.node import AnyMsg
from rostui.models.sensors.lazy_msg import LazyArray, LazyDecodeError, decode_lazily, read_message

PoseStamped = get_message_class("geometry_msgs/PoseStamped")
TransformStamped = get_message_class("geometry_msgs/TransformStamped")
PointField = get_message_class("sensor_msgs/PointField")


def same(type_name: str, lazy: Any, eager: Any, where: str = "") -> None:
    """Every field of ``lazy`` equals the generated class's ``eager``, nested messages and arrays too."""
    for f in get_message_spec(type_name).fields:
        a, b, at = getattr(lazy, f.name), getattr(eager, f.name), f"{where}.{f.name}"
        if f.is_array and f.base_type not in ("string", "time", "duration") and f.is_builtin:
            assert isinstance(a, np.ndarray) and not a.flags.writeable, at
            expected = np.frombuffer(b, dtype=np.uint8) if isinstance(b, bytes) else np.asarray(b)
            assert np.array_equal(a.astype(expected.dtype), expected), at
        elif f.is_array and not f.is_builtin:
            assert isinstance(a, LazyArray) and len(a) == len(b), at
            for i, (x, y) in enumerate(zip(a, b)):
                same(f.base_type, x, y, f"{at}[{i}]")
        elif f.base_type in ("time", "duration") and not f.is_array:
            assert isinstance(a, Time if f.base_type == "time" else Duration) and (a.secs, a.nsecs) == (b.secs, b.nsecs)
        elif not f.is_builtin:
            same(f.base_type, a, b, at)
        else:
            assert a == b, at


def examples() -> list[Any]:
    """One message of each type the views draw, with values in every kind of field."""
    scan = get_message_class("sensor_msgs/LaserScan")(ranges=[1.0, 2.5, float("inf")], intensities=[7.0],
                                                      angle_min=-1.5, range_max=30.0)
    scan.header.frame_id, scan.header.stamp = "laser", Time(12, 345)
    cloud = get_message_class("sensor_msgs/PointCloud2")(
        height=1, width=2, point_step=8, row_step=16, data=bytes(range(16)), is_dense=True,
        fields=[PointField(name="x", offset=0, datatype=7, count=1), PointField(name="y", offset=4, datatype=7,
                                                                                 count=1)])
    path = get_message_class("nav_msgs/Path")(poses=[PoseStamped(), PoseStamped(), PoseStamped()])
    path.poses[1].header.frame_id, path.poses[2].pose.position.x = "odom", 5.5
    odom = get_message_class("nav_msgs/Odometry")(child_frame_id="base")
    odom.pose.covariance = [float(i) for i in range(36)]
    tf = get_message_class("tf2_msgs/TFMessage")(transforms=[TransformStamped(child_frame_id="a"),
                                                             TransformStamped(child_frame_id="bb")])
    grid = get_message_class("nav_msgs/OccupancyGrid")(data=[-1, 0, 100, 50])
    grid.info.width, grid.info.height = 2, 2
    image = get_message_class("sensor_msgs/Image")(height=1, width=2, encoding="mono8", step=2, data=b"\x01\x02")
    compressed = get_message_class("sensor_msgs/CompressedImage")(format="png", data=b"\x89PNG")
    poses = get_message_class("geometry_msgs/PoseArray")(poses=[PoseStamped().pose] * 4)
    return [scan, cloud, path, odom, tf, grid, image, compressed, poses]


@pytest.mark.parametrize("msg", examples(), ids=lambda m: m._type)
def test_read_lazily_as_the_generated_class_reads(msg: Any) -> None:
    same(msg._type, read_message(msg._type, msg.serialize()), msg)


def test_a_ten_million_range_scan_is_read_without_a_copy() -> None:
    scan = get_message_class("sensor_msgs/LaserScan")(ranges=[1.0])
    head = scan.serialize()[:-12]  # up to the ranges' length
    raw = head + (10_000_000).to_bytes(4, "little") + bytes(40_000_000) + bytes(4)
    tracemalloc.start()
    try:
        lazy = read_message("sensor_msgs/LaserScan", raw)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert len(lazy.ranges) == 10_000_000 and peak < 1_000_000


@pytest.mark.parametrize("cut", [1, 5, 30])
def test_damaged_bytes_are_one_line(cut: int) -> None:
    raw = examples()[2].serialize()  # a Path: strings and arrays of messages
    with pytest.raises(LazyDecodeError) as caught:
        read_message("nav_msgs/Path", raw[:-cut])
    text = str(caught.value)
    assert "\n" not in text and "bytes" in text, text


def test_a_length_beyond_the_message_is_refused_before_anything_is_built() -> None:
    raw = bytearray(examples()[2].serialize())
    at = 4 + 8 + 4  # the poses' count, after the header (seq, stamp, an empty frame_id)
    raw[at:at + 4] = (0xFFFFFFFF).to_bytes(4, "little")
    with pytest.raises(LazyDecodeError, match="needs .* bytes"):
        read_message("nav_msgs/Path", bytes(raw))


def test_only_known_types_with_their_md5sum_are_read_lazily() -> None:
    msg = examples()[0]
    raw = AnyMsg(msg.serialize())
    raw._connection_header = {"type": msg._type, "md5sum": md5sum(msg._type)}
    assert decode_lazily(raw) is not None
    raw._connection_header = {"type": msg._type, "md5sum": "0" * 32}
    assert decode_lazily(raw) is None
    raw._connection_header = {"type": "nobody_msgs/Unknown", "md5sum": "*"}
    assert decode_lazily(raw) is None
