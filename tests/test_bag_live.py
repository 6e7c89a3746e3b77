"""Bags on a live graph: the book's bag of squares, real rosbag both ways, kills and a full disk."""

from __future__ import annotations

import json
import resource
import shutil
import signal
import subprocess
import time
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag.files import open_reader

from cli_helpers import rostui
from conftest import REPO, need_command, rostui_cmd, stop_process, wait_until
from live_helpers import DEADLINE, Program, Watcher, start_headless_sim, stop_all

HOME = (5.544444561004639, 5.544444561004639)


class Cmd:
    """A command started in the background with its output in files."""

    def __init__(self, argv: list[str], env: dict[str, str], tmp: Path, label: str, **popen: Any) -> None:
        self.out = tmp / f"{label}.out"
        with self.out.open("w") as out:
            self.proc = subprocess.Popen(argv, env=env, cwd=REPO, stdin=subprocess.DEVNULL, stdout=out,
                                         stderr=subprocess.STDOUT, **popen)

    @property
    def output(self) -> str:
        """What it printed so far."""
        return self.out.read_text(errors="replace")

    def wait_for(self, text: str, timeout: float = DEADLINE) -> None:
        """Wait until the output holds ``text``."""
        def check() -> bool:
            if text in self.output:
                return True
            assert self.proc.poll() is None, f"exited with {self.proc.returncode}:\n{self.output}"
            return False
        wait_until(check, repr(text), timeout)

    def stop(self) -> None:
        """Ctrl-C, then SIGKILL if needed."""
        stop_process(self.proc)

    close = stop

    def interrupt(self) -> int:
        """Ctrl-C and wait for the exit status."""
        self.proc.send_signal(signal.SIGINT)
        return self.proc.wait(timeout=DEADLINE)


def counts(path: Path) -> dict[str, int]:
    """Messages per topic, by reading every message back."""
    reader = open_reader(str(path))
    found: dict[str, int] = {}
    for conn, _t, _d in reader.messages():
        found[conn.topic] = found.get(conn.topic, 0) + 1
    reader.close()
    return found


def moved(watcher: Watcher, since: int, poses: Any) -> bool:
    """True when the turtle left the point where it stood at message ``since``."""
    msgs = poses.messages
    if len(msgs) <= since:
        return False
    start = msgs[since]
    return any(abs(m.x - start.x) + abs(m.y - start.y) > 0.5 for m in msgs[since:])


def recorders_on(watcher: Watcher, topic: str) -> int:
    """How many ``/record_...`` nodes subscribe to ``topic`` (real rosbag's output is buffered: ask the master)."""
    _pubs, subs, _srvs = watcher.engine.run(watcher.node.master_call("getSystemState"), timeout=DEADLINE)
    return sum(1 for name, nodes in subs if name == topic for n in nodes if n.startswith("/record_"))


def record_squares(ros_env: dict[str, str], tmp_path: Path, items: list, recorders: list[tuple[str, list[str]]],
                   seconds_of_velocity: int = 120) -> Watcher:
    """turtlesim + draw_square recorded by each recorder command until enough velocity messages went by."""
    sim = start_headless_sim(ros_env, tmp_path)
    items.append(sim)
    watcher = Watcher()
    items.append(watcher)
    poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
    poses.wait_for_count(1, "turtlesim's pose")
    started = [Cmd(argv, ros_env, tmp_path, label) for label, argv in recorders]
    items.extend(started)
    wait_until(lambda: recorders_on(watcher, "/turtle1/pose") >= len(started), "the recorders to subscribe")
    time.sleep(0.5)  # the recorders' subscriptions connect before the first command goes out
    square = Program(ros_env, tmp_path, "turtlesim", "draw_square")
    items.append(square)
    velocities = watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    velocities.wait_for_count(seconds_of_velocity, "draw_square's commands", timeout=60)
    for cmd in started:
        assert cmd.interrupt() == 0, cmd.output
    square.stop()
    return watcher


