"""`rostui bag info` prints what Debian's `rosbag info` prints, byte for byte, for bags of odd shapes written by
real rosbag (its Python API) and for bags rostui writes.

The shapes: topics written one after the other with interleaved times, unsorted and backwards chunks (so the
first chunk's start and the last chunk's end are not the bag's earliest and latest message), no messages, one
and several connections per topic, a topic recorded with two types, a type with two md5sums, none/bz2/lz4 and
mixed compression, durations under a minute (rounded), over a minute and over an hour (truncated), times
whose hundredths round up, one message (`msg`), and sizes from kilobytes to megabytes.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection

from cli_helpers import rostui
from conftest import need_command, need_peer, stop_process, wait_until

#: The same time zone (a POSIX rule, so no tz database is needed: UTC+5:30, which shows the local time is
#: used) and locale for both programs.
TIME_ENV = {"TZ": "XST-5:30", "LC_ALL": "C.UTF-8"}

#: Writes every bag of ``ROSBAG_BAGS`` into the directory ``sys.argv[1]`` with the rosbag Python API.
ROSBAG_WRITER = r'''
import sys, os, rosbag, rospy
from std_msgs.msg import Int32, String, Float64
from geometry_msgs.msg import PoseStamped

out = sys.argv[1]
T0 = rospy.Time(1795360262, 0)


def at(seconds, base=T0):
    return base + rospy.Duration.from_sec(seconds)


def conn_header(topic, cls, callerid, latching=False):
    header = {"topic": topic, "type": cls._type, "md5sum": cls._md5sum, "message_definition": cls._full_text,
              "callerid": callerid}
    if latching:
        header["latching"] = "1"
    return header


def use_connection(bag, topic, key, known):
    """The Python API keeps one connection per topic; pointing the topic at the connection ``key`` made
    before (or at none, so the next write opens one with the connection header given) gives a topic several
    connections, as rosbag record makes for several publishers."""
    if key in known:
        bag._topic_connections[topic] = known[key]
    else:
        bag._topic_connections.pop(topic, None)


def remember_connection(bag, topic, key, known):
    known[key] = bag._topic_connections[topic]


def per_topic(path, compression, threshold):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=threshold) as bag:
        for i in range(120):
            bag.write("/a", Int32(data=i), at(i * 0.5))
        for i in range(120):
            bag.write("/b", String(data="b" * (i % 40)), at(i * 0.5 + 0.25))
        bag.write("/c/one", Float64(data=1.5), at(3.0))


def unsorted_chunks(path, compression):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=300) as bag:
        for i in range(300):
            back_and_forth = (i * 37) % 101 * 0.731
            bag.write("/jitter", Int32(data=i), at(5 + back_and_forth))
        bag.write("/jitter", Int32(data=-1), at(20.0))


def backwards(path, compression):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=100) as bag:
        for i in range(60):
            bag.write("/down", Int32(data=i), at(100.0 - i * 1.7))


def empty(path, compression):
    with rosbag.Bag(path, "w", compression=compression):
        pass


def duration(path, seconds, start=T0, compression="none"):
    with rosbag.Bag(path, "w", compression=compression) as bag:
        bag.write("/t", Int32(data=0), start)
        bag.write("/t", Int32(data=1), at(seconds / 3.0, start))
        bag.write("/t", Int32(data=2), at(seconds, start))


def connections(path, compression):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=2000) as bag:
        known = {}
        for i in range(30):
            for k, (caller, latch) in enumerate([("/talker_a", False), ("/talker_b", True), ("/talker_c", False)]):
                use_connection(bag, "/chatter", caller, known)
                bag.write("/chatter", String(data="hello %d" % i), at(i * 0.1 + k * 0.01),
                          connection_header=conn_header("/chatter", String, caller, latch))
                remember_connection(bag, "/chatter", caller, known)
            bag.write("/lone", Int32(data=i), at(i * 0.1 + 0.05),
                      connection_header=conn_header("/lone", Int32, "/only"))


def types(path, compression):
    with rosbag.Bag(path, "w", compression=compression) as bag:
        # one type, two md5sums (an older definition recorded before the current one): the first is listed
        old = dict(conn_header("/old_int", Int32, "/legacy"), md5sum="0123456789abcdef0123456789abcdef")
        bag.write("/old_int", Int32(data=3), at(1.0), connection_header=old)
        bag.write("/mixed", Int32(data=1), at(0.5), connection_header=conn_header("/mixed", Int32, "/one"))
        use_connection(bag, "/mixed", "/two", {})
        bag.write("/mixed", String(data="s"), at(0.7), connection_header=conn_header("/mixed", String, "/two"))
        pose = PoseStamped()
        pose.header.frame_id = "map"
        for i in range(12):
            pose.header.seq = i
            bag.write("/a_rather_long/topic/name/pose", pose, at(i * 0.25))
        bag.write("/new_int", Int32(data=7), at(1.5))


def sizes(path, compression, size):
    with rosbag.Bag(path, "w", compression=compression) as bag:
        block = String(data="".join(chr(33 + (i * 7919) % 90) for i in range(size)))
        for i in range(30):
            bag.write("/blob", block, at(i * 0.04))


def mixed(path):
    with rosbag.Bag(path, "w", compression="lz4", chunk_threshold=400) as bag:
        for i in range(200):
            if i == 60:
                bag.compression = "none"
            elif i == 110:
                bag.compression = "bz2"
            elif i == 150:
                bag.compression = "lz4"
            bag.write("/m", String(data="m" * (i % 30)), at(i * 0.3))


def write(name, build, *args):
    build(os.path.join(out, name + ".bag"), *args)


for kind in ("none", "bz2", "lz4"):
    write("per_topic_" + kind, per_topic, kind, 768 * 1024)
    write("per_topic_small_chunks_" + kind, per_topic, kind, 500)
    write("unsorted_" + kind, unsorted_chunks, kind)
    write("backwards_" + kind, backwards, kind)
    write("empty_" + kind, empty, kind)
    write("connections_" + kind, connections, kind)
    write("types_" + kind, types, kind)
    write("hour_" + kind, duration, 3725.73, T0, kind)
write("mixed", mixed)
write("seconds_rounding_up", duration, 59.96)
write("seconds_short", duration, 0.04)
write("zero_length", duration, 0.0)
write("minute_truncated", duration, 114.6)
write("minute_exact", duration, 60.0)
write("day", duration, 90061.999)
write("hundredths_carry", duration, 12.0, rospy.Time(1795360262, 996000000))
write("hundredths_end", duration, 30.0, rospy.Time(1795360262, 4999999))
write("epoch", duration, 1.5, rospy.Time(0, 1))
write("kilobytes", sizes, "none", 20)
write("megabytes", sizes, "none", 100 * 1024)
write("megabytes_bz2", sizes, "bz2", 100 * 1024)
'''

ROSBAG_BAGS = [f"{shape}_{kind}" for shape in ("per_topic", "per_topic_small_chunks", "unsorted", "backwards", "empty",
                                              "connections", "types", "hour")
               for kind in ("none", "bz2", "lz4")]
ROSBAG_BAGS += ["mixed", "seconds_rounding_up", "seconds_short", "zero_length", "minute_truncated", "minute_exact",
                "day", "hundredths_carry", "hundredths_end", "epoch", "kilobytes", "megabytes", "megabytes_bz2"]


def _rosbag_tools() -> bool:
    probe = subprocess.run(["/usr/bin/python3", "-c", "import rosbag, roslz4, geometry_msgs.msg"], capture_output=True)
    return probe.returncode == 0 and shutil.which("rosbag") is not None


@pytest.fixture(scope="module")
def rosbag_bags(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A directory of bags the rosbag Python API wrote."""
    need_peer(_rosbag_tools(), "rosbag with its Python API (Debian python3-rosbag, python3-roslz4)")
    where = tmp_path_factory.mktemp("rosbag_bags")
    written = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_WRITER, str(where)], capture_output=True, text=True,
                             timeout=300)
    assert written.returncode == 0, written.stderr
    return where


