"""Bags whose file order is not time order, written by real rosbag (Debian python3-rosbag).

rosbag writes such bags when a program writes messages per topic (or per
publisher), or with times going back and forth. Real ``rosbag play``
interleaves them by time; so must ``rostui bag play`` (a live rospy subscriber
checks the order it hears), bag view's index (its seeks and per-topic times),
and the same bags converted to MCAP, which keep the file's order.
"""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag.files import merged_messages, open_reader, open_writer, time_ordered, unordered_notice
from rostui.core.bag.index import IndexSource, load_index
from rostui.core.msg import get_message_class

from cli_helpers import rostui
from conftest import SYSTEM_PYTHON, need_command, need_peer, rostui_cmd
from interop_helpers import Peer, rospy_peer, spawn  # noqa: F401

Int32 = get_message_class("std_msgs/Int32")
T0_NS = 1_700_000_000 * 1_000_000_000
STEP_NS = 100_000_000
COUNT = 24

#: Writes a bag with real rosbag: message i has data i and time T0 + i * STEP, in a file order that is not
#: time order. chunk_threshold=64 closes a chunk after every message, so the chunks are unsorted too.
WRITE = r'''
import sys, rosbag, rospy
from std_msgs.msg import Int32
path, shape, count, step = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
t0 = rospy.Time(1700000000)
stamp = lambda i: t0 + rospy.Duration(0, i * step)
with rosbag.Bag(path, "w", chunk_threshold=64) as bag:
    if shape == "per_topic":  # all of /a (the even ones), then all of /b (the odd ones)
        for topic, first in (("/a", 0), ("/b", 1)):
            for i in range(first, count, 2):
                bag.write(topic, Int32(i), stamp(i))
    elif shape == "per_publisher":  # one topic, two publishers, each written whole
        for callerid, first in (("/x", 0), ("/y", 1)):
            header = {"callerid": callerid, "topic": "/seq", "type": Int32._type, "md5sum": Int32._md5sum,
                      "message_definition": Int32._full_text}
            for i in range(first, count, 2):
                bag.write("/seq", Int32(i), stamp(i), connection_header=header)
    elif shape == "backwards":  # blocks of four, the last block first
        for block in reversed(range(0, count, 4)):
            for i in range(block, min(block + 4, count)):
                bag.write("/a" if i % 2 == 0 else "/b", Int32(i), stamp(i))
'''

#: (shape, the topics a subscriber listens to)
SHAPES = {"per_topic": ("/a", "/b"), "per_publisher": ("/seq",), "backwards": ("/a", "/b")}


