"""Message layer vs. real ROS 1 (genpy/genmsg in the system Python): md5, full text, bytes, YAML."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from conftest import SYSTEM_PYTHON, need_peer
from rostui.core.msg import (
    get_message_class,
    get_service_class,
    list_message_types,
    list_service_types,
)
from rostui.core.msg.convert import fill_message, message_to_yaml
from rostui.core.packages import BUILTIN_SHARE

PACKAGES = ["std_msgs", "geometry_msgs", "sensor_msgs", "rosgraph_msgs", "std_srvs", "roscpp"]

_DUMP_TYPES = r'''
import importlib, json, sys
out = {}
for pkg in sys.argv[1:]:
    for kind in ("msg", "srv"):
        try:
            mod = importlib.import_module(pkg + "." + kind)
        except ImportError:
            continue
        for name in sorted(dir(mod)):
            cls = getattr(mod, name)
            if not isinstance(cls, type) or not hasattr(cls, "_md5sum"):
                continue
            if kind == "srv" and not hasattr(cls, "_request_class"):
                continue
            if kind == "msg":
                out[cls._type] = {"kind": "msg", "md5": cls._md5sum, "full_text": cls._full_text,
                                  "slot_types": list(cls._slot_types), "slots": list(cls.__slots__)}
            else:
                halves = {}
                for k, c in (("req", cls._request_class), ("resp", cls._response_class)):
                    halves[k] = {"type": c._type, "md5": c._md5sum, "full_text": c._full_text}
                out[cls._type] = {"kind": "srv", "md5": cls._md5sum, **halves}
print(json.dumps(out))
'''


def _system_python_ok() -> bool:
    if not Path(SYSTEM_PYTHON).exists():
        return False
    r = subprocess.run([SYSTEM_PYTHON, "-c", "import genpy, genmsg, std_msgs.msg, geometry_msgs.msg, sensor_msgs.msg, "
                        "rosgraph_msgs.msg, std_srvs.srv, roscpp.msg, rostopic"], capture_output=True)
    return r.returncode == 0


@pytest.fixture(scope="module")
def oracle_types() -> dict[str, Any]:
    """Every msg/srv type of Debian's python3-*-msgs packages, as genpy sees it."""
    need_peer(_system_python_ok(), "genpy + python3-{std,geometry,sensor,rosgraph}-msgs, std-srvs, roscpp-msg, rostopic")
    r = subprocess.run([SYSTEM_PYTHON, "-c", _DUMP_TYPES, *PACKAGES], capture_output=True, text=True, check=True)
    return json.loads(r.stdout)


def test_every_debian_type_exists_here(oracle_types: dict[str, Any]) -> None:
    ours = set()
    for pkg in PACKAGES:
        ours.update(list_message_types(pkg))
        ours.update(list_service_types(pkg))
    assert set(oracle_types) <= ours
    assert len(oracle_types) > 90


def test_md5_and_full_text_match_genpy(oracle_types: dict[str, Any]) -> None:
    problems = []
    for t, e in sorted(oracle_types.items()):
        if e["kind"] == "msg":
            cls = get_message_class(t)
            if cls._md5sum != e["md5"]:
                problems.append(f"{t}: md5 {cls._md5sum} != {e['md5']}")
            if cls._full_text != e["full_text"]:
                problems.append(f"{t}: full_text differs")
            if cls._slot_types != e["slot_types"] or list(cls.__slots__) != e["slots"]:
                problems.append(f"{t}: slots differ")
        else:
            srv = get_service_class(t)
            if srv._md5sum != e["md5"]:
                problems.append(f"{t}: srv md5 {srv._md5sum} != {e['md5']}")
            for k, c in (("req", srv._request_class), ("resp", srv._response_class)):
                if c._type != e[k]["type"] or c._md5sum != e[k]["md5"]:
                    problems.append(f"{t}: {k} {c._type} {c._md5sum} != {e[k]['type']} {e[k]['md5']}")
                if c._full_text != e[k]["full_text"]:
                    problems.append(f"{t}: {k} full_text differs")
    assert not problems, "\n".join(problems)


def test_full_text_layout_matches_genmsg_rules() -> None:
    """Separators and MSG: lines, depth first, each nested type once, no trailing newline."""
    text = get_message_class("geometry_msgs/PoseWithCovarianceStamped")._full_text
    heads = re.findall(r"^MSG: (.*)$", text, flags=re.M)
    assert heads == ["std_msgs/Header", "geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose",
                     "geometry_msgs/Point", "geometry_msgs/Quaternion"]
    assert text.count("\n" + "=" * 80 + "\n") == 5
    assert not text.endswith("\n\n")