def _both(path: Path, ros_env: dict[str, str]) -> tuple[str, str]:
    """``rosbag info PATH`` and ``rostui bag info PATH`` with the same TZ and locale; each must succeed."""
    env = {**ros_env, **TIME_ENV}
    theirs = subprocess.run(["rosbag", "info", str(path)], capture_output=True, text=True, env=env, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    ours = rostui(["bag", "info", str(path)], env, timeout=120)
    assert ours.returncode == 0, ours.stderr
    return theirs.stdout, ours.stdout


@pytest.mark.parametrize("name", ROSBAG_BAGS)
def test_info_of_a_rosbag_written_bag_is_rosbag_infos(rosbag_bags: Path, ros_env: dict[str, str], name: str) -> None:
    theirs, ours = _both(rosbag_bags / f"{name}.bag", ros_env)
    assert ours == theirs


def _rows(text: str) -> dict[str, str]:
    """``field: value`` rows of info text (continuation rows left out), values stripped."""
    pairs = [line.split(":", 1) for line in text.splitlines() if line[:1].strip()]
    return {key: value.strip() for key, value in pairs}


def test_the_odd_shapes_are_really_odd(rosbag_bags: Path, ros_env: dict[str, str]) -> None:
    """The bags exercise what they are meant to (guards the comparisons above against bland bags)."""
    text = {name: _both(rosbag_bags / f"{name}.bag", ros_env)[0]
            for name in ("backwards_none", "empty_lz4", "connections_bz2", "types_none", "minute_truncated", "day",
                         "seconds_rounding_up", "hundredths_carry", "mixed", "megabytes", "kilobytes")}
    rows = {name: _rows(t) for name, t in text.items()}
    assert rows["backwards_none"]["duration"].startswith("-")
    assert sorted(rows["empty_lz4"]) == ["path", "size", "version"]
    assert "/chatter   90 msgs    : std_msgs/String (3 connections)" in text["connections_bz2"]
    assert "1 msg     : std_msgs/Int32" in text["types_none"]
    assert "std_msgs/Int32            [0123456789abcdef0123456789abcdef]" in text["types_none"]
    mixed = "/mixed                            2 msgs    : std_msgs/Int32            (2 connections)"
    assert mixed in text["types_none"]
    assert any(line.endswith(" ") for line in text["types_none"].splitlines())
    assert rows["minute_truncated"]["duration"] == "1:54s (114s)"
    assert rows["day"]["duration"] == "25hr 1:01s (90061s)"
    assert rows["seconds_rounding_up"]["duration"] == "60.0s"
    assert rows["hundredths_carry"]["start"] == "Nov 22 2026 20:41:02.00 (1795360263.00)"  # in UTC+5:30
    assert rows["mixed"]["compression"].count("chunks") == 3
    assert rows["megabytes"]["size"].endswith(" MB") and rows["kilobytes"]["size"].endswith(" KB")


def test_unsorted_chunks_take_start_and_end_from_the_first_and_last_chunk(rosbag_bags: Path,
                                                                          ros_env: dict[str, str]) -> None:
    """rosbag info's start and end are the first chunk's start and the last chunk's end, not the bag's earliest
    and latest message; `--json` keeps the earliest and latest."""
    import json

    theirs, _ours = _both(rosbag_bags / "unsorted_none.bag", ros_env)
    result = rostui(["bag", "info", "--json", str(rosbag_bags / "unsorted_none.bag")], {**ros_env, **TIME_ENV})
    info = json.loads(result.stdout)
    start = next(line for line in theirs.splitlines() if line.startswith("start:"))
    end = next(line for line in theirs.splitlines() if line.startswith("end:"))
    assert f"({info['start']:.2f})" != start.rsplit(" ", 1)[1] or f"({info['end']:.2f})" != end.rsplit(" ", 1)[1]


def test_several_bags_print_as_rosbag_info_prints_them(rosbag_bags: Path, ros_env: dict[str, str]) -> None:
    paths = [str(rosbag_bags / f"{name}.bag") for name in ("empty_none", "types_lz4", "mixed")]
    env = {**ros_env, **TIME_ENV}
    theirs = subprocess.run(["rosbag", "info", *paths], capture_output=True, text=True, env=env, timeout=120)
    ours = rostui(["bag", "info", *paths], env, timeout=120)
    assert theirs.returncode == ours.returncode == 0, theirs.stderr + ours.stderr
    assert ours.stdout == theirs.stdout and theirs.stdout.count("---\n") == 2


def test_a_bag_converted_through_mcap_still_infos_as_rosbag(rosbag_bags: Path, tmp_path: Path,
                                                            ros_env: dict[str, str]) -> None:
    """rostui's `.bag` writer (via `bag convert` from an MCAP of a rosbag-written bag) gives a file whose info
    is rosbag's too."""
    for source, target in ((rosbag_bags / "connections_bz2.bag", tmp_path / "c.mcap"),
                           (tmp_path / "c.mcap", tmp_path / "c.bag")):
        result = rostui(["bag", "convert", str(source), str(target)], ros_env, timeout=120)
        assert result.returncode == 0, result.stderr
    theirs, ours = _both(tmp_path / "c.bag", ros_env)
    assert ours == theirs and "(3 connections)" in ours


STRING_MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"
INT32_MD5 = "da5909fbe378aeaf85e547e830cc1bb7"
T0 = 1795360262 * 10**9


def _write_rostui_bag(path: Path, compression: str, shape: str) -> None:
    writer = open_writer(str(path), compression)
    try:
        if shape == "connections":
            for conn_id, caller in enumerate(["/a", "/b", "/c"]):
                writer.add_connection(Connection(conn_id, "/chatter", "std_msgs/String", STRING_MD5, "string data\n",
                                                 caller, latching=conn_id == 1))
            writer.add_connection(Connection(3, "/one", "std_msgs/Int32", INT32_MD5, "int32 data\n", "/d"))
            writer.add_connection(Connection(4, "/odd_md5", "std_msgs/Int32", "f" * 32, "int32 data\n", "/e"))
            for i in range(400):
                writer.write(i % 3, T0 + i * 37_000_000, b"\x05\x00\x00\x00hello")
            writer.write(3, T0 + 5_000_000, b"\x01\x00\x00\x00")
            writer.write(4, T0 + 6_000_000, b"\x02\x00\x00\x00")
        else:
            writer.add_connection(Connection(0, "/big", "std_msgs/String", STRING_MD5, "string data\n", "/p"))
            blob = bytes((i * 131) % 251 for i in range(300_000))
            for i in range(20):
                writer.write(0, T0 + i * 6_431_000_000, len(blob).to_bytes(4, "little") + blob)
    finally:
        writer.close()


@pytest.mark.parametrize("compression", ["none", "bz2", "lz4"])
@pytest.mark.parametrize("shape", ["connections", "big"])
def test_info_of_a_rostui_written_bag_is_rosbag_infos(tmp_path: Path, ros_env: dict[str, str], compression: str,
                                                      shape: str) -> None:
    need_peer(_rosbag_tools(), "rosbag with its Python API (Debian python3-rosbag, python3-roslz4)")
    path = tmp_path / f"ours_{shape}_{compression}.bag"
    _write_rostui_bag(path, compression, shape)
    theirs, ours = _both(path, ros_env)
    assert ours == theirs
    assert ("(3 connections)" in ours) == (shape == "connections")


def _publishers(ros_env: dict[str, str], topic: str) -> int:
    import xmlrpc.client

    master = xmlrpc.client.ServerProxy(ros_env["ROS_MASTER_URI"])
    _code, _msg, (pubs, _subs, _srvs) = master.getSystemState("/info_test")
    return next((len(nodes) for name, nodes in pubs if name == topic), 0)


def test_info_of_a_bag_real_rosbag_record_wrote_is_rosbag_infos(tmp_path: Path, ros_env: dict[str, str],
                                                                 real_roscore: subprocess.Popen) -> None:
    """A bag as robots make them: C++ `rosbag record` with small lz4 chunks, two publishers on one topic (two
    connections with their callerids) and a latched topic."""
    need_command("rostopic")
    need_command("rosbag")
    path = tmp_path / "live.bag"
    pubs = [subprocess.Popen(argv, env=ros_env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
            for argv in (["rostopic", "pub", "-r", "40", "/chatter", "std_msgs/String", "data: from a",
                          "__name:=talker_a"],
                         ["rostopic", "pub", "-r", "30", "/chatter", "std_msgs/String", "data: from b",
                          "__name:=talker_b"],
                         ["rostopic", "pub", "-l", "/latched", "std_msgs/Int32", "data: 3", "__name:=latcher"])]
    try:
        wait_until(lambda: _publishers(ros_env, "/chatter") == 2 and _publishers(ros_env, "/latched") == 1,
                   "the three publishers to register")
        record = subprocess.run(["rosbag", "record", "-O", str(path), "--lz4", "--chunksize=1", "--duration=4",
                                 "/chatter", "/latched"], env=ros_env, capture_output=True, text=True, timeout=120)
        assert record.returncode == 0, record.stderr
    finally:
        for proc in pubs:
            stop_process(proc)
    theirs, ours = _both(path, ros_env)
    assert ours == theirs
    assert "(2 connections)" in theirs and "lz4 [" in theirs


ROSBAG_FORMATTERS = r'''
import json, sys
from rosbag.bag import _human_readable_size, _time_to_str
values = json.load(sys.stdin)
print(json.dumps({"sizes": [_human_readable_size(v) for v in values["sizes"]],
                  "times": ["%s (%.2f)" % (_time_to_str(v), v) for v in values["times"]]}))
'''


def test_sizes_and_times_format_as_rosbags_own_helpers(ros_env: dict[str, str]) -> None:
    """rostui's size and time text against the helpers `rosbag info` uses, on edges: a unit's rounding
    boundary (1023.95 KB prints ``1024.0 KB``), past yottabytes, hundredths that round up or sit on .xx5."""
    import json
    import random

    from rostui.tools.bag.info import human_size, human_time, seconds_of

    need_peer(_rosbag_tools(), "rosbag with its Python API (Debian python3-rosbag, python3-roslz4)")
    rng = random.Random(18)
    sizes = [0, 1, 512, 1023, 1024, 4096 + 300, 1048524, 1048525, 1048576, 1024**3 - 1, 1024**4 * 1023.96, 1024**8,
             1024**9, *(rng.randrange(1, 1 << 50) for _ in range(300))]
    stamps = [(0, 1), (1795360262, 996000000), (1795360262, 4999999), (1795360262, 5000000), (1795360262, 994999999),
              (2**32 - 1, 999999999), *((rng.randrange(0, 2**32), rng.randrange(0, 10**9)) for _ in range(300))]
    times = [seconds_of(s * 10**9 + n) for s, n in stamps]
    result = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_FORMATTERS], input=json.dumps({"sizes": sizes,
                            "times": times}), capture_output=True, text=True, env={**ros_env, **TIME_ENV}, timeout=60)
    assert result.returncode == 0, result.stderr
    theirs = json.loads(result.stdout)
    old_tz = os.environ.get("TZ")
    os.environ["TZ"] = TIME_ENV["TZ"]
    time.tzset()
    try:
        ours = {"sizes": [human_size(v) for v in sizes], "times": [human_time(v) for v in times]}
    finally:
        if old_tz is None:
            del os.environ["TZ"]
        else:
            os.environ["TZ"] = old_tz
        time.tzset()
    assert ours == theirs
    assert "1024.0 KB" in ours["sizes"] and "-" in ours["sizes"]


