"""Unit tests of the message layer: rostime, spec parsing, robustness, dynamic types, pub args, packages."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

from rostui.core import packages
from rostui.core.msg import (
    DeserializationError,
    MessageSpecError,
    MessageValueError,
    SerializationError,
    UnknownMessageTypeError,
    clear_cache,
    get_message_class,
    get_service_class,
    parse_msg_text,
    parse_srv_text,
    connection_class,
    definition_md5,
)
from rostui.core.msg.errors import Md5MismatchError
from rostui.core.msg.convert import (
    default_yaml_template,
    fill_message,
    message_from_yaml_args,
    message_to_dict,
    message_to_yaml,
)
from rostui.core.rostime import Duration, Time


# --------------------------------------------------------------------------- rostime
def test_time_normalizes_and_compares() -> None:
    t = Time(1, 1_500_000_000)
    assert (t.secs, t.nsecs) == (2, 500_000_000)
    assert Time.from_sec(2.5) == t
    assert t.to_nsec() == 2_500_000_000 and t.to_sec() == 2.5
    assert Time(3) > t and Time(0).is_zero() and not t.is_zero()
    assert hash(Time(2, 500_000_000)) == hash(t)
    assert isinstance(t - Time(1), Duration) and (t - Time(1)) == Duration(1, 500_000_000)
    assert t + Duration(0, 600_000_000) == Time(3, 100_000_000)
    with pytest.raises(TypeError):
        t - Duration(3)  # negative time, as in rospy
    with pytest.raises(TypeError):
        Time(-1)
    assert Time.now().secs > 1_600_000_000
    assert Time(1) != Duration(1)


def test_duration_negative_and_arithmetic() -> None:
    d = Duration(-1, 500_000_000)
    assert d.to_sec() == -0.5
    assert -d == Duration(0, 500_000_000)
    assert abs(d) == Duration(0, 500_000_000)
    assert Duration(1) * 3 == Duration(3) and Duration(3) / 2 == Duration(1, 500_000_000)
    assert Duration(3) / Duration(1) == 3.0
    assert Duration(2) < Duration(3)
    assert pickle.loads(pickle.dumps(d)) == d


# --------------------------------------------------------------------------- spec parsing
def test_parse_msg_constants_comments_and_resolution() -> None:
    spec = parse_msg_text(
        "# comment\nint32 A=1 # c\nstring S= hello # not a comment \nfloat64 F=1.5\nbool B=True\n"
        "Header header\nPoint p  # same package\ngeometry_msgs/Vector3[3] vs\nbyte b\nchar c\nuint8[] raw\n",
        "my_pkg/Thing",
    )
    assert [(c.type, c.name, c.value) for c in spec.constants] == [
        ("int32", "A", 1), ("string", "S", "hello # not a comment"), ("float64", "F", 1.5), ("bool", "B", True)]
    assert [f.type for f in spec.fields] == [
        "std_msgs/Header", "my_pkg/Point", "geometry_msgs/Vector3[3]", "byte", "char", "uint8[]"]
    assert spec.has_header
    assert spec.fields[2].array_len == 3 and spec.fields[5].array_len is None


@pytest.mark.parametrize("text,line", [
    ("int32 a\nfoo\n", 2),
    ("int32 a\nint32 1bad\n", 2),
    ("\n\nint8 X=300\n", 3),
    ("time T=1\n", 1),
    ("int32[x] a\n", 1),
    ("int32 a\nint32 a\n", 2),
])
def test_parse_errors_have_line_numbers(text: str, line: int) -> None:
    with pytest.raises(MessageSpecError) as ei:
        parse_msg_text(text, "p/T", "p/msg/T.msg")
    assert ei.value.line == line
    assert str(ei.value).startswith(f"p/msg/T.msg:{line}: ")


def test_parse_srv_halves() -> None:
    srv = parse_srv_text("int64 a\nint64 b\n---\nint64 sum\n", "p/AddTwoInts")
    assert srv.request.type_name == "p/AddTwoIntsRequest"
    assert [f.name for f in srv.response.fields] == ["sum"]


def test_unknown_types() -> None:
    with pytest.raises(UnknownMessageTypeError):
        get_message_class("std_msgs/NoSuchThing")
    with pytest.raises(UnknownMessageTypeError):
        get_message_class("no_such_pkg/X")
    with pytest.raises(UnknownMessageTypeError):
        get_message_class("not a type")
    with pytest.raises(UnknownMessageTypeError):
        get_service_class("std_srvs/Nope")


# --------------------------------------------------------------------------- classes
def test_class_attributes_and_construction() -> None:
    Log = get_message_class("rosgraph_msgs/Log")
    assert Log.DEBUG == 1 and Log.FATAL == 16 and Log._has_header
    assert Log.__slots__[:2] == ["header", "level"]  # a list, as genpy's
    m = Log(level=Log.INFO, msg="x")
    assert m.header.stamp == Time() and m.topics == [] and m.name == ""
    Twist = get_message_class("geometry_msgs/Twist")
    t = Twist(get_message_class("geometry_msgs/Vector3")(1.0, 2.0, 3.0))
    assert t.linear.y == 2.0 and t.angular.x == 0.0
    with pytest.raises(TypeError):
        Twist(1, 2, 3)
    with pytest.raises(TypeError):
        Twist(bogus=1)
    ci = get_message_class("sensor_msgs/CameraInfo")()
    assert ci.K == [0.0] * 9 and ci.D == []
    img = get_message_class("sensor_msgs/Image")()
    assert img.data == b""
    assert get_message_class("Header") is get_message_class("std_msgs/Header")
    # instance-style deserialize (rospy habit) fills the instance
    S = get_message_class("std_msgs/String")
    s = S()
    assert s.deserialize(S("abc").serialize()) is s and s.data == "abc"
    assert pickle.loads(pickle.dumps(S("p"))) == S("p")


def test_uint8_array_deserializes_as_bytes_and_accepts_lists() -> None:
    U = get_message_class("std_msgs/UInt8MultiArray")
    m = U(data=[1, 2, 3])
    back = U.deserialize(m.serialize())
    assert back.data == b"\x01\x02\x03"


def test_serialization_errors_are_clear() -> None:
    S = get_message_class("std_msgs/Int8")
    with pytest.raises(SerializationError, match="std_msgs/Int8"):
        S(data=1000).serialize()
    with pytest.raises(SerializationError):
        get_message_class("std_msgs/String")(data=5).serialize()
    with pytest.raises(SerializationError, match="expected 9"):
        ci = get_message_class("sensor_msgs/CameraInfo")()
        ci.K = [1.0]
        ci.serialize()


# --------------------------------------------------------------------------- robustness
@pytest.mark.parametrize("type_name", [
    "std_msgs/String", "sensor_msgs/Image", "rosgraph_msgs/Log", "sensor_msgs/PointCloud2",
    "geometry_msgs/PoseArray", "sensor_msgs/CameraInfo", "sensor_msgs/JointState",
])
def test_truncated_buffers_raise(type_name: str) -> None:
    cls = get_message_class(type_name)
    msg = cls()
    for f, t in zip(cls.__slots__, cls._slot_types):
        if t == "string":
            setattr(msg, f, "abc")
        elif t == "string[]":
            setattr(msg, f, ["a", "bb"])
        elif t == "uint8[]":
            setattr(msg, f, b"xyz")
        elif t == "float64[]":
            setattr(msg, f, [1.0, 2.0])
        elif t == "geometry_msgs/Pose[]":
            setattr(msg, f, [get_message_class("geometry_msgs/Pose")()])
    data = msg.serialize()
    assert cls.deserialize(data) == msg
    for cut in range(len(data)):
        with pytest.raises(DeserializationError):
            cls.deserialize(data[:cut])


def test_garbage_lengths_do_not_allocate_or_hang() -> None:
    S = get_message_class("std_msgs/String")
    with pytest.raises(DeserializationError):
        S.deserialize(b"\xff\xff\xff\xff abc")
    M = get_message_class("std_msgs/Float64MultiArray")
    with pytest.raises(DeserializationError):
        M.deserialize(b"\xff\xff\xff\x7f" + b"\x00" * 16)
    E = get_message_class("geometry_msgs/PoseArray")
    with pytest.raises(DeserializationError):
        E.deserialize(b"\x00" * 12 + b"\x00\x00\x00\x00" + b"\xff\xff\xff\xff")
    # invalid utf-8 decodes with replacement instead of crashing
    assert S.deserialize(b"\x02\x00\x00\x00\xff\xfe").data == "\ufffd\ufffd"


# --------------------------------------------------------------------------- dynamic types
def test_classes_from_a_definition_round_trip() -> None:
    Log = get_message_class("rosgraph_msgs/Log")
    cls = connection_class("rosgraph_msgs/Log", Log._md5sum, Log._full_text)
    assert cls is Log
    definition = (
        "Header header\nfoo_pkg/Inner[] items\nstring note\n"
        + "=" * 80 + "\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
        + "=" * 80 + "\nMSG: foo_pkg/Inner\nint32 K=3\nfloat32 v\nduration d\n"
    )
    md5 = definition_md5("foo_pkg/Outer", definition)
    Outer = connection_class("foo_pkg/Outer", md5, definition)
    assert Outer._md5sum == md5
    Inner = Outer._field_classes["foo_pkg/Inner"]
    assert Inner.K == 3
    o = Outer(note="n", items=[Inner(v=1.5, d=Duration(-1))])
    back = Outer.deserialize(o.serialize())
    assert back == o and back.items[0].d == Duration(-1)
    assert "MSG: foo_pkg/Inner" in Outer._full_text
    # a sender's definition with comments gives the same md5 as our files
    commented = "# the text\nstring data # payload\n"
    assert definition_md5("std_msgs/String", commented) == get_message_class("std_msgs/String")._md5sum


def test_a_conflicting_definition_of_a_type_we_know_is_refused() -> None:
    """It once built a private class; rostui's type now wins, as in ROS (the md5sums differ)."""
    with pytest.raises(Md5MismatchError, match="but our version has"):
        connection_class("std_msgs/String", definition_md5("std_msgs/String", "int32 data\n"), "int32 data\n")


