"""Standard ROS 1 MCAP files, which carry no md5sum in their channel metadata (the ``mcap`` tools, Foxglove and
``mcap-ros1-support`` write them so): rostui computes each type's md5 from the schema's definition for info,
convert, play and bag view, and real rosbag and rospy accept the result.

The files are written by ``mcap-ros1-support``'s writer with message classes that its own vendored genpy
builds from Debian's ``_full_text``; the expected md5s are Debian's generated ``_md5sum`` (genmsg's).
"""

from __future__ import annotations

import io
import json
import re
import subprocess
from pathlib import Path
from typing import Any

import pytest
from mcap.reader import make_reader
from mcap.writer import Writer as McapWriter
from mcap_ros1.writer import Writer as Ros1Writer

from rostui.core.bag.files import open_reader
from rostui.core.bag.index import load_index
from rostui.core.bag.schema_md5 import UNKNOWN_MD5, definition_md5, schema_md5

from cli_helpers import rostui
from conftest import REPO, SYSTEM_PYTHON, need_command, need_peer, rostui_cmd, wait_until
from interop_helpers import Peer, rospy_peer, run_tool, spawn  # noqa: F401  (spawn is a fixture)

TOPICS = {
    "/pose": "geometry_msgs/PoseStamped",
    "/imu": "sensor_msgs/Imu",
    "/chatter": "std_msgs/String",
    "/fix": "sensor_msgs/NavSatFix",  # constants, in it and in its nested NavSatStatus
}
PER_TOPIC = 5
T0 = 1_700_000_000_000_000_000
STEP = 50_000_000  # 50 ms between messages, topics interleaved

