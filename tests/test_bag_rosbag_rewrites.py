"""Real rosbag rewrites a .bag's file header in place (``rosbag reindex``, ``rosbag.Bag(f, 'a')``): on a rostui
bag it must find rosbag's exact header size, or it writes over the first chunk.  Cleanly closed bags and bags
whose recorder was killed (no index) must both come out readable, with every message, by both tools."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from rostui.core.bag.files import open_reader, open_writer
from rostui.core.bag.rosbag2_0 import FILE_HEADER_RECORD_SIZE, MAGIC
from rostui.core.msg import get_message_class

from conftest import SYSTEM_PYTHON, need_command, need_peer
from test_bag_files import T0, pose_conn, write_poses

Pose = get_message_class("turtlesim/Pose")

APPEND = """
import sys, rosbag, rospy
from std_msgs.msg import Int32
with rosbag.Bag(sys.argv[1], "a") as bag:
    for i in range(50):
        bag.write("/appended", Int32(data=i), rospy.Time(2000, i))
"""

COUNT = """
import sys, collections, rosbag
counts = collections.Counter(topic for topic, _, _ in rosbag.Bag(sys.argv[1]).read_messages())
print(dict(sorted(counts.items())))
"""


def _rosbag_python() -> None:
    r = subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag, roslz4"], capture_output=True)
    need_peer(r.returncode == 0, "rosbag Python API (Debian python3-rosbag)")


def _their_counts(path: Path) -> str:
    r = subprocess.run([SYSTEM_PYTHON, "-c", COUNT, str(path)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


def _our_counts(path: Path) -> dict[str, int]:
    reader = open_reader(str(path))
    counts: dict[str, int] = {}
    for conn, _t, _data in reader.messages():
        counts[conn.topic] = counts.get(conn.topic, 0) + 1
    reader.close()
    return counts


def _killed_bag(path: Path, count: int, compression: str) -> None:
    """A bag whose writer never closed: chunks on disk, no index, the header still saying index_pos 0."""
    writer = open_writer(str(path), compression, max_chunk_age=0.0)
    writer.add_connection(pose_conn())
    for i in range(count):
        writer.write(0, T0 + i * 10_000_000, Pose(x=float(i)).serialize())
        if i % 50 == 49:
            writer.flush()
    writer.flush()  # what a kill -9 leaves: everything flushed so far, and no index


def test_the_file_header_record_is_rosbags_size(tmp_path: Path) -> None:
    write_poses(tmp_path / "a.bag", count=3)
    data = (tmp_path / "a.bag").read_bytes()
    assert FILE_HEADER_RECORD_SIZE == 4104  # rosbag: 4-byte length, header, 4-byte length, padding to 4096
    header_len = int.from_bytes(data[len(MAGIC):len(MAGIC) + 4], "little")
    data_len = int.from_bytes(data[len(MAGIC) + 4 + header_len:len(MAGIC) + 8 + header_len], "little")
    assert header_len + data_len == 4096
    first = len(MAGIC) + FILE_HEADER_RECORD_SIZE
    first_header_len = int.from_bytes(data[first:first + 4], "little")
    assert b"op=\x05" in data[first + 4:first + 4 + first_header_len]  # a chunk


@pytest.mark.parametrize("compression", ["none", "lz4"])
def test_rosbag_append_to_a_rostui_bag_keeps_every_message(tmp_path: Path, compression: str) -> None:
    _rosbag_python()
    path = tmp_path / "ours.bag"
    write_poses(path, count=200, compression=compression)
    r = subprocess.run([SYSTEM_PYTHON, "-c", APPEND, str(path)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert _their_counts(path) == "{'/appended': 50, '/turtle1/pose': 200, '/vel': 1}"
    assert _our_counts(path) == {"/turtle1/pose": 200, "/vel": 1, "/appended": 50}


@pytest.mark.parametrize("state", ["closed", "killed"])
def test_rosbag_reindex_of_a_rostui_bag_keeps_every_message(tmp_path: Path, state: str) -> None:
    need_command("rosbag")
    _rosbag_python()
    path = tmp_path / "ours.bag"
    if state == "closed":
        write_poses(path, count=300)
        expected = {"/turtle1/pose": 300, "/vel": 1}
    else:
        _killed_bag(path, 300, "lz4")
        expected = {"/turtle1/pose": 300}
    (tmp_path / "out").mkdir()
    r = subprocess.run(["rosbag", "reindex", "--output-dir", str(tmp_path / "out"), str(path)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    reindexed = tmp_path / "out" / "ours.bag"
    assert _our_counts(reindexed) == expected
    assert _their_counts(reindexed) == str(dict(sorted(expected.items())))
    in_place = tmp_path / "in_place.bag"
    shutil.copy(path, in_place)
    r = subprocess.run(["rosbag", "reindex", str(in_place)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert _our_counts(in_place) == expected


def test_rosbag_append_refuses_a_killed_rostui_bag_and_leaves_it_whole(tmp_path: Path) -> None:
    """rosbag will not append to a bag without an index (ROSBagUnindexedException); the bag is left as it was."""
    _rosbag_python()
    path = tmp_path / "killed.bag"
    _killed_bag(path, 200, "lz4")
    before = path.read_bytes()
    r = subprocess.run([SYSTEM_PYTHON, "-c", APPEND, str(path)], capture_output=True, text=True, timeout=120)
    assert r.returncode != 0 and "ROSBagUnindexedException: Unindexed bag" in r.stderr
    assert path.read_bytes() == before
    assert _our_counts(path) == {"/turtle1/pose": 200}