@pytest.mark.parametrize("compression", ["none", "lz4"])
def test_a_killed_rostui_bag_reindexed_by_either_tool_infos_as_rosbag(tmp_path: Path, ros_env: dict[str, str],
                                                                     compression: str) -> None:
    """A recording cut short (chunks out of time order, the last one lost) reindexed by `rosbag reindex` and by
    `rostui bag reindex`: both files' info is rosbag's."""
    need_command("rosbag")
    writer = open_writer(str(tmp_path / "killed.bag"), compression)
    writer.add_connection(Connection(0, "/late", "std_msgs/Int32", INT32_MD5, "int32 data\n", "/p"))
    writer.add_connection(Connection(1, "/early", "std_msgs/Int32", INT32_MD5, "int32 data\n", "/q"))
    for i in range(400):
        writer.write(i % 2, T0 + ((i * 53) % 400) * 250_000_000 + (i % 2) * 7_000_000_000, i.to_bytes(4, "little"))
        if i % 50 == 49:
            writer.flush()  # complete chunks, as the recorder's timer leaves them
    size = writer.size
    writer.out.close()  # killed: no close()
    with open(tmp_path / "killed.bag", "r+b") as f:
        f.truncate(size - 1200)  # into the last chunk
    shutil.copy(tmp_path / "killed.bag", tmp_path / "theirs.bag")
    reindexed = subprocess.run(["rosbag", "reindex", str(tmp_path / "theirs.bag")], capture_output=True, text=True,
                               env=ros_env, timeout=120)
    assert reindexed.returncode == 0, reindexed.stderr
    ours_reindex = rostui(["bag", "reindex", str(tmp_path / "killed.bag")], ros_env, timeout=120)
    assert ours_reindex.returncode == 0, ours_reindex.stderr
    infos = [_both(tmp_path / name, ros_env) for name in ("theirs.bag", "killed.bag")]
    for theirs, ours in infos:
        assert ours == theirs
    assert _rows(infos[0][0])["messages"] == _rows(infos[1][0])["messages"] == "350"