def write_with_rosbag(path: Path, shape: str) -> Path:
    """A bag of ``shape`` written by real rosbag's Python API."""
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag"], capture_output=True).returncode == 0,
              "rosbag's Python API (Debian python3-rosbag)")
    r = subprocess.run([SYSTEM_PYTHON, "-c", WRITE, str(path), shape, str(COUNT), str(STEP_NS)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return path


@pytest.fixture(params=["bag", "mcap"])
def shaped(request: pytest.FixtureRequest, tmp_path: Path) -> Any:
    """``make(shape)``: a rosbag-written bag of that shape, or the same copied to MCAP in file order."""
    def make(shape: str) -> Path:
        bag = write_with_rosbag(tmp_path / f"{shape}.bag", shape)
        if request.param == "bag":
            return bag
        mcap = tmp_path / f"{shape}.mcap"
        reader, writer = open_reader(str(bag)), open_writer(str(mcap))
        for conn in reader.summary().connections:
            writer.add_connection(conn)
        for conn, t, data in reader.messages():  # file order, unlike `rostui bag convert`
            writer.write(conn.id, t, data)
        writer.close()
        reader.close()
        file_order = [Int32().deserialize(d).data for _c, _t, d in open_reader(str(mcap)).messages()]
        assert file_order != sorted(file_order), "the MCAP kept the bag's file order"
        return mcap
    return make


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_messages_come_in_time_order_through_the_index(shaped: Any, shape: str) -> None:
    path = shaped(shape)
    reader = open_reader(str(path))
    try:
        file_order = [Int32().deserialize(d).data for _c, _t, d in reader.messages()]
        assert file_order != list(range(COUNT)) and sorted(file_order) == list(range(COUNT))
        assert unordered_notice(reader) == ""
        ordered = [(t, Int32().deserialize(d).data) for _c, t, d in time_ordered(reader)]
        assert ordered == [(T0_NS + i * STEP_NS, i) for i in range(COUNT)]
    finally:
        reader.close()


def _every_message(index: Any) -> list[Any]:
    """Every message of ``index`` in the order bag view plays them."""
    source, got = IndexSource(index), []
    while (item := source.peek()) is not None:
        got.append(item)
        source.advance()
    return got


@pytest.mark.parametrize("shape", ["per_topic", "backwards"])
def test_bag_view_index_seeks_to_the_right_message(shaped: Any, shape: str) -> None:
    index = load_index([str(shaped(shape))])
    try:
        assert index.notices == []
        assert [t for _c, t, _d in _every_message(index)] == [T0_NS + i * STEP_NS for i in range(COUNT)]
        assert index.tracks["/a"].count == index.tracks["/b"].count == COUNT // 2
        assert sum(index.density("/b", 4)) == COUNT // 2
        for i in (0, 7, 13, COUNT - 1):
            topic = "/a" if i % 2 == 0 else "/b"
            at = index.message_at(topic, T0_NS + i * STEP_NS + 1)
            assert at is not None
            conn, t, data = index.item(at)
            assert (conn.topic, t, Int32().deserialize(data).data) == (topic, T0_NS + i * STEP_NS, i)
            assert index.neighbour_time(topic, T0_NS + i * STEP_NS, +1) == (
                T0_NS + (i + 2) * STEP_NS if i + 2 < COUNT else None)
        source = IndexSource(index)
        source.seek(T0_NS + 9 * STEP_NS)
        heard = []
        while (item := source.peek()) is not None and len(heard) < 5:
            heard.append(Int32().deserialize(item[2]).data)
            source.advance()
        assert heard == [9, 10, 11, 12, 13]
        source.seek(T0_NS + 2 * STEP_NS)  # backwards
        item = source.peek()
        assert item is not None and Int32().deserialize(item[2]).data == 2
    finally:
        index.close()


def test_convert_writes_time_order(tmp_path: Path) -> None:
    """`rostui bag convert` rewrites a bag in time order, as rosbag's own tools rewrite bags."""
    bag = write_with_rosbag(tmp_path / "backwards.bag", "backwards")
    out = tmp_path / "sorted.mcap"
    r = rostui(["bag", "convert", str(bag), str(out)], {})
    assert r.returncode == 0, r.stderr
    reader = open_reader(str(out))
    try:
        assert [Int32().deserialize(d).data for _c, _t, d in reader.messages()] == list(range(COUNT))
    finally:
        reader.close()


def test_a_file_without_an_index_plays_in_file_order_and_says_so(tmp_path: Path) -> None:
    """Cut off its index (the end of the file), a rosbag-written bag reads in file order; bag view still
    finds every message by reading the chunks and shows them in time order."""
    bag = write_with_rosbag(tmp_path / "per_topic.bag", "per_topic")
    reader = open_reader(str(bag))
    index_pos = reader.index_pos  # type: ignore[attr-defined]
    reader.close()
    cut = tmp_path / "cut.bag"
    cut.write_bytes(bag.read_bytes()[:index_pos])
    reader = open_reader(str(cut))
    try:
        assert "cut.bag has no index" in unordered_notice(reader)
        heard = [Int32().deserialize(d).data for _c, _t, d, _i in merged_messages([reader])]
        assert heard == list(range(0, COUNT, 2)) + list(range(1, COUNT, 2))
    finally:
        reader.close()
    index = load_index([str(cut)])
    try:
        assert [Int32().deserialize(d).data for _c, _t, d in _every_message(index)] == list(range(COUNT))
        assert len(index.notices) == 1 and "cut.bag" in index.notices[0]
    finally:
        index.close()


def _heard(spawn: Any, player: list[str], topics: tuple[str, ...], label: str) -> list[str]:
    """What a rospy subscriber to ``topics`` hears, in order, while ``player`` plays."""
    listener = spawn(rospy_peer("rospy_int32_sequence.py", str(COUNT), *topics), label=f"rospy listener ({label})")
    listener.wait_for(r"^subscribed$")
    play = spawn([*player], label=label)
    assert listener.wait_exit(60) == 0, listener.describe() + "\n" + play.describe()
    assert play.wait_exit(60) == 0, play.describe()
    return [line for line in listener.lines if line.startswith("/")]


def assert_heard_in_time_order(heard: list[str], topics: tuple[str, ...]) -> None:
    """Every message heard once, on its topic, in time order.

    One topic comes over one connection, so its order is exact. Two topics
    come over two connections, and which of two messages one step apart
    arrives first is the machine's scheduling, for rosbag play as for us (a
    loaded CI machine swapped such pairs): there a message may be heard at most
    one place from its own. File-order playback (all of /a, then all of /b)
    moves half of them by up to COUNT / 2 places.
    """
    values = [int(line.split()[1]) for line in heard]
    assert sorted(values) == list(range(COUNT)), heard
    assert all(line.split()[0] == (topics[0] if len(topics) == 1 else topics[v % 2])
               for line, v in zip(heard, values)), heard
    if len(topics) == 1:
        assert values == list(range(COUNT)), heard
    else:
        assert all(abs(v - place) <= 1 for place, v in enumerate(values)), heard


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_rostui_bag_play_delivers_rosbag_plays_order(real_roscore: Any, ros_env: dict[str, str], spawn: Any,
                                                      shaped: Any, shape: str) -> None:
    need_command("rosbag")
    path = shaped(shape)
    topics = SHAPES[shape]
    if path.suffix == ".bag":
        theirs = _heard(spawn, ["rosbag", "play", "-d", "1", str(path)], topics, "rosbag play")
        assert_heard_in_time_order(theirs, topics)
    ours = _heard(spawn, rostui_cmd("bag", "play", "-q", "-d", "1", str(path)), topics, "rostui bag play")
    assert_heard_in_time_order(ours, topics)