# --------------------------------------------------------------------------- conversions
def test_dict_round_trip_and_fill_errors() -> None:
    Img = get_message_class("sensor_msgs/Image")
    m = fill_message(Img, {"header": {"frame_id": "c", "stamp": {"secs": 1, "nsecs": 2}}, "data": [1, 2]})
    d = message_to_dict(m)
    assert d["header"]["stamp"] == {"secs": 1, "nsecs": 2} and d["data"] == [1, 2]
    assert fill_message(Img, d) == m
    with pytest.raises(MessageValueError, match=r"header\.bogus"):
        fill_message(Img, {"header": {"bogus": 1}})
    with pytest.raises(MessageValueError, match="must be an integer"):
        fill_message(Img, {"height": "tall"})
    with pytest.raises(MessageValueError, match="out of range"):
        fill_message(Img, {"height": -1})
    with pytest.raises(MessageValueError, match="must be a string"):
        fill_message(Img, {"encoding": 5})
    with pytest.raises(MessageValueError, match="incorrect number"):
        fill_message(get_message_class("sensor_msgs/CameraInfo"), {"K": [1.0]})


def test_pub_args_semantics() -> None:
    Twist = get_message_class("geometry_msgs/Twist")
    m = message_from_yaml_args(Twist, ["[2.0, 0.0, 0.0]", "[0.0, 0.0, 1.8]"])
    assert m.linear.x == 2.0 and m.angular.z == 1.8
    m = message_from_yaml_args(Twist, ["{linear: {x: 1}, angular: {z: -1}}"])
    assert m.linear.x == 1.0 and m.angular.z == -1.0
    S = get_message_class("std_msgs/String")
    assert message_from_yaml_args(S, ["hello"]).data == "hello"
    assert message_from_yaml_args(S, ["data: hi there"]).data == "hi there"
    now = Time(123, 456)
    Ps = get_message_class("geometry_msgs/PointStamped")
    m = message_from_yaml_args(Ps, ["{header: auto, point: {x: 1.0}}"], now=now)
    assert m.header.stamp == now
    m = message_from_yaml_args(Ps, ["{header: {stamp: now, frame_id: base}}"], now=now)
    assert m.header.stamp == now and m.header.frame_id == "base"
    T = get_message_class("std_msgs/Time")
    assert message_from_yaml_args(T, ["now"], now=now).data == now
    assert message_from_yaml_args(T, ["{data: 1500000000}"]).data == Time(1, 500_000_000)
    with pytest.raises(MessageValueError, match="Not enough arguments"):
        message_from_yaml_args(Twist, ["[1, 2, 3]"])
    with pytest.raises(MessageValueError, match="Too many arguments"):
        message_from_yaml_args(S, ["a", "b"])
    with pytest.raises(MessageValueError, match="No key named"):
        message_from_yaml_args(Ps, ["{header: later}"])
    with pytest.raises(MessageValueError, match="not valid YAML"):
        message_from_yaml_args(S, ["{a: [}"])