def test_the_real_span_beside_rosbags_duration_in_a_terminal(rosbag_bags: Path, ros_env: dict[str, str]) -> None:
    """Issue 31, 4: chunks out of time order make rosbag info's duration negative. `bag info` keeps rosbag's
    text byte for byte and says the messages' span in a note on stderr; `--exact` prints their start, end and
    duration; bag view's header shows the span and what bag info says instead."""
    from rostui.tools.bag.info import human_duration
    from tmux_helpers import rostui_line, shell_pane

    path = rosbag_bags / "backwards_none.bag"
    theirs, ours = _both(path, ros_env)
    assert ours == theirs
    rosbag_duration = _rows(theirs)["duration"]
    note = rostui(["bag", "info", str(path)], {**ros_env, **TIME_ENV}).stderr
    assert note.startswith(f"note: {path}: the duration {rosbag_duration} is rosbag's (its first and last chunk)")
    exact = rostui(["bag", "info", "--exact", "--json", str(path)], ros_env)
    span = json.loads(exact.stdout)["duration"]
    assert span > 0 and rosbag_duration.startswith("-")
    with shell_pane("span", 120, 30) as pane:
        pane.type(rostui_line({**ros_env, **TIME_ENV}, "SPAN_EXIT=", "bag", "info", "--exact", str(path)))
        pane.wait_until(lambda: "SPAN_EXIT=0" in pane.screen().replace("\n", ""), "bag info --exact")
        assert f"\nduration:    {human_duration(span)}\n" in pane.screen(), pane.screen()
        pane.clear()
        pane.type(rostui_line(ros_env, "SPAN_EXIT=", "bag", "view", str(path)))
        pane.wait_until(lambda: f"{span:.3f} s (bag info: {rosbag_duration}, first and last chunk)" in pane.screen(),
                        "bag view's header")
        pane.keys("q")
        pane.wait_until(lambda: "SPAN_EXIT=0" in pane.screen().replace("\n", ""), "bag view to quit")
