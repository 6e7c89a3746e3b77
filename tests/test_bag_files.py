"""Bag files without a ROS graph: round trips, the mcap reader and decoder, damaged files, reindex, convert."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from rostui.core.bag.files import convert, open_reader, open_writer, reindex
from rostui.core.bag.model import BagError, Connection
from rostui.core.msg import get_message_class

from cli_helpers import rostui
from conftest import need_command, need_peer

Pose = get_message_class("turtlesim/Pose")
Velocity = get_message_class("turtlesim/Velocity")
T0 = 1_700_000_000_000_000_000


def pose_conn(conn_id: int = 0, topic: str = "/turtle1/pose", latching: bool = False) -> Connection:
    return Connection(conn_id, topic, "turtlesim/Pose", Pose._md5sum, Pose._full_text, "/turtlesim", latching)


def write_poses(path: Path, count: int = 200, compression: str = "none") -> list[bytes]:
    """A bag of ``count`` poses on /turtle1/pose and one latched velocity on /vel."""
    writer = open_writer(str(path), compression)
    writer.add_connection(pose_conn())
    writer.add_connection(Connection(1, "/vel", "turtlesim/Velocity", Velocity._md5sum, Velocity._full_text,
                                     "/teleop", True))
    datas = []
    for i in range(count):
        data = Pose(x=float(i), y=2.5, theta=0.5, linear_velocity=1.0, angular_velocity=-1.0).serialize()
        datas.append(data)
        writer.write(0, T0 + i * 10_000_000, data)
    writer.write(1, T0 + count * 10_000_000, Velocity(linear=2.0, angular=1.0).serialize())
    writer.close()
    return datas


CASES = [("a.bag", "none"), ("b.bag", "bz2"), ("c.bag", "lz4"), ("a.mcap", "none"), ("b.mcap", "lz4"),
         ("c.mcap", "zstd")]


@pytest.mark.parametrize("name,compression", CASES)
def test_round_trip_keeps_bytes_times_and_connections(tmp_path: Path, name: str, compression: str) -> None:
    datas = write_poses(tmp_path / name, compression=compression)
    reader = open_reader(str(tmp_path / name))
    messages = list(reader.messages())
    summary = reader.summary()
    reader.close()
    assert [d for c, _t, d in messages if c.topic == "/turtle1/pose"] == datas
    assert [t for c, t, _d in messages if c.topic == "/turtle1/pose"] == [T0 + i * 10_000_000 for i in range(200)]
    assert summary.closed and not summary.problem
    assert summary.message_count == 201
    assert summary.start_ns == T0 and summary.end_ns == T0 + 200 * 10_000_000
    conns = {c.topic: c for c in summary.connections}
    assert conns["/vel"].latching and not conns["/turtle1/pose"].latching
    assert conns["/turtle1/pose"].md5sum == Pose._md5sum and conns["/vel"].callerid == "/teleop"
    assert conns["/turtle1/pose"].definition == Pose._full_text
    assert set(summary.chunk_compression) == {compression}


def test_mcap_reads_back_with_the_mcap_reader_and_ros1_decoder(tmp_path: Path) -> None:
    from mcap.reader import make_reader
    from mcap_ros1.decoder import DecoderFactory

    write_poses(tmp_path / "poses.mcap", count=50, compression="zstd")
    with open(tmp_path / "poses.mcap", "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        header = reader.get_header()
        decoded = [(schema.name, schema.encoding, channel.message_encoding, channel.topic, msg)
                   for schema, channel, _m, msg in reader.iter_decoded_messages()]
    assert header.profile == "ros1"
    poses = [d for d in decoded if d[3] == "/turtle1/pose"]
    assert len(poses) == 50
    assert {(n, e, m) for n, e, m, _t, _msg in poses} == {("turtlesim/Pose", "ros1msg", "ros1")}
    assert [p[4].x for p in poses] == [float(i) for i in range(50)]
    assert all(p[4].y == 2.5 and p[4].angular_velocity == -1.0 for p in poses)
    vel = [d for d in decoded if d[3] == "/vel"][0][4]
    assert (vel.linear, vel.angular) == (2.0, 1.0)


@pytest.mark.parametrize("name", ["cut.bag", "cut.mcap"])
def test_a_file_cut_short_reads_to_its_last_complete_chunk_and_info_warns(tmp_path: Path, name: str,
                                                                           ros_env: dict[str, str]) -> None:
    path = tmp_path / name
    writer = open_writer(str(path), "none")
    writer.add_connection(pose_conn())
    for i in range(300):
        writer.write(0, T0 + i * 1_000_000, Pose(x=float(i)).serialize())
        if i % 100 == 99:
            writer.flush()  # three complete chunks, as the recorder's timer leaves them
    size = writer.size
    os.close(writer.fd) if hasattr(writer, "fd") else writer.out.close()  # killed: no close()
    with open(path, "r+b") as f:
        f.truncate(size - 2500)  # the last chunk loses its end
    reader = open_reader(str(path))
    count = sum(1 for _ in reader.messages())
    reader.close()
    assert 200 <= count < 300
    result = rostui(["bag", "info", str(path)], ros_env)
    assert result.returncode == 0, result.stderr
    assert "not closed" in result.stdout
    fixed, problem = reindex(str(path))
    assert fixed == count
    assert (tmp_path / (Path(name).stem + ".orig" + Path(name).suffix)).exists()
    again = rostui(["bag", "info", "--json", str(path)], ros_env)
    info = json.loads(again.stdout)
    assert info["closed"] is True and info["messages"] == count


@pytest.mark.parametrize("content", [b"", os.urandom(5000), b"#ROSBAG V2.0\n" + os.urandom(300),
                                     b"\x89MCAP0\r\n" + os.urandom(300)],
                         ids=["empty", "random", "bag-magic-then-random", "mcap-magic-then-random"])
def test_damaged_files_give_one_clear_line(tmp_path: Path, ros_env: dict[str, str], content: bytes) -> None:
    path = tmp_path / "junk.bag"
    path.write_bytes(content)
    for command in (["info"], ["play"]):
        result = rostui(["bag", *command, str(path)], ros_env, timeout=30)
        if result.returncode == 0:  # magic followed by garbage: readable, holds nothing (rosbag's empty layout)
            assert command == ["play"] or ("size:" in result.stdout and "messages:" not in result.stdout
                                           and "warning:" in result.stdout)
            continue
        assert "Traceback" not in result.stderr
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and "junk.bag" in lines[0], result.stderr


def test_missing_file_is_one_line(tmp_path: Path, ros_env: dict[str, str]) -> None:
    result = rostui(["bag", "info", str(tmp_path / "nope.bag")], ros_env)
    assert result.returncode == 1
    assert result.stderr.strip() == f"rostui bag info: {tmp_path / 'nope.bag'}: no such file"


def test_convert_between_mcap_and_bag_keeps_every_message(tmp_path: Path, ros_env: dict[str, str]) -> None:
    datas = write_poses(tmp_path / "in.mcap", compression="lz4")
    result = rostui(["bag", "convert", str(tmp_path / "in.mcap"), str(tmp_path / "out.bag")], ros_env)
    assert result.returncode == 0, result.stderr
    assert convert(str(tmp_path / "out.bag"), str(tmp_path / "back.mcap"), "zstd") == 201
    reader = open_reader(str(tmp_path / "back.mcap"))
    back = [d for c, _t, d in reader.messages() if c.topic == "/turtle1/pose"]
    reader.close()
    assert back == datas
    with pytest.raises(BagError):
        convert(str(tmp_path / "in.mcap"), str(tmp_path / "in.mcap"))


def test_real_rosbag_info_reads_a_rostui_bag(tmp_path: Path, ros_env: dict[str, str]) -> None:
    need_command("rosbag")
    write_poses(tmp_path / "poses.bag", compression="lz4")
    theirs = subprocess.run(["rosbag", "info", str(tmp_path / "poses.bag")], capture_output=True, text=True,
                            env=ros_env, timeout=60)
    assert theirs.returncode == 0, theirs.stderr
    assert "messages:     201" in theirs.stdout or "messages:    201" in theirs.stdout
    assert "/turtle1/pose   200 msgs    : turtlesim/Pose" in theirs.stdout
    ours = rostui(["bag", "info", str(tmp_path / "poses.bag")], ros_env)
    for field in ("types:", "/vel "):
        assert field in ours.stdout
    ours_topics = [line.split(":", 1)[-1].strip() for line in ours.stdout.splitlines() if " msg" in line]
    theirs_topics = [line.split(":", 1)[-1].strip() for line in theirs.stdout.splitlines() if "msg" in line
                     and "/" in line]
    assert ours_topics == theirs_topics


@pytest.mark.parametrize("args,message", [
    (["-O", "x.bag", "--compression", "zstd", "/x"], "a .bag file cannot use zstd compression (none, bz2 or lz4)"),
    (["-O", "x.mcap", "--compression", "bz2", "/x"], "MCAP files use lz4 or zstd compression, not bz2"),
    (["--mcap", "--compression", "bz2", "/x"], "MCAP files use lz4 or zstd compression, not bz2"),
    (["--mcap", "-O", "x.bag", "/x"], "--mcap records MCAP, but x.bag names a .bag file"),
    (["-O", "x.mcap", "--compression", "rar", "/x"], "unknown compression 'rar' (none, lz4, zstd or bz2)"),
    (["-O", "a.bag", "-o", "b", "/x"], "use -O NAME or -o PREFIX, not both"),
])
def test_record_refuses_bad_options_in_one_line(tmp_path: Path, ros_env: dict[str, str], args: list[str],
                                                message: str) -> None:
    result = rostui(["bag", "record", *args], ros_env)
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1 and message in result.stderr, result.stderr
    assert not (tmp_path / "x.bag").exists()


ROSBAG_READ = """
import sys, rosbag
bag = rosbag.Bag(sys.argv[1])
for topic, msg, t in bag.read_messages():
    print(topic, getattr(msg, "x", getattr(msg, "linear", None)), t.to_nsec())