DEBIAN_TYPES = """
import importlib, json, sys
out = {}
for type_name in sys.argv[1:]:
    package, name = type_name.split("/")
    cls = getattr(importlib.import_module(package + ".msg"), name)
    out[type_name] = [cls._md5sum, cls._full_text]
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def debian() -> dict[str, tuple[str, str]]:
    """``type -> (md5sum, full text)`` from Debian's generated rospy message modules."""
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import geometry_msgs.msg, sensor_msgs.msg, std_msgs.msg"],
                           capture_output=True)
    need_peer(probe.returncode == 0, "Debian's python3-geometry-msgs, python3-sensor-msgs, python3-std-msgs")
    out = subprocess.run([SYSTEM_PYTHON, "-c", DEBIAN_TYPES, *TOPICS.values()], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    return {t: (md5, text) for t, (md5, text) in json.loads(out.stdout).items()}


def _fill(msg: Any, type_name: str, i: int) -> None:
    """Give message ``i`` of a type values of its own, in nested fields, arrays and strings."""
    if hasattr(msg, "header"):
        msg.header.seq = i
        msg.header.stamp.secs, msg.header.stamp.nsecs = 1_700_000_000 + i, 1000 * i
        msg.header.frame_id = f"frame_{i}"
    if type_name == "geometry_msgs/PoseStamped":
        msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 0.5 * i, -1.25, 3.0 + i
        msg.pose.orientation.w = 1.0
    elif type_name == "sensor_msgs/Imu":
        msg.orientation.z, msg.orientation.w = 0.1 * i, 0.99
        msg.angular_velocity.z = -0.25 * i
        msg.linear_acceleration.x = 9.81
        msg.orientation_covariance = [float(i + k) for k in range(9)]
        msg.linear_acceleration_covariance = [-1.0] + [0.0] * 8
    elif type_name == "std_msgs/String":
        msg.data = f"hello world {i} ✓"
    elif type_name == "sensor_msgs/NavSatFix":
        msg.status.status, msg.status.service = 0, 1
        msg.latitude, msg.longitude, msg.altitude = 48.1 + i / 1000, 11.5, 520.0
        msg.position_covariance = [0.5] * 9
        msg.position_covariance_type = 2


def write_standard_mcap(path: Path, debian: dict[str, tuple[str, str]]) -> dict[str, list[str]]:
    """A ROS 1 MCAP as ``mcap-ros1-support`` writes it; returns each topic's serialized messages (hex)."""
    from mcap_ros1._vendor.genpy.dynamic import generate_dynamic

    classes = {t: generate_dynamic(t, debian[t][1])[t] for t in TOPICS.values()}
    sent: dict[str, list[str]] = {topic: [] for topic in TOPICS}
    with Ros1Writer(str(path)) as writer:
        for i in range(PER_TOPIC):
            for k, (topic, type_name) in enumerate(TOPICS.items()):
                msg = classes[type_name]()
                _fill(msg, type_name, i)
                writer.write_message(topic, msg, log_time=T0 + (i * len(TOPICS) + k) * STEP)
                out = io.BytesIO()
                msg.serialize(out)
                sent[topic].append(out.getvalue().hex())
    return sent


@pytest.fixture
def standard(tmp_path: Path, debian: dict[str, tuple[str, str]]) -> tuple[Path, dict[str, list[str]]]:
    """A standard ROS 1 MCAP file and the messages in it."""
    path = tmp_path / "standard.mcap"
    return path, write_standard_mcap(path, debian)


def _types_in(text: str) -> dict[str, str]:
    """``type -> md5`` from the ``types:`` rows of rosbag info's (or rostui's) output."""
    return dict(re.findall(r"^(?:types:)?\s+(\S+/\S+)\s+\[(\S*)\]\s*$", text, re.M))


def test_the_mcap_ros1_writer_stores_no_md5sum(standard: tuple[Path, dict[str, list[str]]]) -> None:
    path, _sent = standard
    with path.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None and len(summary.channels) == len(TOPICS)
    for channel in summary.channels.values():
        assert "md5sum" not in channel.metadata and "callerid" not in channel.metadata
        assert channel.message_encoding == "ros1"
        assert summary.schemas[channel.schema_id].encoding == "ros1msg"


def test_the_reader_computes_genmsgs_md5_and_keeps_the_rest(standard: tuple[Path, dict[str, list[str]]],
                                                            debian: dict[str, tuple[str, str]]) -> None:
    path, sent = standard
    reader = open_reader(str(path))
    summary = reader.summary()
    got: dict[str, list[str]] = {}
    for conn, _t, data in reader.messages():
        got.setdefault(conn.topic, []).append(data.hex())
    reader.close()
    conns = {c.topic: c for c in summary.connections}
    assert {topic: (c.type, c.md5sum) for topic, c in conns.items()} == \
        {topic: (t, debian[t][0]) for topic, t in TOPICS.items()}
    assert all(c.definition == debian[c.type][1] and c.callerid == "" and not c.latching for c in conns.values())
    assert got == sent


def test_bag_info_prints_the_md5s_without_a_warning(standard: tuple[Path, dict[str, list[str]]],
                                                    debian: dict[str, tuple[str, str]],
                                                    ros_env: dict[str, str]) -> None:
    path, _sent = standard
    result = rostui(["bag", "info", str(path)], ros_env)
    assert result.returncode == 0 and result.stderr == "", result.stderr
    assert re.search(r"^version: +0 \(ros1 profile\)$", result.stdout, re.M), result.stdout
    assert _types_in(result.stdout) == {t: debian[t][0] for t in TOPICS.values()}, result.stdout
    as_json = json.loads(rostui(["bag", "info", "--json", str(path)], ros_env).stdout)
    assert {row["type"]: row["md5sum"] for row in as_json["types"]} == {t: debian[t][0] for t in TOPICS.values()}


def test_bag_info_names_the_profile_the_file_declares(ros_env: dict[str, str]) -> None:
    """A ROS 2 MCAP (rosbag2's, tests/bag_corpus) is not called a ros1 profile file."""
    result = rostui(["bag", "info", str(REPO / "tests" / "bag_corpus" / "talker.mcap")], ros_env)
    assert result.returncode == 0, result.stderr
    assert re.search(r"^version: +0 \(ros2 profile\)$", result.stdout, re.M), result.stdout


def test_each_definition_is_parsed_once(standard: tuple[Path, dict[str, list[str]]], tmp_path: Path,
                                        debian: dict[str, tuple[str, str]]) -> None:
    path, _sent = standard
    with path.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    schema = summary.schemas[1]
    many = tmp_path / "many_channels.mcap"
    with many.open("wb") as f:  # 40 channels of one schema, as a fleet of robots' topics would be
        writer = McapWriter(f)
        writer.start(profile="ros1", library="test")
        schema_id = writer.register_schema(schema.name, schema.encoding, schema.data)
        for n in range(40):
            channel = writer.register_channel(f"/robot{n}/data", "ros1", schema_id)
            writer.add_message(channel, log_time=n, publish_time=n, data=b"")
        writer.finish()
    schema_md5.cache_clear()
    for name in (many, path, many):
        reader = open_reader(str(name))
        reader.summary()
        reader.close()
    assert schema_md5.cache_info().misses == len(TOPICS)  # PoseStamped's schema is in both files
    assert definition_md5(schema.name, schema.data.decode()) == debian[schema.name][0]


def test_a_file_cut_short_gets_the_md5s_too(standard: tuple[Path, dict[str, list[str]]],
                                            debian: dict[str, tuple[str, str]], ros_env: dict[str, str]) -> None:
    path, sent = standard
    whole = path.read_bytes()
    with path.open("rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    last = summary.chunk_indexes[-1]
    path.write_bytes(whole[:last.chunk_start_offset + last.chunk_length])  # the chunks, no summary, no footer
    reader = open_reader(str(path))
    got = {(conn.topic, conn.md5sum, data.hex()) for conn, _t, data in reader.messages()}
    reader.close()
    assert got == {(topic, debian[TOPICS[topic]][0], hexed) for topic, rows in sent.items() for hexed in rows}
    result = rostui(["bag", "info", str(path)], ros_env)
    assert "warning:" in result.stdout and "[]" not in result.stdout
    assert _types_in(result.stdout) == {t: debian[t][0] for t in TOPICS.values()}, result.stdout


def test_bag_view_gets_the_md5s(standard: tuple[Path, dict[str, list[str]]],
                                debian: dict[str, tuple[str, str]]) -> None:
    path, _sent = standard
    index = load_index([str(path)])
    assert {c.topic: c.md5sum for c in index.connections} == {topic: debian[t][0] for topic, t in TOPICS.items()}


def _listener_args() -> list[str]:
    return [f"{topic}={type_name}" for topic, type_name in TOPICS.items()]


def _received(listener: Peer) -> dict[str, list[str]]:
    """What the typed listener printed: each topic's messages (hex), in order of arrival."""
    got: dict[str, list[str]] = {}
    for line in listener.output.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0] in TOPICS:
            assert parts[1] == TOPICS[parts[0]], line
            got.setdefault(parts[0], []).append(parts[3])
    return got


def test_convert_gives_a_bag_that_real_rosbag_plays_to_rospy_subscribers(
        standard: tuple[Path, dict[str, list[str]]], debian: dict[str, tuple[str, str]], tmp_path: Path,
        ros_env: dict[str, str], real_roscore: Any, spawn: Any) -> None:
    need_command("rosbag")
    path, sent = standard
    out = tmp_path / "converted.bag"
    result = rostui(["bag", "convert", str(path), str(out)], ros_env)
    assert result.returncode == 0 and result.stderr == "", result.stderr
    info = run_tool(["rosbag", "info", str(out)], ros_env)
    assert _types_in(info.stdout) == {t: debian[t][0] for t in TOPICS.values()}, info.stdout
    listener = spawn(rospy_peer("rospy_typed_listener.py", *_listener_args()), label="rospy typed listener")
    listener.wait_for("subscribed")
    play = run_tool(["rosbag", "play", "--wait-for-subscribers", str(out)], ros_env, timeout=60)
    assert play.returncode == 0
    total = len(TOPICS) * PER_TOPIC
    wait_until(lambda: sum(map(len, _received(listener).values())) >= total, f"{total} messages at the listener")
    assert _received(listener) == sent, listener.describe()
    assert "md5sum" not in listener.output and "ERROR" not in listener.output


def test_bag_play_of_the_mcap_reaches_rospy_subscribers(
        standard: tuple[Path, dict[str, list[str]]], ros_env: dict[str, str], real_roscore: Any,
        spawn: Any) -> None:
    path, sent = standard
    listener = spawn(rospy_peer("rospy_typed_listener.py", *_listener_args()), label="rospy typed listener")
    listener.wait_for("subscribed")
    # Looping, so that messages published before a subscriber had connected come round again.
    spawn(rostui_cmd("bag", "play", "-q", "-l", "-d", "0.5", str(path)), label="rostui bag play")

    def all_heard() -> bool:
        got = _received(listener)
        return all(set(rows) <= set(got.get(topic, [])) for topic, rows in sent.items())

    wait_until(all_heard, "every message of every topic at the rospy listener")
    got = _received(listener)
    assert all(set(got[topic]) == set(rows) for topic, rows in sent.items()), listener.describe()
    assert "md5sum" not in listener.output and "ERROR" not in listener.output


def _odd_mcap(path: Path, schemas: list[tuple[str, str, str, bytes]]) -> None:
    """An MCAP of one message per ``(topic, type, schema encoding, definition)``, written by mcap's own writer with
    no channel metadata; equal schemas are written once, and schema encoding '' means a channel without one."""
    with path.open("wb") as f:
        writer = McapWriter(f)
        writer.start(profile="ros1", library="another writer")
        ids: dict[tuple[str, str, bytes], int] = {}
        for n, (topic, type_name, encoding, definition) in enumerate(schemas):
            key = (type_name, encoding, definition)
            if encoding and key not in ids:
                ids[key] = writer.register_schema(type_name, encoding, definition)
            schema_id = ids.get(key, 0)
            channel = writer.register_channel(topic, "ros1", schema_id)
            writer.add_message(channel, log_time=n, publish_time=n, data=b"\0\0\0\0")
        writer.finish()


BROKEN = [
    ("/bad", "pkg/Bad", "ros1msg", b"int32 x\nthis is not a field\n", "pkg/Bad: invalid declaration"),
    ("/missing", "pkg/Missing", "ros1msg", b"other_pkg/Thing thing\n", "no 'MSG:' section for other_pkg/Thing"),
    ("/latin1", "pkg/Latin", "ros1msg", b"string s # caf\xe9\n", "definition is not UTF-8 text"),
]


def test_a_definition_that_does_not_parse_warns_once_and_gives_the_wildcard(
        tmp_path: Path, ros_env: dict[str, str]) -> None:
    path = tmp_path / "broken.mcap"
    _odd_mcap(path, [(t, ty, enc, d) for t, ty, enc, d, _why in BROKEN] +
              [("/bad_again", "pkg/Bad", "ros1msg", BROKEN[0][3])])
    result = rostui(["bag", "info", str(path)], ros_env)
    assert result.returncode == 0, result.stderr
    assert _types_in(result.stdout) == {ty: UNKNOWN_MD5 for _t, ty, _e, _d, _why in BROKEN}, result.stdout
    lines = result.stderr.splitlines()
    assert len(lines) == len(BROKEN), result.stderr  # one line per schema, whatever the number of channels
    for line, (_topic, type_name, _enc, _def, why) in zip(lines, BROKEN):
        assert line.startswith(f"{path}: no md5sum for type {type_name} (") and why in line, line
        assert line.endswith("using the wildcard '*'"), line
    out = tmp_path / "broken.bag"
    converted = rostui(["bag", "convert", str(path), str(out)], ros_env)
    assert converted.returncode == 0 and len(converted.stderr.splitlines()) == len(BROKEN), converted.stderr
    need_command("rosbag")
    info = run_tool(["rosbag", "info", str(out)], ros_env)
    assert _types_in(info.stdout) == {ty: UNKNOWN_MD5 for _t, ty, _e, _d, _why in BROKEN}, info.stdout


def test_channels_that_are_not_ros1_or_lack_a_schema_are_read_with_a_warning(
        tmp_path: Path, debian: dict[str, tuple[str, str]], ros_env: dict[str, str]) -> None:
    path = tmp_path / "mixed.mcap"
    string_md5, string_text = debian["std_msgs/String"]
    _odd_mcap(path, [("/json", "pkg/Json", "jsonschema", b"{}"), ("/none", "", "", b""),
                     ("/chatter", "std_msgs/String", "ros1msg", string_text.encode())])
    result = rostui(["bag", "info", "--json", str(path)], ros_env)
    assert result.returncode == 0, result.stderr
    assert {row["type"]: row["md5sum"] for row in json.loads(result.stdout)["types"]} == \
        {"pkg/Json": "*", "": "*", "std_msgs/String": string_md5}
    assert [line.split(": ", 1)[1] for line in result.stderr.splitlines()] == [
        "no md5sum for type pkg/Json (schema encoding 'jsonschema' is not 'ros1msg'): using the wildcard '*'",
        "no md5sum for channel /none (it has no schema): using the wildcard '*'"]


def test_a_channel_without_a_schema_is_not_played_and_play_says_so(
        tmp_path: Path, debian: dict[str, tuple[str, str]], ros_env: dict[str, str], rostui_core: Any) -> None:
    """The master refuses a publisher with no type: play skips that topic with one line and plays the rest."""
    path = tmp_path / "untyped.mcap"
    _odd_mcap(path, [("/none", "", "", b""), ("/chatter", "std_msgs/String", "ros1msg",
                                              debian["std_msgs/String"][1].encode())])
    result = rostui(["bag", "play", "-q", "-d", "0", str(path)], ros_env)
    assert result.returncode == 0, result.stderr
    assert "/none was recorded without a message type: it is not played" in result.stderr.splitlines()
    assert "Traceback" not in result.stderr


def test_the_wildcard_plays_to_rospy_and_real_rosbag_play_refuses_it(
        standard: tuple[Path, dict[str, list[str]]], debian: dict[str, tuple[str, str]], tmp_path: Path,
        ros_env: dict[str, str], real_roscore: Any, spawn: Any) -> None:
    """A writer that keeps only the type's own text (no ``MSG:`` sections): no md5 can be computed from it."""
    _standard, sent = standard
    own_text = debian["geometry_msgs/PoseStamped"][1].split("\n" + "=" * 80 + "\n")[0]
    path = tmp_path / "no_nested.mcap"
    with path.open("wb") as f:
        writer = McapWriter(f)
        writer.start(profile="ros1", library="another writer")
        channel = writer.register_channel("/pose", "ros1", writer.register_schema(
            "geometry_msgs/PoseStamped", "ros1msg", own_text.encode()))
        for i, hexed in enumerate(sent["/pose"]):
            writer.add_message(channel, log_time=T0 + i * STEP, publish_time=T0 + i * STEP, data=bytes.fromhex(hexed))
        writer.finish()
    info = rostui(["bag", "info", str(path)], ros_env)
    assert _types_in(info.stdout) == {"geometry_msgs/PoseStamped": UNKNOWN_MD5}, info.stdout
    assert info.stderr == f"{path}: no md5sum for type geometry_msgs/PoseStamped (the definition has no 'MSG:' section " \
        "for geometry_msgs/Pose, std_msgs/Header): using the wildcard '*'\n", info.stderr
    listener = spawn(rospy_peer("rospy_typed_listener.py", "/pose=geometry_msgs/PoseStamped"),
                     label="rospy typed listener")
    listener.wait_for("subscribed")
    play = spawn(rostui_cmd("bag", "play", "-q", "-l", "-d", "0.5", str(path)), label="rostui bag play")
    wait_until(lambda: set(sent["/pose"]) <= set(_received(listener).get("/pose", [])),
               "every pose at the rospy listener")
    assert set(_received(listener)["/pose"]) == set(sent["/pose"]), listener.describe()
    play.stop()
    need_command("rosbag")
    bag = tmp_path / "no_nested.bag"
    assert rostui(["bag", "convert", str(path), str(bag)], ros_env).returncode == 0
    refused = run_tool(["rosbag", "play", str(bag)], ros_env, timeout=60, check=False)
    assert "Advertising with * as the md5sum is not allowed" in refused.stdout + refused.stderr