def test_the_book_bag_of_squares_records_and_replays_into_a_fresh_turtlesim(
        ros_env: dict[str, str], rostui_core: Any, tmp_path: Path) -> None:
    items: list = []
    bag, mcap = tmp_path / "square.bag", tmp_path / "square.mcap"
    topics = ["/turtle1/command_velocity", "/turtle1/pose"]
    try:
        watcher = record_squares(ros_env, tmp_path, items, [
            ("record_bag", rostui_cmd("bag", "record", "-O", str(bag), *topics)),
            ("record_mcap", rostui_cmd("run", "rosbag", "record", "-O", str(mcap), *topics)),
        ])
        for path in (bag, mcap):
            info = json.loads(rostui(["bag", "info", "--json", str(path)], ros_env).stdout)
            assert info["closed"]
            by_topic = {t["topic"]: t for t in info["topics"]}
            assert by_topic["/turtle1/command_velocity"]["types"] == ["turtlesim/Velocity"]
            assert by_topic["/turtle1/pose"]["types"] == ["turtlesim/Pose"]
            read = counts(path)
            assert {t: by_topic[t]["messages"] for t in topics} == read
            assert read["/turtle1/command_velocity"] >= 100
            assert info["messages"] == sum(read.values())
        text = rostui(["bag", "info", str(bag)], ros_env).stdout
        assert "turtlesim/Velocity [9d5c2dcd348ac8f76ce2a4307bd63a13]" in text
        # a fresh turtlesim, nobody drawing: the bag alone moves the turtle
        stop_all(items)
        items.clear()
        for path in (bag, mcap):
            sim = start_headless_sim(ros_env, tmp_path, "__name:=fresh_sim")
            items.append(sim)
            watcher = Watcher("bag_watcher")
            items.append(watcher)
            poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
            poses.wait_for_count(1, "the fresh turtlesim's pose")
            here = len(poses.messages)
            play = Cmd(rostui_cmd("bag", "play", "-r", "2", str(path)), ros_env, tmp_path, "play")
            items.append(play)
            assert play.proc.wait(timeout=60) == 0, play.output
            assert "[RUNNING]  Bag Time:" in play.output and "Duration:" in play.output
            wait_until(lambda: moved(watcher, here, poses), "the turtle to move", DEADLINE)
            stop_all(items)
            items.clear()
    finally:
        stop_all(items)


def test_rostui_bag_plays_with_real_rosbag_and_real_bags_play_with_rostui(
        ros_env: dict[str, str], real_roscore: Any, tmp_path: Path) -> None:
    need_command("rosbag")
    items: list = []
    ours, theirs = tmp_path / "ours.bag", tmp_path / "theirs.bag"
    topics = ["/turtle1/command_velocity", "/turtle1/pose"]
    try:
        record_squares(ros_env, tmp_path, items, [
            ("record_ours", rostui_cmd("bag", "record", "-O", str(ours), *topics)),
            ("record_theirs", ["rosbag", "record", "-O", str(theirs), *topics]),
        ], seconds_of_velocity=90)
        wait_until(lambda: theirs.exists(), "rosbag record to finish its file")
        real_info = subprocess.run(["rosbag", "info", str(ours)], capture_output=True, text=True, env=ros_env,
                                   timeout=60)
        assert real_info.returncode == 0 and "turtlesim/Velocity" in real_info.stdout, real_info.stderr
        for player, path in ((["rosbag", "play"], ours), (rostui_cmd("bag", "play"), theirs)):
            stop_all(items)
            items.clear()
            sim = start_headless_sim(ros_env, tmp_path, "__name:=fresh_sim")
            items.append(sim)
            watcher = Watcher("bag_watcher")
            items.append(watcher)
            poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
            poses.wait_for_count(1, "the fresh turtlesim's pose")
            here = len(poses.messages)
            play = Cmd([*player, str(path)], ros_env, tmp_path, "play")
            items.append(play)
            assert play.proc.wait(timeout=90) == 0, play.output
            wait_until(lambda: moved(watcher, here, poses), f"{player[0]} play to move the turtle", DEADLINE)
    finally:
        stop_all(items)


