#!/usr/bin/env python3
"""Big bags: `rostui bag view` opening 2 GB files, and `rostui bag play` of a 2 GB bag against `rosbag play`.

Files (written by rostui's own writers, ``rostui.core.bag.files.open_writer``,
into ``--dir``, deleted at the end):
- ``robot.bag`` (rosbag v2.0, uncompressed like ``rosbag record``'s default)
  and ``robot.mcap`` (lz4 chunks), ``--size`` GB each: a robot-like mix of
  /camera/image_raw (sensor_msgs/Image 640x480 rgb8, 30 Hz, a moving
  pattern with noise), /scan (LaserScan, 1081 ranges, 40 Hz), /imu (Imu,
  200 Hz), /tf (tf2_msgs/TFMessage, 100 Hz) and /odom (nav_msgs/Odometry,
  50 Hz);
- ``small.bag``: ``--small-count`` messages of Imu/TFMessage/Odometry size
  (no image), for the per-message index; ``mid.bag`` (``--mid-count``) and
  ``tiny.bag`` (``--tiny-count``, the baseline) of the same mix: the view's
  peak memory above tiny.bag's, per message (issue 35: at most 16 bytes);
- ``old.bag``: ``--old-size`` MB of the robot mix, for the implementation
  before the lazy index (commit ``--old-commit``, checked out in a worktree
  of its own), which read every payload into memory.

(a) ``view``: `rostui bag view FILE` runs in a private tmux server (120x30)
    and capture-pane is polled until the header shows the bag's message count
    and the timeline every topic with its count: the time to first screen is
    from starting tmux to that. The view's VmHWM (peak resident set, from
    /proc/PID/status) is read then and again 2 s later; then ``5`` seeks to
    50% (timed until the status line says 50%), ``s`` steps three times, and
    VmHWM is read once more, and again after 5 s of play at x16 (bytes a
    message above tiny.bag's are counted from that last one). Each file is opened
    warm (in the page cache) and cold (its pages dropped first with
    posix_fadvise DONTNEED, only that file's). rqt_bag is not packaged in
    Debian; what it stands on, the rosbag Python API, is measured instead on
    the .bag files: ``rosbag.Bag(FILE)`` (which reads the whole index) and
    the per-topic entry walk rqt_bag's timeline makes, time and VmHWM.
(b) ``play``: a Debian ``roscore`` on a free port; ``bench/bag_tally.cpp``
    (one roscpp node, any type, a queue of 10^6) subscribes to every topic
    and counts messages and bytes, and the lag of each message behind the
    player's schedule (its stamp / rate). `rostui bag play -r R` of
    robot.bag and robot.mcap and `rosbag play -r R` of robot.bag, for each R
    of ``--rates`` (small.bag at ``--small-rates``): time from first to last
    arrival, messages/s and MB/s delivered, lag, and the ratio rostui/rosbag
    of the delivered rate. A rate is *held* when every message arrived and
    the last was late by at most 5% of the schedule (0.1 s at least); the
    highest rate each player holds is compared.
``--load N`` runs N busy-looping processes during the whole benchmark.

    .venv/bin/python bench/bench_bag_view.py [--size 2] [--small-count 5000000] [--mid-count 1000000]
        [--tiny-count 10000] [--old-size 400] [--rates 10,20,30,40,50,100] [--small-rates 1000] [--load N]
        [--only view|play] [--dir /tmp] [--keep DIR] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import uuid
import xmlrpc.client
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterator

from _common import REPO, build_cpp, free_port, ros_env, wait_port

sys.path.insert(0, str(REPO))
GB = 1_000_000_000
MB = 1_000_000
BENCH = Path(__file__).resolve().parent
TALLY_SRC = BENCH / "bag_tally.cpp"
TALLY = BENCH / "_build" / "bag_tally"
T0_NS = 1_700_000_000_000_000_000
COLS, ROWS = 120, 30

RULE = "=" * 80
HEADER = """uint32 seq
time stamp
string frame_id"""
VECTOR3 = "float64 x\nfloat64 y\nfloat64 z"
QUATERNION = "float64 x\nfloat64 y\nfloat64 z\nfloat64 w"


def _full(main: str, *deps: tuple[str, str]) -> str:
    return main + "".join(f"\n{RULE}\nMSG: {name}\n{text}\n" for name, text in deps)


# Message definitions (the field lists of the ROS 1 packages, comments left out: md5 sums are computed from
# fields alone, and are checked below against the published ones).
DEFINITIONS: dict[str, tuple[str, str]] = {
    "sensor_msgs/Image": ("060021388200f6f0f447d0fcd9c64743", _full(
        "Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\nuint8[] data",
        ("std_msgs/Header", HEADER))),
    "sensor_msgs/LaserScan": ("90c7ef2dc6895d81024acba2ac42f369", _full(
        "Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\nfloat32 time_increment\n"
        "float32 scan_time\nfloat32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities",
        ("std_msgs/Header", HEADER))),
    "sensor_msgs/Imu": ("6a62c6daae103f4ff57a132d6f95cec2", _full(
        "Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
        "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
        "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance",
        ("std_msgs/Header", HEADER), ("geometry_msgs/Quaternion", QUATERNION), ("geometry_msgs/Vector3", VECTOR3))),
    "tf2_msgs/TFMessage": ("94810edda583a504dfda3829e70d7eec", _full(
        "geometry_msgs/TransformStamped[] transforms",
        ("geometry_msgs/TransformStamped", "Header header\nstring child_frame_id\ngeometry_msgs/Transform transform"),
        ("std_msgs/Header", HEADER),
        ("geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation"),
        ("geometry_msgs/Vector3", VECTOR3), ("geometry_msgs/Quaternion", QUATERNION))),
    "nav_msgs/Odometry": ("cd5e73d190d741a2f92e81eda573aca7", _full(
        "Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
        "geometry_msgs/TwistWithCovariance twist",
        ("std_msgs/Header", HEADER),
        ("geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance"),
        ("geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation"),
        ("geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z"),
        ("geometry_msgs/Quaternion", QUATERNION),
        ("geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance"),
        ("geometry_msgs/Twist", "geometry_msgs/Vector3  linear\ngeometry_msgs/Vector3  angular"),
        ("geometry_msgs/Vector3", VECTOR3))),
}


@dataclass
class Stream:
    """One topic of a generated bag: its type, rate, where its stamp lies, and how to make message ``i``."""

    topic: str
    type: str
    hz: float
    stamp_offset: int
    make: Callable[[int, int], bytes]


def _templates() -> dict[str, Any]:
    """Filled-in serialized messages per type (built with rostui's message classes from the definitions)."""
    import numpy as np

    from rostui.core.msg import MessageError, connection_class, get_message_class

    rng = np.random.default_rng(18)
    out: dict[str, Any] = {}
    classes = {}
    for name, (md5, text) in DEFINITIONS.items():
        try:
            classes[name] = connection_class(name, md5, text)
        except MessageError as exc:
            raise SystemExit(f"the definition of {name}: {exc}") from None
    scan = classes["sensor_msgs/LaserScan"]()
    scan.header.frame_id = "laser"
    scan.angle_min, scan.angle_max, scan.angle_increment = -2.356, 2.356, 0.004363
    scan.scan_time, scan.range_min, scan.range_max = 0.025, 0.05, 30.0
    scan.ranges = (rng.random(1081) * 30).astype(np.float32).tolist()
    scan.intensities = (rng.random(1081) * 1000).astype(np.float32).tolist()
    out["sensor_msgs/LaserScan"] = scan.serialize()
    imu = classes["sensor_msgs/Imu"]()
    imu.header.frame_id = "imu_link"
    imu.orientation.w, imu.orientation.z = 0.96, 0.28
    imu.orientation_covariance = [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]
    imu.angular_velocity.z, imu.linear_acceleration.z = 0.12, 9.81
    imu.angular_velocity_covariance = imu.linear_acceleration_covariance = imu.orientation_covariance
    out["sensor_msgs/Imu"] = imu.serialize()
    tf_cls = classes["tf2_msgs/TFMessage"]
    transform_cls = get_message_class("geometry_msgs/TransformStamped")  # registered with TFMessage
    tf = tf_cls()
    for parent, child in (("odom", "base_link"), ("base_link", "laser"), ("base_link", "camera")):
        t = transform_cls()
        t.header.frame_id, t.child_frame_id = parent, child
        t.transform.translation.x, t.transform.rotation.w = 0.3, 1.0
        tf.transforms.append(t)
    out["tf2_msgs/TFMessage"] = tf.serialize()
    odom = classes["nav_msgs/Odometry"]()
    odom.header.frame_id, odom.child_frame_id = "odom", "base_link"
    odom.pose.pose.position.x, odom.pose.pose.orientation.w = 1.5, 1.0
    odom.pose.covariance = odom.twist.covariance = rng.random(36).tolist()
    odom.twist.twist.linear.x = 0.4
    out["nav_msgs/Odometry"] = odom.serialize()
    # a 640x480 rgb8 picture: smooth gradients plus noise (compresses a little, like a camera's), twice as
    # wide as needed so each frame is a different window of it
    y, x = np.mgrid[0:480, 0:1280]
    base = np.stack([(x * 255 // 1280), (y * 255 // 480), ((x + y) % 256)], axis=-1).astype(np.int16)
    base += rng.integers(-12, 12, size=base.shape, dtype=np.int16)
    out["image_base"] = np.clip(base, 0, 255).astype(np.uint8)
    head = classes["sensor_msgs/Image"]()
    head.header.frame_id = "camera"
    head.height, head.width, head.encoding, head.step = 480, 640, "rgb8", 1920
    out["image_head"] = head.serialize()[:-4]  # all but data's (empty) length
    return out


def _stamped(template: bytes, at: int) -> Callable[[int, int], bytes]:
    """Message ``i`` at ``t_ns``: the template with its seq and stamp (at byte ``at``) filled in."""
    def make(i: int, t_ns: int) -> bytes:
        buf = bytearray(template)
        struct.pack_into("<III", buf, at - 4, i, t_ns // 1_000_000_000, t_ns % 1_000_000_000)
        return bytes(buf)
    return make


def robot_streams(tpl: dict[str, Any], *, image: bool = True) -> list[Stream]:
    """The robot-like mix (without the camera for the small-message bag)."""
    streams = []
    if image:
        head, base = tpl["image_head"], tpl["image_base"]

        def make_image(i: int, t_ns: int) -> bytes:
            shift = (i * 7) % 640
            frame = base[:, shift:shift + 640].tobytes()
            buf = bytearray(head)
            struct.pack_into("<III", buf, 0, i, t_ns // 1_000_000_000, t_ns % 1_000_000_000)
            return bytes(buf) + struct.pack("<I", len(frame)) + frame
        streams.append(Stream("/camera/image_raw", "sensor_msgs/Image", 30, 4, make_image))
        streams.append(Stream("/scan", "sensor_msgs/LaserScan", 40, 4, _stamped(tpl["sensor_msgs/LaserScan"], 4)))
    streams += [Stream("/imu", "sensor_msgs/Imu", 200 if image else 1000, 4, _stamped(tpl["sensor_msgs/Imu"], 4)),
                Stream("/tf", "tf2_msgs/TFMessage", 100 if image else 500, 8,
                       _stamped(tpl["tf2_msgs/TFMessage"], 8)),
                Stream("/odom", "nav_msgs/Odometry", 50 if image else 500, 4, _stamped(tpl["nav_msgs/Odometry"], 4))]
    return streams


def schedule(streams: list[Stream]) -> Iterator[tuple[int, int, int]]:
    """``(t_ns, stream number, i)`` of every message of every stream, in time order, for ever."""
    import heapq

    periods = [int(1e9 / s.hz) for s in streams]
    heap = [(k * 97_000, k, 0) for k in range(len(streams))]  # streams start a little apart
    while True:
        t, k, i = heapq.heappop(heap)
        yield t, k, i
        heapq.heappush(heap, (t + periods[k], k, i + 1))


def generate(path: Path, streams: list[Stream], *, size: int = 0, count: int = 0, compression: str = "none") -> int:
    """Write ``streams`` into ``path`` until it holds ``size`` bytes or ``count`` messages; returns the count."""
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection

    writer = open_writer(str(path), compression)
    for k, s in enumerate(streams):
        md5, text = DEFINITIONS[s.type]
        writer.add_connection(Connection(k, s.topic, s.type, md5, text, "/bench_robot"))
    written = 0
    for t, k, i in schedule(streams):
        if (size and writer.size >= size) or (count and written >= count):
            break
        t_ns = T0_NS + t
        writer.write(k, t_ns, streams[k].make(i, t_ns))
        written += 1
    writer.close()
    return written


# ----------------------------------------------------------------------------- (a) bag view
def vm_hwm_mb(pid: int) -> float:
    """Peak resident set of ``pid`` in MB (VmHWM), 0 when it is gone."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024 / MB
    except OSError:
        pass
    return 0.0


def drop_from_cache(path: Path) -> None:
    """Evict ``path``'s pages from the page cache (that file only)."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
        os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
    finally:
        os.close(fd)


class Tmux:
    """One private tmux server with one session running a command."""

    def __init__(self, command: list[str], env: dict[str, str], cwd: Path) -> None:
        self.socket = f"bench-bagview-{os.getpid()}-{uuid.uuid4().hex[:8]}"
        env = {k: v for k, v in env.items() if k not in ("COLUMNS", "LINES", "TMUX")}
        env["TERM"] = "xterm-256color"
        line = "exec " + shlex.join(command)
        subprocess.run(["tmux", "-u", "-L", self.socket, "-f", "/dev/null", "new-session", "-d", "-s", "bench",
                        "-x", str(COLS), "-y", str(ROWS), "sh", "-c", line], env=env, cwd=cwd, check=True, timeout=30)

    def run(self, *args: str) -> str:
        """A tmux command's stdout."""
        return subprocess.run(["tmux", "-L", self.socket, *args], capture_output=True, text=True, timeout=30).stdout

    def pid(self) -> int:
        """The pane's process (the command, after sh's exec)."""
        return int(self.run("display-message", "-p", "-t", "bench", "#{pane_pid}").strip() or 0)

    def screen(self) -> str:
        """The visible text."""
        return self.run("capture-pane", "-p", "-t", "bench")

    def close(self) -> None:
        """Kill the server and its session."""
        subprocess.run(["tmux", "-L", self.socket, "kill-server"], capture_output=True, timeout=30)


def first_screen(screen: str, total: int, counts: dict[str, int]) -> bool:
    """True when the header shows ``total`` msgs and the timeline each topic with its count."""
    if f"{total} msgs" not in screen:
        return False
    lines = screen.splitlines()
    return all(any(topic in line and f" {n} " in f"{line} " for line in lines) for topic, n in counts.items())


def open_view(path: Path, counts: dict[str, int], env: dict[str, str], source: Path,
              timeout: float = 180.0) -> dict[str, Any]:
    """Time to first screen and VmHWM of `rostui bag view PATH` run from the rostui tree at ``source``."""
    total = sum(counts.values())
    env = dict(env, PYTHONPATH=str(source))
    start = time.perf_counter()
    tmux = Tmux([sys.executable, "-m", "rostui", "bag", "view", str(path)], env, source)
    try:
        pid = tmux.pid()
        shown = None
        peak = 0.0
        while time.perf_counter() - start < timeout:
            peak = max(peak, vm_hwm_mb(pid))
            if first_screen(tmux.screen(), total, counts):
                shown = time.perf_counter() - start
                break
            time.sleep(0.02)
        at_screen = vm_hwm_mb(pid)
        time.sleep(2.0)
        settled = vm_hwm_mb(pid)
        seek_s = None
        if shown is not None:  # 5 seeks to 50% (the chunks there are read), then three steps
            asked = time.perf_counter()
            tmux.run("send-keys", "-t", "bench", "5")
            while time.perf_counter() - asked < 30:
                if " 50%" in tmux.screen():
                    seek_s = time.perf_counter() - asked
                    break
                time.sleep(0.02)
            for _ in range(3):
                tmux.run("send-keys", "-t", "bench", "s")
                time.sleep(0.2)
            time.sleep(1.0)
        after_seek = vm_hwm_mb(pid)
        if shown is not None:  # then play at x16 for 5 s (every chunk on the way is read)
            tmux.run("send-keys", "-t", "bench", "space", "+", "+", "+", "+")
            time.sleep(5.0)
        after_play = vm_hwm_mb(pid)
        screen = tmux.screen()
        tmux.run("send-keys", "-t", "bench", "q")
        deadline = time.monotonic() + 15
        while Path(f"/proc/{pid}").exists() and time.monotonic() < deadline:
            time.sleep(0.05)
    finally:
        tmux.close()
    out = {"first_screen_s": shown, "hwm_at_screen_mb": max(at_screen, peak), "hwm_after_2s_mb": settled,
           "seek_s": seek_s, "hwm_after_seek_mb": after_seek, "hwm_after_play_mb": after_play}
    if shown is None:
        out["screen"] = screen
    return out


ROSBAG_INDEX_WALK = r"""
import os, sys, time
t = time.perf_counter()
import rosbag
bag = rosbag.Bag(sys.argv[1])
info = bag.get_type_and_topic_info()
opened = time.perf_counter() - t
walked = 0
for topic in info.topics:  # what rqt_bag's timeline does to draw each topic's messages
    for entry in bag._get_entries(bag._get_connections(topic)):
        walked += 1
took = time.perf_counter() - t
for line in open("/proc/self/status"):
    if line.startswith("VmHWM:"):
        print(opened, took, walked, int(line.split()[1]) * 1024)
"""


def rosbag_api(path: Path) -> dict[str, Any]:
    """Time and VmHWM of the rosbag Python API opening ``path`` and walking its index (rqt_bag's load)."""
    done = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_INDEX_WALK, str(path)], capture_output=True, text=True,
                          timeout=900)
    if done.returncode != 0:
        return {"error": done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"}
    opened, took, walked, hwm = done.stdout.split()
    return {"open_s": float(opened), "open_and_walk_s": float(took), "entries": int(walked), "hwm_mb": int(hwm) / MB}


def topic_counts(path: Path) -> dict[str, int]:
    """Messages per topic (from the file's summary)."""
    from rostui.core.bag.files import open_reader

    reader = open_reader(str(path))
    try:
        counts: dict[str, int] = {}
        for conn_id, c in reader.summary().counts.items():
            topic = reader.connections[conn_id].topic
            counts[topic] = counts.get(topic, 0) + c
        return counts
    finally:
        reader.close()


def bench_view(files: dict[str, Path], old: Path | None, old_tree: Path | None, env: dict[str, str],
               repeats: int) -> dict[str, Any]:
    """Every file, warm and cold, with this tree's bag view; old.bag also with the old tree's; rosbag's API."""
    out: dict[str, Any] = {}
    runs = [(name, path, REPO) for name, path in files.items()]
    if old is not None:
        runs.append(("old.bag (this tree)", old, REPO))
        if old_tree is not None:
            runs.append(("old.bag (old tree)", old, old_tree))
    for name, path, tree in runs:
        counts = topic_counts(path)
        size = path.stat().st_size
        rows = []
        for cache in ("cold", "warm") * repeats:
            if cache == "cold":
                drop_from_cache(path)
            else:
                path.read_bytes() if size < 4 * GB else None
            r = open_view(path, counts, env, tree)
            r["cache"] = cache
            rows.append(r)
            shown = "NEVER" if r["first_screen_s"] is None else f"{r['first_screen_s']:.2f} s"
            seek = "never" if r["seek_s"] is None else f"{r['seek_s']:.2f} s"
            print(f"  {name:22} {size / MB:7.0f} MB {sum(counts.values()):9d} msgs {cache}: first screen {shown}, "
                  f"VmHWM {r['hwm_at_screen_mb']:.0f} MB then {r['hwm_after_2s_mb']:.0f} MB 2 s later; "
                  f"seek to 50% {seek}, after it and 3 steps {r['hwm_after_seek_mb']:.0f} MB, after 5 s of play at "
                  f"x16 {r['hwm_after_play_mb']:.0f} MB; load {load_average()}",
                  flush=True)
            if r["first_screen_s"] is None:
                print(r["screen"], flush=True)
        out[name] = {"size_mb": size / MB, "messages": sum(counts.values()), "runs": rows}
    tiny = out.get("tiny.bag")
    if tiny is not None:  # issue 35: memory above a small bag's, per message
        base = max(r["hwm_after_play_mb"] for r in tiny["runs"])
        for name in ("mid.bag", "small.bag"):
            if name in out:
                peak = max(r["hwm_after_play_mb"] for r in out[name]["runs"])
                extra = (peak - base) * MB / max(out[name]["messages"] - tiny["messages"], 1)
                out[name]["bytes_a_message_above_tiny"] = extra
                print(f"  {name}: VmHWM {peak:.0f} MB, tiny.bag's {base:.0f} MB: {extra:.1f} bytes a message above "
                      "a small bag's", flush=True)
    for name, path in [*files.items(), *([("old.bag", old)] if old is not None else [])]:
        if not name.endswith(".bag"):
            continue
        drop_from_cache(path)
        r = rosbag_api(path)
        out.setdefault("rosbag_api", {})[name] = r
        if "error" in r:
            print(f"  rosbag.Bag {name}: {r['error']}", flush=True)
        else:
            print(f"  rosbag.Bag({name}) cold: open {r['open_s']:.2f} s, open + walk of {r['entries']} entries "
                  f"{r['open_and_walk_s']:.2f} s, VmHWM {r['hwm_mb']:.0f} MB", flush=True)
    return out


# ----------------------------------------------------------------------------- (b) play
def build_tally() -> Path | None:
    """Compile bench/bag_tally.cpp unless the binary is newer; None when it cannot be built."""
    return build_cpp(TALLY_SRC)


def subscribed(env: dict[str, str], topics: list[str]) -> bool:
    """True when a /bag_tally node subscribes to every topic."""
    state = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/bench")[2]
    subs = {t: nodes for t, nodes in state[1]}
    return all(any(n.startswith("/bag_tally") for n in subs.get(t, [])) for t in topics)


def play_once(player: list[str], streams: list[Stream], rate: float, env: dict[str, str]) -> dict[str, Any]:
    """One playback to the tally: what arrived, how fast, how late."""
    specs = [f"{s.topic}:{s.stamp_offset}" for s in streams]
    tally = subprocess.Popen([str(TALLY), str(rate), *specs], env=env, stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True)
    try:
        deadline = time.monotonic() + 30
        while not subscribed(env, [s.topic for s in streams]):
            if time.monotonic() > deadline:
                raise RuntimeError("bag_tally never subscribed")
            time.sleep(0.05)
        start = time.perf_counter()
        subprocess.run(player, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=1800)
        wall = time.perf_counter() - start
        out, _ = tally.communicate(timeout=60)
    finally:
        if tally.poll() is None:
            tally.kill()
            tally.wait()
    result = json.loads(out.strip().splitlines()[-1])
    received = sum(n for n, _ in result["topics"].values())
    nbytes = sum(b for _, b in result["topics"].values())
    span = max(result["last_s"] - result["first_s"], 1e-9)
    return {"received": received, "bytes": nbytes, "span_s": span, "player_wall_s": wall,
            "msgs_per_s": received / span, "mb_per_s": nbytes / MB / span, "lag_p50_s": result["lag_p50_s"],
            "lag_p99_s": result["lag_p99_s"], "lag_max_s": result["lag_max_s"], "lag_last_s": result["lag_last_s"],
            "per_topic": result["topics"]}


def bench_play(files: dict[str, tuple[Path, list[Stream], int, list[float]]], env: dict[str, str]) -> dict[str, Any]:
    """rostui bag play of each file and rosbag play of each .bag, at each of the file's rates.

    A rate is held when every message arrived and the last one was late by at most 5% of the schedule
    (0.1 s at least)."""
    out: dict[str, Any] = {}
    for name, (path, streams, count, rates) in files.items():
        bag_span = bag_span_s(path)
        for rate in rates:
            players = {"rostui": [sys.executable, "-m", "rostui", "bag", "play", "-q", "-d", "1", "-r", str(rate),
                                  str(path)]}
            if name.endswith(".bag"):
                players["rosbag"] = ["rosbag", "play", "-q", "-d", "1", "-r", str(rate), str(path)]
            for player, argv in players.items():
                r = play_once(argv, streams, rate, env)
                r["load"] = load_average()
                out.setdefault(name, {}).setdefault(str(rate), {})[player] = r
                scheduled = bag_span / rate
                r["held"] = r["received"] == count and r["lag_last_s"] <= max(0.1, 0.05 * scheduled)
                print(f"  {player:7} play -r {rate:g} {name:10}: {r['received']}/{count} msgs in {r['span_s']:.2f} s "
                      f"(schedule {scheduled:.2f} s): {r['msgs_per_s']:.0f} msg/s, {r['mb_per_s']:.0f} MB/s; lag "
                      f"p50 {r['lag_p50_s']:.2f} s, p99 {r['lag_p99_s']:.2f} s, at the end {r['lag_last_s']:.2f} s"
                      f"{' HELD' if r['held'] else ''}; load {r['load']}", flush=True)
            row = out[name][str(rate)]
            if "rosbag" in row and row["rosbag"]["msgs_per_s"]:
                ratio = row["rostui"]["msgs_per_s"] / row["rosbag"]["msgs_per_s"]
                row["ratio_rostui_rosbag"] = ratio
                print(f"  -r {rate:g} {name}: rostui/rosbag delivered rate {ratio:.2f}x", flush=True)
        for player in ("rostui", "rosbag"):
            held = [rate for rate in rates if out[name][str(rate)].get(player, {}).get("held")]
            if player in out[name][str(rates[0])]:
                out[name].setdefault("highest_held", {})[player] = max(held, default=0)
        best = out[name]["highest_held"]
        ratio = f"; rostui/rosbag {best['rostui'] / best['rosbag']:.2f}x" if best.get("rosbag") else ""
        print(f"  {name}: highest rate held (every message, on schedule) "
              + ", ".join(f"{p} -r {r:g}" if r else f"{p} none of them" for p, r in best.items()) + ratio,
              flush=True)
    return out


def bag_span_s(path: Path) -> float:
    """Seconds from the first to the last message."""
    from rostui.core.bag.files import open_reader

    reader = open_reader(str(path))
    try:
        summary = reader.summary()
        assert summary.message_count
        return (summary.end_ns - summary.start_ns) / 1e9
    finally:
        reader.close()


def load_average() -> str:
    """The 1, 5 and 15 minute load averages."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def old_worktree(commit: str, where: Path) -> Path | None:
    """A detached worktree of ``commit`` at ``where`` (made once); None when git cannot make it."""
    if not (where / "rostui").is_dir():
        done = subprocess.run(["git", "-C", str(REPO), "worktree", "add", "--detach", str(where), commit],
                              capture_output=True, text=True)
        if done.returncode != 0:
            print(f"  cannot check out {commit}: {done.stderr.strip()}", flush=True)
            return None
    return where


def main() -> int:
    """Generate the files, run the benchmarks, delete the files."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=float, default=2.0, help="GB of robot.bag and of robot.mcap; 0 leaves them out.")
    parser.add_argument("--small-count", type=int, default=5_000_000,
                        help="Messages of small.bag (Imu, TFMessage, Odometry); 0 leaves it out.")
    parser.add_argument("--mid-count", type=int, default=1_000_000,
                        help="Messages of mid.bag (as small.bag); 0 leaves it out.")
    parser.add_argument("--tiny-count", type=int, default=10_000,
                        help="Messages of tiny.bag (as small.bag), the baseline of bytes a message; 0 leaves it out.")
    parser.add_argument("--old-size", type=float, default=400, help="MB of old.bag; 0 leaves it out.")
    parser.add_argument("--old-commit", default="da0f12e", help="The bag view before the lazy index.")
    parser.add_argument("--old-tree", default=str(REPO.parent / f"{REPO.name}-old"),
                        help="Where the old commit is checked out (a detached git worktree).")
    parser.add_argument("--rates", default="10,20,30,40,50,100", help="Playback rates (-r) of the robot files in (b).")
    parser.add_argument("--small-rates", default="1000",
                        help="Playback rates of small.bag in (b) ('' leaves it out; 1000 plays it flat out).")
    parser.add_argument("--load", type=int, default=0,
                        help="Run this many busy-looping processes (CPU load) during the whole benchmark.")
    parser.add_argument("--repeats", type=int, default=1, help="Cold+warm opens per file in (a).")
    parser.add_argument("--only", choices=["view", "play"], help="Run one part.")
    parser.add_argument("--dir", default="/tmp", help="Where the files go (they are deleted at the end).")
    parser.add_argument("--keep", help="Keep the files in this folder and reuse them on the next run.")
    parser.add_argument("--json", help="Write the results to this file.")
    args = parser.parse_args()
    if args.keep:
        tmp = Path(args.keep)
        tmp.mkdir(parents=True, exist_ok=True)
    else:
        tmp = Path(tempfile.mkdtemp(prefix="bench_bag_view_", dir=args.dir))
    results: dict[str, Any] = {"load_before": load_average(), "args": vars(args)}
    print(f"files in {tmp}; load average {results['load_before']}", flush=True)
    roscore: subprocess.Popen | None = None
    burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.load)]
    if burners:
        print(f"  {len(burners)} busy-looping processes run alongside (--load)", flush=True)
    try:
        tpl = _templates()
        robot, small = robot_streams(tpl), robot_streams(tpl, image=False)
        plan = [("robot.bag", robot, int(args.size * GB), 0, "none"),
                ("robot.mcap", robot, int(args.size * GB), 0, "lz4")] if args.size else []
        if args.tiny_count:
            plan.append(("tiny.bag", small, 0, args.tiny_count, "none"))
        if args.mid_count:
            plan.append(("mid.bag", small, 0, args.mid_count, "none"))
        if args.small_count:
            plan.append(("small.bag", small, 0, args.small_count, "none"))
        if args.old_size:
            plan.append(("old.bag", robot, int(args.old_size * MB), 0, "none"))
        files: dict[str, tuple[Path, list[Stream], int]] = {}
        for name, streams, size, count, compression in plan:
            path = tmp / name
            done = tmp / f"{name}.count"
            if not (path.exists() and done.exists()):
                t = time.perf_counter()
                n = generate(path, streams, size=size, count=count, compression=compression)
                done.write_text(str(n))
                print(f"  wrote {name}: {path.stat().st_size / MB:.0f} MB, {n} messages, {compression}, "
                      f"{bag_span_s(path):.1f} s of bag time, in {time.perf_counter() - t:.0f} s", flush=True)
            files[name] = (path, streams, int(done.read_text()))
        port = free_port()
        env = ros_env(port, str(tmp / "ros_home"))
        env.pop("PYTHONPATH", None)
        roscore = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL, start_new_session=True)
        wait_port(port)
        if args.only in (None, "view"):
            print(f"(a) bag view: time to first screen and peak RSS; load average {load_average()}", flush=True)
            old_tree = old_worktree(args.old_commit, Path(args.old_tree)) if args.old_size else None
            view_files = {n: files[n][0] for n in files if n != "old.bag"}
            results["view"] = bench_view(view_files, files["old.bag"][0] if "old.bag" in files else None,
                                         old_tree, env, args.repeats)
        if args.only in (None, "play"):
            if build_tally() is None:
                print("  bench/bag_tally.cpp cannot be built here (g++ and roscpp headers): no playback", flush=True)
            else:
                rates = [float(r) for r in args.rates.split(",")]
                print(f"(b) play to one roscpp subscriber at -r {args.rates}; load average {load_average()}",
                      flush=True)
                wanted = {n: (*files[n], rates) for n in ("robot.bag", "robot.mcap") if n in files}
                if args.small_rates and "small.bag" in files:
                    wanted["small.bag"] = (*files["small.bag"], [float(r) for r in args.small_rates.split(",")])
                results["play"] = bench_play(wanted, env)
        results["load_after"] = load_average()
        print(f"load average after: {results['load_after']}", flush=True)
    finally:
        for burner in burners:
            burner.kill()
            burner.wait()
        if roscore is not None and roscore.poll() is None:
            os.killpg(roscore.pid, 2)
            try:
                roscore.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(roscore.pid, 9)
        if not args.keep:
            shutil.rmtree(tmp, ignore_errors=True)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