def test_yaml_views() -> None:
    Log = get_message_class("rosgraph_msgs/Log")
    text = message_to_yaml(Log(name="/n", topics=["/a"]))
    assert text.startswith("header: \n  seq: 0\n  stamp: \n    secs: 0\n    nsecs:         0\n")
    assert str(Log()) == message_to_yaml(Log())
    assert default_yaml_template(get_message_class("std_msgs/String")) == "data: ''"
    assert default_yaml_template(get_message_class("geometry_msgs/Twist")).startswith("linear:\n  x: 0.0\n")


# --------------------------------------------------------------------------- packages
def test_package_discovery_and_ros_package_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    assert packages.find_package("std_msgs") == packages.BUILTIN_SHARE / "std_msgs"
    assert packages.find_package("nope") is None
    with pytest.raises(packages.PackageNotFoundError):
        packages.get_package_path("nope")
    ws = tmp_path / "ws" / "src"
    (ws / "deep" / "my_msgs" / "msg").mkdir(parents=True)
    (ws / "deep" / "my_msgs" / "package.xml").write_text("<package><name>my_msgs</name></package>")
    (ws / "deep" / "my_msgs" / "msg" / "Num.msg").write_text("int64 num\nstd_msgs/String s\n")
    (ws / "std_msgs").mkdir()
    (ws / "std_msgs" / "package.xml").write_text("<package><name>std_msgs</name></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ws"))
    found = packages.list_packages()
    assert found["my_msgs"] == ws / "deep" / "my_msgs"
    assert found["std_msgs"] == ws / "std_msgs"  # ROS_PACKAGE_PATH wins over built-ins
    assert found["geometry_msgs"] == packages.BUILTIN_SHARE / "geometry_msgs"
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(ws / "deep"))
    assert packages.find_package("std_msgs") == packages.BUILTIN_SHARE / "std_msgs"
    Num = get_message_class("my_msgs/Num")
    assert Num.deserialize(Num(num=-5).serialize()).num == -5
    clear_cache()