class Counter:
    """Publishes std_msgs/Int32 0, 1, 2 ... at a steady rate from a watcher node."""

    def __init__(self, watcher: Watcher, topic: str = "/count", size: int = 0) -> None:
        self.type = "std_msgs/Int32" if not size else "std_msgs/String"
        self.pub = watcher.publisher(topic, self.type)
        self.cls = self.pub.msg_class
        self.size = size
        self.sent = 0

    def publish(self, n: int = 1) -> None:
        """Publish ``n`` more messages."""
        for _ in range(n):
            if self.size:
                self.pub.publish(self.cls(data=f"{self.sent:08d}".ljust(self.size, "x")))
            else:
                self.pub.publish(self.cls(data=self.sent))
            self.sent += 1


@pytest.mark.parametrize("name", ["killed.bag", "killed.mcap"])
def test_sigkill_during_record_loses_at_most_the_last_second(ros_env: dict[str, str], rostui_core: Any,
                                                            tmp_path: Path, name: str) -> None:
    items: list = []
    path = tmp_path / name
    try:
        watcher = Watcher()
        items.append(watcher)
        counter = Counter(watcher)
        rec = Cmd(rostui_cmd("bag", "record", "-O", str(path), "/count"), ros_env, tmp_path, "record")
        items.append(rec)
        rec.wait_for("Subscribing to /count")
        wait_until(lambda: counter.pub.get_num_connections() > 0, "the recorder to connect")
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:  # 100 messages a second for three seconds
            counter.publish()
            time.sleep(0.01)
        sent_before_last_second = counter.sent - 100
        rec.proc.send_signal(signal.SIGKILL)
        rec.proc.wait(timeout=DEADLINE)
        reader = open_reader(str(path))
        from rostui.core.msg import get_message_class

        Int32 = get_message_class("std_msgs/Int32")
        values = [Int32.deserialize(d).data for _c, _t, d in reader.messages()]
        reader.close()
        assert values == list(range(len(values)))  # a prefix, nothing garbled
        assert len(values) >= sent_before_last_second
        info = rostui(["bag", "info", str(path)], ros_env)
        assert info.returncode == 0 and "not closed" in info.stdout
        play = rostui(["bag", "play", "-r", "50", str(path)], ros_env, timeout=60)
        assert play.returncode == 0, play.stderr
    finally:
        stop_all(items)


FILE_LIMIT = 3_000_000


def _small_file_limit() -> None:
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_LIMIT, FILE_LIMIT))


@pytest.mark.parametrize("name", ["full.bag", "full.mcap"])
def test_a_full_disk_stops_recording_with_a_clear_error_and_a_valid_file(ros_env: dict[str, str], rostui_core: Any,
                                                                        tmp_path: Path, name: str) -> None:
    items: list = []
    path = tmp_path / name
    try:
        watcher = Watcher()
        items.append(watcher)
        counter = Counter(watcher, size=10_000)
        rec = Cmd(rostui_cmd("bag", "record", "-O", str(path), "/count"), ros_env, tmp_path, "record",
                  preexec_fn=_small_file_limit)
        items.append(rec)
        rec.wait_for("Subscribing to /count")
        wait_until(lambda: counter.pub.get_num_connections() > 0, "the recorder to connect")
        deadline = time.monotonic() + DEADLINE
        while rec.proc.poll() is None and time.monotonic() < deadline:
            counter.publish()
            time.sleep(0.005)
        assert rec.proc.wait(timeout=DEADLINE) == 1
        lines = [line for line in rec.output.splitlines() if "rostui bag record:" in line]
        assert len(lines) == 1 and "File too large" in lines[0] and "Traceback" not in rec.output, rec.output
        info = json.loads(rostui(["bag", "info", "--json", str(path)], ros_env).stdout)
        assert info["closed"] and info["messages"] > 5
        assert path.stat().st_size <= FILE_LIMIT
        if name.endswith(".bag") and shutil.which("rosbag"):
            real = subprocess.run(["rosbag", "info", str(path)], capture_output=True, text=True, env=ros_env,
                                  timeout=60)
            assert real.returncode == 0, real.stderr
    finally:
        stop_all(items)


