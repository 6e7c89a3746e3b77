"""The inspector's text of a large message (rostui/models/sensors/lazy_text.py): laid out as ``rostopic echo``
prints it, each array cut to its first items and its length."""

from __future__ import annotations

from rostui.core.msg import get_message_class
from rostui.core.msg.convert import message_to_yaml
from rostui.models.monitor.tree import ARRAY_SHOWN
from rostui.models.sensors.lazy_msg import read_message
from rostui.models.sensors.lazy_text import lazy_text


def cloud(data: bytes) -> object:
    """A PointCloud2 of two fields holding ``data``."""
    cls, field = get_message_class("sensor_msgs/PointCloud2"), get_message_class("sensor_msgs/PointField")
    msg = cls(height=1, width=len(data) // 8, point_step=8, row_step=len(data), data=data, is_dense=True,
              fields=[field(name="x", offset=0, datatype=7, count=1), field(name="y", offset=4, datatype=7, count=1)])
    msg.header.frame_id = "base"
    msg.header.stamp.secs = 5
    return msg


def test_short_arrays_read_as_rostopic_echo_prints_them() -> None:
    scan = get_message_class("sensor_msgs/LaserScan")(angle_min=-1.5, ranges=[1.0, 2.5], intensities=[])
    tf = get_message_class("tf2_msgs/TFMessage")()
    tf.transforms = [get_message_class("geometry_msgs/TransformStamped")(child_frame_id="a b: 'x'")]
    tf.transforms[0].header.stamp.secs = 7
    tf.transforms[0].transform.rotation.w = 1.0
    for msg in (cloud(bytes(8)), scan, tf):
        assert lazy_text(read_message(msg._type, msg.serialize())) == message_to_yaml(msg)


def test_a_long_array_shows_its_first_items_and_its_length() -> None:
    msg = cloud(bytes(range(16)))
    text = lazy_text(read_message(msg._type, msg.serialize()))
    shown = ", ".join(str(i) for i in range(ARRAY_SHOWN))
    assert f"\ndata: [{shown}, … (16 items)]\n" in text
    assert text.replace(f"[{shown}, … (16 items)]", str(list(range(16)))) == message_to_yaml(msg)