"""

ROSBAG_WRITE = """
import sys, rosbag, rospy
from std_msgs.msg import Int32
with rosbag.Bag(sys.argv[1], "w", compression=sys.argv[2]) as bag:
    for i in range(300):
        bag.write("/count", Int32(data=i), rospy.Time(1000, i * 1000))
"""


def _system_rosbag() -> bool:
    probe = subprocess.run(["/usr/bin/python3", "-c", "import rosbag, roslz4"], capture_output=True)
    return probe.returncode == 0


@pytest.mark.parametrize("compression", ["none", "bz2", "lz4"])
def test_compressed_bags_read_both_ways_with_the_rosbag_python_api(tmp_path: Path, compression: str) -> None:
    need_peer(_system_rosbag(), "rosbag Python API (Debian python3-rosbag)")
    write_poses(tmp_path / "ours.bag", count=100, compression=compression)
    theirs = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_READ, str(tmp_path / "ours.bag")],
                            capture_output=True, text=True, timeout=60)
    assert theirs.returncode == 0, theirs.stderr
    rows = theirs.stdout.splitlines()
    assert rows[:3] == [f"/turtle1/pose {float(i)} {T0 + i * 10_000_000}" for i in range(3)]
    assert len(rows) == 101
    written = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_WRITE, str(tmp_path / "theirs.bag"), compression],
                             capture_output=True, text=True, timeout=60)
    assert written.returncode == 0, written.stderr
    from rostui.core.msg import get_message_class

    Int32 = get_message_class("std_msgs/Int32")
    reader = open_reader(str(tmp_path / "theirs.bag"))
    got = [(c.topic, Int32.deserialize(d).data, t) for c, t, d in reader.messages()]
    summary = reader.summary()
    reader.close()
    assert got == [("/count", i, 1000 * 10**9 + i * 1000) for i in range(300)]
    assert summary.closed and summary.message_count == 300