# --------------------------------------------------------------------------- serialization + YAML
_GENPY_CASES = r'''
import json, sys, genpy, importlib
from genpy.message import fill_message_args, strify_message
import rostopic
cases = json.load(sys.stdin)
out = []
def cls_of(t):
    pkg, name = t.split("/")
    return getattr(importlib.import_module(pkg + ".msg"), name)
for c in cases:
    cls = cls_of(c["type"])
    m = cls()
    fill_message_args(m, [c["values"]])
    for path, v in c.get("bytes", {}).items():
        obj = m
        parts = path.split(".")
        for p in parts[:-1]:
            obj = getattr(obj, p)
        setattr(obj, parts[-1], bytes(v))
    data = m.serialize_numpy if False else None
    import io
    buf = io.BytesIO(); m.serialize(buf); data = buf.getvalue()
    back = cls().deserialize(data)
    tr = rostopic.create_value_transform(True, True)
    tr_arr = rostopic.create_value_transform(False, True)
    out.append({
        "hex": data.hex(),
        "yaml": strify_message(m),
        "yaml_back": strify_message(back),
        "yaml_noarr_nostr": strify_message(tr(back)),
        "yaml_noarr": strify_message(tr_arr(back)),
        "yaml_w": strify_message(back, fixed_numeric_width=4),
    })
print(json.dumps(out))
'''