def test_record_all_finds_later_topics_excludes_and_splits(ros_env: dict[str, str], rostui_core: Any,
                                                           tmp_path: Path) -> None:
    items: list = []
    try:
        watcher = Watcher()
        items.append(watcher)
        rec = Cmd(rostui_cmd("bag", "record", "-a", "-x", "/skip.*", "-o", str(tmp_path / "all"), "--split",
                             "--size", "0.05", "--mcap"), ros_env, tmp_path, "record")
        items.append(rec)
        rec.wait_for("Recording to")
        later = Counter(watcher, "/later", size=1000)
        skipped = Counter(watcher, "/skipped")
        rec.wait_for("Subscribing to /later")
        wait_until(lambda: later.pub.get_num_connections() > 0, "the recorder to connect")
        for _ in range(150):
            later.publish()
            skipped.publish()
            time.sleep(0.002)
        time.sleep(0.5)
        assert rec.interrupt() == 0, rec.output
        assert "/skipped" not in rec.output
        files = sorted(tmp_path.glob("all_*.mcap"))
        assert len(files) >= 2 and all(f.name.endswith(("_0.mcap", "_1.mcap", "_2.mcap", "_3.mcap")) for f in files)
        total = sum(counts(f).get("/later", 0) for f in files)
        assert total == 150
        assert all("/skipped" not in counts(f) for f in files)
    finally:
        stop_all(items)


