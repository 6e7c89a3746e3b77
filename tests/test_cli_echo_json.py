"""`rostui topic echo --json`: one JSON object a line (JSON Lines), from real rospy and rostopic publishers and from
a bag written by Debian's rosbag; -n, fields, --offset, --noarr/--nostr, and the options it cannot go with."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from cli_helpers import rostui
from conftest import SYSTEM_PYTHON, need_command, need_peer
from interop_helpers import Peer, Spawn, rospy_peer, spawn  # noqa: F401

IMAGE = {
    "header": {"seq": None, "stamp": {"secs": 1700000000, "nsecs": 123}, "frame_id": "cam"},
    "height": 2, "width": 2, "encoding": "mono8", "is_bigendian": 0, "step": 2, "data": [0, 1, 2, 255],
}


def records(text: str) -> list[object]:
    """Each stdout line parsed on its own, as `jq` reads JSON Lines (strict JSON: no NaN literals)."""

    def refuse(constant: str) -> object:
        raise AssertionError(f"non-standard JSON constant {constant}")

    lines = text.splitlines()
    assert lines and all(line.strip() for line in lines), text
    return [json.loads(line, parse_constant=refuse) for line in lines]


def without_seq(image: object) -> object:
    assert isinstance(image, dict) and isinstance(image["header"]["seq"], int)
    return {**image, "header": {**image["header"], "seq": None}}


@pytest.fixture
def shapes(any_master: str, ros_env: dict[str, str], spawn: Spawn, rospy_available: None) -> Peer:
    """A rospy node publishing the /image and /point of tests/peers/rospy_shapes_talker.py."""
    peer = spawn(rospy_peer("rospy_shapes_talker.py"), label="shapes")
    peer.wait_for("ready")
    return peer


def test_rospy_messages_as_json_lines(shapes: Peer, ros_env: dict[str, str]) -> None:
    ours = rostui(["topic", "echo", "--json", "-n", "3", "/image"], ros_env)
    assert ours.returncode == 0, ours.stderr
    images = records(ours.stdout)
    assert len(images) == 3
    assert [without_seq(i) for i in images] == [IMAGE] * 3
    assert [list(i) for i in images] == [list(IMAGE)] * 3  # fields in message order
    assert list(images[0]["header"]) == ["seq", "stamp", "frame_id"]


def test_fields_and_non_finite_floats(shapes: Peer, ros_env: dict[str, str]) -> None:
    point = records(rostui(["topic", "echo", "--json", "-n", "1", "/point"], ros_env).stdout)[0]
    assert point["point"] == {"x": "nan", "y": "inf", "z": -1.5}
    assert point["header"]["stamp"] == {"secs": 5, "nsecs": 500000000}
    assert records(rostui(["topic", "echo", "--json", "-n", "2", "/image/data"], ros_env).stdout) == [[0, 1, 2, 255]] * 2
    assert records(rostui(["topic", "echo", "--json", "-n", "1", "/point/point/z"], ros_env).stdout) == [-1.5]
    assert records(rostui(["topic", "echo", "--json", "-n", "1", "/image/header/stamp"], ros_env).stdout) == \
        [{"secs": 1700000000, "nsecs": 123}]
    assert records(rostui(["topic", "echo", "--json", "-n", "1", "/image/encoding"], ros_env).stdout) == ["mono8"]
    trimmed = records(rostui(["topic", "echo", "--json", "--noarr", "--nostr", "-n", "1", "/image"], ros_env).stdout)[0]
    assert list(trimmed) == ["header", "height", "width", "is_bigendian", "step"]
    assert list(trimmed["header"]) == ["seq", "stamp"]


def test_real_rostopic_pub_and_offset(any_master: str, ros_env: dict[str, str], spawn: Spawn) -> None:
    need_command("rostopic")
    spawn(["rostopic", "pub", "-r", "10", "-s", "/stamped", "geometry_msgs/PointStamped",
           "{header: {stamp: now, frame_id: base}, point: {x: 1.25}}"], label="rostopic pub")
    ours = rostui(["topic", "echo", "--json", "-n", "2", "/stamped"], ros_env)
    assert ours.returncode == 0, ours.stderr
    first, second = records(ours.stdout)
    assert first["point"] == second["point"] == {"x": 1.25, "y": 0.0, "z": 0.0}
    assert first["header"]["frame_id"] == "base" and first["header"]["stamp"]["secs"] > 1_600_000_000
    assert second["header"]["seq"] == first["header"]["seq"] + 1
    age = records(rostui(["topic", "echo", "--json", "--offset", "-n", "1", "/stamped/header/stamp"],
                         ros_env).stdout)[0]
    assert set(age) == {"secs", "nsecs"} and 0 <= age["nsecs"] < 1_000_000_000
    assert -60 < age["secs"] + age["nsecs"] / 1e9 <= 1  # now minus a fresh stamp: a small offset, not an epoch time


#: A bag written by Debian's rosbag: the shapes above, two of each, at bag times 10 s and 11 s.
MAKE = """
import sys, rosbag, rospy
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import Image
image = Image(height=2, width=2, encoding="mono8", is_bigendian=0, step=2, data=bytes([0, 1, 2, 255]))
image.header.stamp = rospy.Time(1700000000, 123)
image.header.frame_id = "cam"
point = PointStamped()
point.point.x = 2.5
with rosbag.Bag(sys.argv[1], "w") as bag:
    for i in range(2):
        image.header.seq = i
        bag.write("/image", image, rospy.Time(10 + i))
        bag.write("/point", point, rospy.Time(10 + i, 5))
"""


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag, rospy, geometry_msgs, sensor_msgs"],
                           capture_output=True)
    need_peer(probe.returncode == 0, "rosbag Python API with the message packages (Debian python3-rosbag)")
    path = tmp_path_factory.mktemp("json") / "shapes.bag"
    made = subprocess.run([SYSTEM_PYTHON, "-c", MAKE, str(path)], capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    return path


def test_bag_messages_as_json_lines(bag: Path, ros_env: dict[str, str]) -> None:
    ours = rostui(["topic", "echo", "-b", str(bag), "--json", "/image"], ros_env)
    assert ours.returncode == 0, ours.stderr
    images = records(ours.stdout)
    assert [i["header"]["seq"] for i in images] == [0, 1]
    assert [without_seq(i) for i in images] == [IMAGE, IMAGE]
    every = records(rostui(["topic", "echo", "-b", str(bag), "--json", "-a", "-n", "3"], ros_env).stdout)
    assert [sorted(m) for m in every] == [sorted(IMAGE), ["header", "point"], sorted(IMAGE)]
    assert records(rostui(["topic", "echo", "-b", str(bag), "--json", "/point/point/x"], ros_env).stdout) == [2.5, 2.5]


@pytest.mark.parametrize("flag", [["-p"], ["-c"], ["-w", "4"]], ids=lambda f: f[0])
def test_json_refuses_other_formats(ros_env: dict[str, str], flag: list[str]) -> None:
    ours = rostui(["topic", "echo", "--json", *flag, "/image"], ros_env)
    assert ours.returncode == 1 and ours.stdout == ""
    assert ours.stderr == "ERROR: --json cannot be combined with -p, -c or -w\n"