CASES: list[dict[str, Any]] = [
    {"type": "std_msgs/String", "values": {"data": "hello"}},
    {"type": "std_msgs/String", "values": {"data": "h\u00e9llo w\u00f6rld \u2603 \U0001F600"}},
    {"type": "std_msgs/String", "values": {"data": ""}},
    {"type": "std_msgs/String", "values": {"data": "yes"}},
    {"type": "std_msgs/String", "values": {"data": "line1\nline2 'quoted' \"dq\" : # x"}},
    {"type": "std_msgs/String", "values": {"data": "x" * 200}},
    {"type": "std_msgs/Int8", "values": {"data": -128}},
    {"type": "std_msgs/UInt64", "values": {"data": 2**64 - 1}},
    {"type": "std_msgs/Float32", "values": {"data": 1.5}},
    {"type": "std_msgs/Float64", "values": {"data": 3.141592653589793}},
    {"type": "std_msgs/Bool", "values": {"data": True}},
    {"type": "std_msgs/Char", "values": {"data": 200}},
    {"type": "std_msgs/Byte", "values": {"data": -5}},
    {"type": "std_msgs/Time", "values": {"data": {"secs": 1700000000, "nsecs": 123456789}}},
    {"type": "std_msgs/Duration", "values": {"data": {"secs": -3, "nsecs": 500}}},
    {"type": "std_msgs/Header", "values": {"seq": 7, "stamp": {"secs": 12, "nsecs": 34}, "frame_id": "map"}},
    {"type": "std_msgs/Float64MultiArray", "values": {
        "layout": {"dim": [{"label": "rows", "size": 2, "stride": 6}, {"label": "cols", "size": 3, "stride": 3}],
                   "data_offset": 1},
        "data": [1.0, 2.5, -3.25, 4.0, 5.0, 6.0]}},
    {"type": "std_msgs/Int32MultiArray", "values": {"layout": {"dim": [], "data_offset": 0}, "data": [1, -2, 3]}},
    {"type": "std_msgs/UInt8MultiArray", "values": {"layout": {"dim": [], "data_offset": 0}, "data": [0, 1, 255]}},
    {"type": "std_msgs/ColorRGBA", "values": {"r": 0.5, "g": 0.25, "b": 1.0, "a": 0.0}},
    {"type": "geometry_msgs/Twist", "values": {"linear": {"x": 2.0, "y": 0.0, "z": 0.0},
                                               "angular": {"x": 0.0, "y": 0.0, "z": -1.8}}},
    {"type": "geometry_msgs/PoseWithCovarianceStamped", "values": {
        "header": {"seq": 1, "stamp": {"secs": 5, "nsecs": 6}, "frame_id": "odom"},
        "pose": {"pose": {"position": {"x": 1.0, "y": 2.0, "z": 3.0},
                          "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}},
                 "covariance": [float(i) / 7 for i in range(36)]}}},
    {"type": "geometry_msgs/PolygonStamped", "values": {
        "header": {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": ""},
        "polygon": {"points": [{"x": 1.0, "y": 2.0, "z": 0.0}, {"x": -1.0, "y": 0.5, "z": 0.25}]}}},
    {"type": "geometry_msgs/PoseArray", "values": {
        "header": {"seq": 3, "stamp": {"secs": 1, "nsecs": 2}, "frame_id": "w"}, "poses": []}},
    {"type": "sensor_msgs/Image", "values": {
        "header": {"seq": 9, "stamp": {"secs": 100, "nsecs": 200}, "frame_id": "cam"},
        "height": 2, "width": 3, "encoding": "rgb8", "is_bigendian": 0, "step": 9,
        "data": list(range(18))}},
    {"type": "sensor_msgs/PointCloud2", "values": {
        "header": {"seq": 1, "stamp": {"secs": 1, "nsecs": 1}, "frame_id": "lidar"},
        "height": 1, "width": 2,
        "fields": [{"name": "x", "offset": 0, "datatype": 7, "count": 1},
                   {"name": "y", "offset": 4, "datatype": 7, "count": 1}],
        "is_bigendian": False, "point_step": 8, "row_step": 16, "data": [7] * 16, "is_dense": True}},
    {"type": "sensor_msgs/CameraInfo", "values": {
        "header": {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": "c"},
        "height": 480, "width": 640, "distortion_model": "plumb_bob",
        "D": [0.1, -0.2, 0.0, 0.0, 0.0],
        "K": [500.0, 0.0, 320.0, 0.0, 500.0, 240.0, 0.0, 0.0, 1.0],
        "R": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        "P": [500.0, 0.0, 320.0, 0.0, 0.0, 500.0, 240.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        "binning_x": 0, "binning_y": 0,
        "roi": {"x_offset": 1, "y_offset": 2, "height": 3, "width": 4, "do_rectify": True}}},
    {"type": "sensor_msgs/LaserScan", "values": {
        "header": {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": "laser"},
        "angle_min": -1.5, "angle_max": 1.5, "angle_increment": 0.5, "time_increment": 0.0,
        "scan_time": 0.1, "range_min": 0.1, "range_max": 30.0,
        "ranges": [1.0, 2.0, 3.5, 0.25, 8.0, 9.0, 10.0], "intensities": []}},
    {"type": "sensor_msgs/JointState", "values": {
        "header": {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": ""},
        "name": ["j1", "j\u00e4 2", "yes", ""], "position": [0.5, 1.5, 2.5, 3.5], "velocity": [], "effort": []}},
    {"type": "sensor_msgs/NavSatFix", "values": {
        "header": {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": "gps"},
        "status": {"status": -1, "service": 1}, "latitude": 48.1, "longitude": 11.5, "altitude": 500.0,
        "position_covariance": [0.0] * 9, "position_covariance_type": 2}},
    {"type": "sensor_msgs/JoyFeedbackArray", "values": {"array": [
        {"type": 1, "id": 2, "intensity": 0.5}, {"type": 0, "id": 0, "intensity": 1.0}]}},
    {"type": "rosgraph_msgs/Log", "values": {
        "header": {"seq": 4, "stamp": {"secs": 1700000000, "nsecs": 5}, "frame_id": ""},
        "level": 2, "name": "/talker", "msg": "hello world 42", "file": "talker.py", "function": "main",
        "line": 17, "topics": ["/chatter", "/rosout"]}},
    {"type": "rosgraph_msgs/Clock", "values": {"clock": {"secs": 99, "nsecs": 999999999}}},
    {"type": "rosgraph_msgs/TopicStatistics", "values": {
        "topic": "/t", "node_pub": "/a", "node_sub": "/b",
        "window_start": {"secs": 1, "nsecs": 0}, "window_stop": {"secs": 2, "nsecs": 0},
        "delivered_msgs": 10, "dropped_msgs": 0, "traffic": 1000,
        "period_mean": {"secs": 0, "nsecs": 100000000}, "period_stddev": {"secs": 0, "nsecs": 0},
        "period_max": {"secs": 0, "nsecs": 2}, "stamp_age_mean": {"secs": 0, "nsecs": 0},
        "stamp_age_stddev": {"secs": 0, "nsecs": 0}, "stamp_age_max": {"secs": 0, "nsecs": 0}}},
    {"type": "roscpp/Logger", "values": {"name": "ros.roscpp", "level": "info"}},
]


@pytest.fixture(scope="module")
def genpy_results() -> list[dict[str, Any]]:
    """genpy's bytes and strify output for each case in CASES."""
    need_peer(_system_python_ok(), "genpy + rostopic (system python)")
    r = subprocess.run([SYSTEM_PYTHON, "-c", _GENPY_CASES], input=json.dumps(CASES),
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def _ours(case: dict[str, Any]) -> Any:
    return fill_message(get_message_class(case["type"]), case["values"])


@pytest.mark.parametrize("i", range(len(CASES)), ids=[f"{c['type']}-{n}" for n, c in enumerate(CASES)])
def test_serialize_matches_genpy(i: int, genpy_results: list[dict[str, Any]]) -> None:
    case, want = CASES[i], genpy_results[i]
    msg = _ours(case)
    data = msg.serialize()
    assert data.hex() == want["hex"]
    cls = get_message_class(case["type"])
    back = cls.deserialize(bytes.fromhex(want["hex"]))
    assert back.serialize() == data
    assert cls.deserialize(memoryview(data)) == back
    assert message_to_yaml(msg) == want["yaml"]
    assert message_to_yaml(back) == want["yaml_back"]
    assert message_to_yaml(back, noarr=True, nostr=True) == want["yaml_noarr_nostr"]
    assert message_to_yaml(back, noarr=True) == want["yaml_noarr"]
    assert message_to_yaml(back, fixed_numeric_width=4) == want["yaml_w"]


# --------------------------------------------------------------------------- turtlesim via genpy's generators
TURTLESIM_MSGS = ["Pose", "Color", "Velocity"]
TURTLESIM_SRVS = ["Spawn", "Kill", "SetPen", "TeleportAbsolute", "TeleportRelative"]


def test_turtlesim_book_md5s() -> None:
    assert get_message_class("turtlesim/Pose")._md5sum == "863b248d5016ca62ea2e895ae5265cf9"
    assert get_message_class("turtlesim/Velocity")._md5sum == "9d5c2dcd348ac8f76ce2a4307bd63a13"


def test_turtlesim_md5s_match_genpy_generators(tmp_path: Path) -> None:
    gen_msg, gen_srv = Path("/usr/lib/genpy/genmsg_py.py"), Path("/usr/lib/genpy/gensrv_py.py")
    need_peer(gen_msg.exists() and gen_srv.exists() and _system_python_ok(), "genpy generators (python3-genpy)")
    share = BUILTIN_SHARE
    inc = [f"-Iturtlesim:{share}/turtlesim/msg", f"-Istd_msgs:{share}/std_msgs/msg"]
    out_msg, out_srv = tmp_path / "turtlesim" / "msg", tmp_path / "turtlesim" / "srv"
    for name in TURTLESIM_MSGS:
        subprocess.run([SYSTEM_PYTHON, str(gen_msg), "-p", "turtlesim", "-o", str(out_msg), *inc,
                        str(share / "turtlesim" / "msg" / f"{name}.msg")], check=True, capture_output=True)
    for name in TURTLESIM_SRVS:
        subprocess.run([SYSTEM_PYTHON, str(gen_srv), "-p", "turtlesim", "-o", str(out_srv), *inc,
                        str(share / "turtlesim" / "srv" / f"{name}.srv")], check=True, capture_output=True)
    subprocess.run([SYSTEM_PYTHON, str(gen_msg), "--initpy", "-p", "turtlesim", "-o", str(out_msg)], check=True)
    subprocess.run([SYSTEM_PYTHON, str(gen_srv), "--initpy", "-p", "turtlesim", "-o", str(out_srv)], check=True)
    (tmp_path / "turtlesim" / "__init__.py").write_text("")
    script = (
        "import json, turtlesim.msg as m, turtlesim.srv as s\n"
        f"print(json.dumps({{**{{n: getattr(m, n)._md5sum for n in {TURTLESIM_MSGS!r}}}, "
        f"**{{n: getattr(s, n)._md5sum for n in {TURTLESIM_SRVS!r}}}}}))\n"
    )
    r = subprocess.run([SYSTEM_PYTHON, "-c", script], capture_output=True, text=True, check=True,
                       env={"PYTHONPATH": str(tmp_path), "PATH": "/usr/bin:/bin"})
    want = json.loads(r.stdout)
    for name in TURTLESIM_MSGS:
        assert get_message_class(f"turtlesim/{name}")._md5sum == want[name], name
    for name in TURTLESIM_SRVS:
        assert get_service_class(f"turtlesim/{name}")._md5sum == want[name], name
    assert want["Pose"] == "863b248d5016ca62ea2e895ae5265cf9"