def test_play_remaps_filters_latches_and_honours_start_and_duration(ros_env: dict[str, str], rostui_core: Any,
                                                                    tmp_path: Path) -> None:
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection
    from rostui.core.msg import get_message_class

    Int32 = get_message_class("std_msgs/Int32")
    path = tmp_path / "counts.mcap"
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/c"))
    writer.add_connection(Connection(1, "/latched", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/l", True))
    writer.add_connection(Connection(2, "/other", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/o"))
    writer.write(1, 1_000_000_000, Int32(data=-1).serialize())
    for i in range(100):  # 0 .. 99, 10 ms apart, from t = 1 s
        writer.write(0, 1_000_000_000 + i * 10_000_000, Int32(data=i).serialize())
        writer.write(2, 1_000_000_000 + i * 10_000_000, Int32(data=i).serialize())
    writer.close()
    items: list = []
    try:
        watcher = Watcher()
        items.append(watcher)
        renamed = watcher.record("/renamed", "std_msgs/Int32")
        other = watcher.record("/other", "std_msgs/Int32")
        play = rostui(["bag", "play", "-d", "1", "-r", "2", "-s", "0.2", "-u", "0.5", "--topics", "/count",
                       "--topics", "/latched", "/count:=/renamed", str(path)], ros_env, timeout=60)
        assert play.returncode == 0, play.stderr
        values = [m.data for m in renamed.wait_for_count(1)]
        wait_until(lambda: len(renamed.messages) >= 51, "the played window")
        assert [m.data for m in renamed.messages] == list(range(20, 71))
        assert other.messages == []
        assert values[0] == 20
    finally:
        stop_all(items)
    items = []
    try:  # the latched topic reaches a subscriber that comes late
        play = Cmd(rostui_cmd("bag", "play", "-d", "0", "-l", "--topics", "/latched", str(path)), ros_env,
                   tmp_path, "play")
        items.append(play)
        time.sleep(1.0)
        watcher = Watcher("late")
        items.append(watcher)
        late = watcher.record("/latched", "std_msgs/Int32")
        assert late.wait_for_count(1)[0].data == -1
    finally:
        stop_all(items)


def test_play_clock_publishes_bag_time(ros_env: dict[str, str], rostui_core: Any, tmp_path: Path) -> None:
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection
    from rostui.core.msg import get_message_class

    Int32 = get_message_class("std_msgs/Int32")
    path = tmp_path / "clock.bag"
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/c"))
    for i in range(50):  # 0.5 s of bag time from t = 1000 s
        writer.write(0, 1000_000_000_000 + i * 10_000_000, Int32(data=i).serialize())
    writer.close()
    items: list = []
    try:
        watcher = Watcher()
        items.append(watcher)
        clock = watcher.record("/clock", "rosgraph_msgs/Clock")
        play = rostui(["bag", "play", "--clock", "-d", "1", str(path)], ros_env, timeout=60)
        assert play.returncode == 0, play.stderr
        stamps = [m.clock.to_sec() if hasattr(m.clock, "to_sec") else m.clock.secs + m.clock.nsecs / 1e9
                  for m in clock.wait_for_count(10)]
        assert all(1000.0 <= s <= 1000.5 for s in stamps), stamps
        assert stamps == sorted(stamps)
    finally:
        stop_all(items)


def test_record_stops_by_itself_at_max_size(ros_env: dict[str, str], rostui_core: Any, tmp_path: Path) -> None:
    items: list = []
    path = tmp_path / "capped.bag"
    try:
        watcher = Watcher()
        items.append(watcher)
        counter = Counter(watcher, size=10_000)
        rec = Cmd(rostui_cmd("bag", "record", "-O", str(path), "--max-size", "0.5", "/count"), ros_env, tmp_path,
                  "record")
        items.append(rec)
        rec.wait_for("Subscribing to /count")
        wait_until(lambda: counter.pub.get_num_connections() > 0, "the recorder to connect")
        deadline = time.monotonic() + DEADLINE
        while rec.proc.poll() is None and time.monotonic() < deadline:
            counter.publish()
            time.sleep(0.002)
        assert rec.proc.wait(timeout=DEADLINE) == 0, rec.output
        assert "Reached the maximum size of 0.5 MB" in rec.output
        recorded = counts(path)["/count"]
        assert 40 <= recorded <= 60  # 0.5 MB of 10 KB messages
    finally:
        stop_all(items)


def test_record_split_by_duration_and_stop_by_duration(ros_env: dict[str, str], rostui_core: Any,
                                                       tmp_path: Path) -> None:
    items: list = []
    try:
        watcher = Watcher()
        items.append(watcher)
        counter = Counter(watcher)
        split = Cmd(rostui_cmd("bag", "record", "-O", str(tmp_path / "parts.bag"), "--split", "--duration", "1s",
                               "/count"), ros_env, tmp_path, "split")
        items.append(split)
        once = Cmd(rostui_cmd("bag", "record", "-O", str(tmp_path / "once.mcap"), "--duration", "0.05m", "/count"),
                   ros_env, tmp_path, "once")  # 3 s
        items.append(once)
        split.wait_for("Subscribing to /count")
        once.wait_for("Subscribing to /count")
        wait_until(lambda: counter.pub.get_num_connections() >= 2, "both recorders to connect")
        while once.proc.poll() is None:  # the 3 s recorder stops by itself
            counter.publish()
            time.sleep(0.02)
            assert counter.sent < 50 * DEADLINE, "record --duration 0.05m never stopped"
        assert once.proc.wait() == 0, once.output
        sent_while_once = counter.sent
        time.sleep(0.3)
        assert split.interrupt() == 0, split.output
        pieces = sorted(tmp_path.glob("parts_*.bag"), key=lambda p: int(p.stem.split("_")[1]))
        assert [p.name for p in pieces] == [f"parts_{i}.bag" for i in range(len(pieces))]
        assert len(pieces) >= 3, split.output
        per_piece = [counts(p).get("/count", 0) for p in pieces]
        assert sum(per_piece) == counter.sent  # nothing lost at the cuts
        assert all(n > 0 for n in per_piece[:-1]), per_piece
        once_count = counts(tmp_path / "once.mcap")["/count"]
        assert 0 < once_count <= sent_while_once
        reader = open_reader(str(tmp_path / "once.mcap"))
        summary = reader.summary()
        reader.close()
        assert summary.closed
        assert 0 < (summary.end_ns - summary.start_ns) / 1e9 <= 3.5  # 3 s of file (checked five times a second)
    finally:
        stop_all(items)
