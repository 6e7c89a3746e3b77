"""lz4 chunks in .bag files, both ways with real rosbag.

rostui writes an lz4 chunk as roslz4 (rosbag's lz4 library) writes one -- independent 1 MiB blocks, no block
checksums, no content size, a content checksum -- because roslz4's reader takes nothing else: chunks of 5 MB
must read back in real ``rosbag info``, ``rosbag play`` and the rosbag Python API, byte for byte.  rostui reads
the lz4 bags rosbag writes (Python API, ``rosbag record --lz4``, ``rosbag compress --lz4``) and its own older
files (linked blocks).
"""

from __future__ import annotations

import pickle
import random
import struct
import subprocess
from pathlib import Path
from typing import Any, Callable

import lz4.block
import lz4.frame
import pytest

from rostui.core.bag import rosbag2_0
from rostui.core.bag.files import convert, open_reader
from rostui.core.bag.model import Connection
from rostui.core.bag.rosbag2_0 import FILE_HEADER_RECORD_SIZE, MAGIC, OP_CHUNK, BagWriter, parse_header
from rostui.core.msg import get_message_class

from conftest import SYSTEM_PYTHON, need_command, rostui_cmd, wait_until
from interop_helpers import Spawn, rospy_peer, spawn  # noqa: F401  (spawn is a fixture)
from live_helpers import DEADLINE, Watcher
from test_bag_rosbag_rewrites import _rosbag_python

U8 = get_message_class("std_msgs/UInt8MultiArray")
String = get_message_class("std_msgs/String")
T0 = 1_700_000_000_000_000_000
CHUNK = 5 * 1024 * 1024
MiB = 1024 * 1024
FIRST_CHUNK = len(MAGIC) + FILE_HEADER_RECORD_SIZE
TOPICS = {"/blob": (0, "std_msgs/UInt8MultiArray", U8), "/text": (1, "std_msgs/String", String)}
#: The header roslz4 writes: magic, FLG 0x64 (version 1, independent blocks, content checksum, no content size,
#: no block checksums), BD 0x60 (1 MiB blocks), header checksum.
ROSLZ4_HEADER = bytes.fromhex("04224d18646085")

Message = tuple[str, int, bytes]


def varied_messages(count: int, seed: int, topics: tuple[str, ...] = ("/blob", "/text")) -> list[Message]:
    """``(topic, time_ns, serialized)``: sizes from empty to 1.6 MB, a third of each body random (incompressible),
    the rest a short repeated pattern; every fifth message a std_msgs/String when /text is among ``topics``."""
    rng = random.Random(seed)
    sizes = [0, 17, 900, 65_536, 300_000, MiB, 1_600_000]
    out: list[Message] = []
    for i in range(count):
        size = sizes[i % len(sizes)] + rng.randrange(64)
        noise = rng.randbytes(size // 3)
        pattern = bytes(rng.randrange(4) for _ in range(61)) * (size // 61 + 1)
        body = (pattern[:size // 3] + noise + pattern)[:size]
        t = T0 + i * 10_000_000
        if "/text" in topics and i % 5 == 4:
            out.append(("/text", t, String(data=body.hex()[:size]).serialize()))
        else:
            out.append((topics[0], t, U8(data=body).serialize()))
    return out


def write_ours(path: Path, messages: list[Message], compression: str = "lz4", chunk_bytes: int = CHUNK) -> None:
    """A rostui .bag of ``messages`` with chunks of ``chunk_bytes``."""
    writer = BagWriter(str(path), compression=compression, chunk_bytes=chunk_bytes)
    for topic, (conn_id, type_name, cls) in TOPICS.items():
        writer.add_connection(Connection(conn_id, topic, type_name, cls._md5sum, cls._full_text, "/lz4_test", False))
    for topic, t, data in messages:
        writer.write(TOPICS[topic][0], t, data)
    writer.close()


def read_ours(path: Path) -> list[Message]:
    """Every message as rostui reads it."""
    reader = open_reader(str(path))
    try:
        return [(conn.topic, t, bytes(data)) for conn, t, data in reader.messages()]
    finally:
        reader.close()


def chunks(path: Path) -> list[tuple[str, int, bytes]]:
    """``(compression, uncompressed size, stored data)`` of every chunk record, walking the file."""
    raw = path.read_bytes()
    pos, found = len(MAGIC), []
    while pos + 4 <= len(raw):
        (hlen,) = struct.unpack_from("<I", raw, pos)
        fields = parse_header(raw[pos + 4:pos + 4 + hlen])
        (dlen,) = struct.unpack_from("<I", raw, pos + 4 + hlen)
        data = raw[pos + 8 + hlen:pos + 8 + hlen + dlen]
        pos += 8 + hlen + dlen
        if fields["op"] == bytes([OP_CHUNK]):
            found.append((fields["compression"].decode(), struct.unpack("<I", fields["size"])[0], data))
    return found


def frame_layout(frame: bytes) -> tuple[bytes, list[tuple[bool, int]], bytes]:
    """An lz4 frame's 7-byte header, its blocks as ``(stored raw, plain length)`` and its 4-byte content
    checksum.  Each compressed block is decompressed on its own: it must not lean on the block before."""
    assert frame[:4] == bytes.fromhex("04224d18")
    flags = frame[4]
    assert not flags & 0x08 and not flags & 0x10, f"content size or block checksums in the frame (FLG {flags:#x})"
    block_max = 1 << (8 + 2 * ((frame[5] >> 4) & 7))
    pos, blocks = 7, []
    while True:
        (word,) = struct.unpack_from("<I", frame, pos)
        pos += 4
        if word == 0:
            break
        size, stored_raw = word & 0x7FFFFFFF, bool(word >> 31)
        block = frame[pos:pos + size]
        pos += size
        plain = size if stored_raw else len(lz4.block.decompress(block, uncompressed_size=block_max))
        blocks.append((stored_raw, plain))
    assert pos + 4 == len(frame), "bytes after the content checksum"
    return frame[:7], blocks, frame[pos:]


def system_python(script: str, *args: str, timeout: float = 120) -> str:
    """Run ``script`` under Debian's Python (rosbag, roslz4); its stdout, or the failure with its stderr."""
    r = subprocess.run([SYSTEM_PYTHON, "-c", script, *args], capture_output=True, text=True, timeout=timeout)
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


ROSLZ4_BOTH_WAYS = """
import sys, pathlib, roslz4
folder = pathlib.Path(sys.argv[1])
for plain in sorted(folder.glob("*.plain")):
    ours = plain.with_suffix(".ours").read_bytes()
    assert roslz4.decompress(ours) == plain.read_bytes(), plain
    plain.with_suffix(".theirs").write_bytes(roslz4.compress(plain.read_bytes()))
print("ok")
"""

ROSBAG_API_READ = """
import sys, pickle, rosbag
with rosbag.Bag(sys.argv[1]) as bag:
    got = [(topic, t.to_nsec(), bytes(raw[1])) for topic, raw, t in bag.read_messages(raw=True)]
with open(sys.argv[2], "wb") as out:
    pickle.dump(got, out)
"""

ROSBAG_API_WRITE = """
import sys, pickle, rosbag, rospy
from std_msgs.msg import String, UInt8MultiArray
types = {"/blob": UInt8MultiArray, "/text": String}
with open(sys.argv[2], "rb") as f:
    messages = pickle.load(f)
with rosbag.Bag(sys.argv[1], "w", compression="lz4", chunk_threshold=int(sys.argv[3])) as bag:
    for topic, t, data in messages:
        bag.write(topic, types[topic]().deserialize(data), rospy.Time(t // 10**9, t % 10**9))
"""

ANYMSG_LISTENER = """
import sys, pickle, threading, rospy
expected = {topic: int(n) for topic, n in (arg.split("=") for arg in sys.argv[2:])}
got = {topic: [] for topic in expected}
lock = threading.Lock()
def keep(msg, topic):
    with lock:
        got[topic].append(bytes(msg._buff))
        if all(len(got[t]) == n for t, n in expected.items()):
            with open(sys.argv[1], "wb") as out:
                pickle.dump(got, out)
            rospy.signal_shutdown("all messages arrived")
rospy.init_node("lz4_listener")
subs = [rospy.Subscriber(topic, rospy.AnyMsg, keep, callback_args=topic) for topic in expected]
print("subscribed", flush=True)
rospy.spin()
"""


def rosbag_api_read(path: Path, tmp_path: Path) -> list[Message]:
    """Every message of ``path`` as the rosbag Python API reads it (raw bytes)."""
    out = tmp_path / f"{path.name}.read.pickle"
    system_python(ROSBAG_API_READ, str(path), str(out))
    with out.open("rb") as f:
        got: list[Message] = pickle.load(f)
    return got


def test_rostui_frames_lz4_chunks_as_roslz4_does(tmp_path: Path) -> None:
    """Each chunk's frame has roslz4's header, block boundaries and checksum, and roslz4 decompresses it."""
    _rosbag_python()
    small = tmp_path / "small.bag"
    write_ours(small, [("/text", T0, String(data="tiny").serialize())])
    big = tmp_path / "big.bag"
    write_ours(big, varied_messages(40, seed=1))
    frames = [chunk for path in (small, big) for chunk in chunks(path)]
    assert len(frames) >= 4 and {kind for kind, _, _ in frames} == {"lz4"}
    assert sum(1 for _, size, _ in frames if size >= CHUNK) >= 2
    for i, (_, size, ours) in enumerate(frames):
        plain = lz4.frame.decompress(ours)
        assert len(plain) == size
        (tmp_path / f"{i:02d}.plain").write_bytes(plain)
        (tmp_path / f"{i:02d}.ours").write_bytes(ours)
    assert system_python(ROSLZ4_BOTH_WAYS, str(tmp_path)) == "ok\n"
    for i, (_, size, ours) in enumerate(frames):
        header, blocks, checksum = frame_layout(ours)
        assert header == ROSLZ4_HEADER
        assert [plain for _, plain in blocks] == [min(MiB, size - at) for at in range(0, size, MiB)]
        assert (header, blocks, checksum) == frame_layout((tmp_path / f"{i:02d}.theirs").read_bytes())


def test_real_rosbag_info_and_python_api_read_5mb_lz4_chunks_byte_for_byte(tmp_path: Path,
                                                                          ros_env: dict[str, str]) -> None:
    need_command("rosbag")
    _rosbag_python()
    messages = varied_messages(40, seed=2)
    path = tmp_path / "ours.bag"
    write_ours(path, messages)
    sizes = [size for _, size, _ in chunks(path)]
    assert sum(1 for size in sizes if size >= CHUNK) >= 2, sizes
    info = subprocess.run(["rosbag", "info", str(path)], capture_output=True, text=True, env=ros_env, timeout=60)
    assert info.returncode == 0, info.stderr
    assert f"compression:  lz4 [{len(sizes)}/{len(sizes)} chunks;" in info.stdout, info.stdout
    assert "messages:     40\n" in info.stdout, info.stdout
    assert rosbag_api_read(path, tmp_path) == messages


def test_rosbag_play_of_a_rostui_lz4_bag_reaches_a_rospy_subscriber_byte_for_byte(
        tmp_path: Path, ros_env: dict[str, str], real_roscore: Any, spawn: Spawn) -> None:
    need_command("rosbag")
    messages = varied_messages(40, seed=3)
    path = tmp_path / "ours.bag"
    write_ours(path, messages)
    expected = {topic: [data for t_, _, data in messages if t_ == topic] for topic in TOPICS}
    received = tmp_path / "received.pickle"
    listener = spawn([SYSTEM_PYTHON, "-c", ANYMSG_LISTENER, str(received),
                      *(f"{topic}={len(datas)}" for topic, datas in expected.items())], label="rospy_listener")
    listener.wait_for("^subscribed$")
    play = spawn(["rosbag", "play", "--quiet", "--wait-for-subscribers", "--queue=1000", str(path)],
                 label="rosbag_play")
    assert play.wait_exit(timeout=120) == 0, play.describe()
    assert listener.wait_exit(timeout=60) == 0, listener.describe()
    with received.open("rb") as f:
        assert pickle.load(f) == expected


@pytest.mark.parametrize("chunk_threshold", [768 * 1024, CHUNK])
def test_rostui_reads_lz4_bags_the_rosbag_python_api_writes(tmp_path: Path, chunk_threshold: int) -> None:
    _rosbag_python()
    messages = varied_messages(30, seed=4)
    source = tmp_path / "messages.pickle"
    source.write_bytes(pickle.dumps(messages))
    path = tmp_path / "theirs.bag"
    system_python(ROSBAG_API_WRITE, str(path), str(source), str(chunk_threshold))
    theirs = chunks(path)
    assert {kind for kind, _, _ in theirs} == {"lz4"} and max(size for _, size, _ in theirs) > MiB
    assert all(frame_layout(data)[0] == ROSLZ4_HEADER for _, _, data in theirs)
    assert read_ours(path) == messages


def test_rostui_reads_a_bag_rosbag_compress_made_lz4(tmp_path: Path, ros_env: dict[str, str]) -> None:
    need_command("rosbag")
    messages = varied_messages(30, seed=5)
    plain = tmp_path / "plain.bag"
    write_ours(plain, messages, compression="none")
    (tmp_path / "out").mkdir()
    r = subprocess.run(["rosbag", "compress", "--lz4", "--output-dir", str(tmp_path / "out"), str(plain)],
                       capture_output=True, text=True, env=ros_env, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    compressed = tmp_path / "out" / "plain.bag"
    assert {kind for kind, _, _ in chunks(compressed)} == {"lz4"}
    assert read_ours(compressed) == messages


def _publisher(watcher: Watcher, topic: str) -> Any:
    """A publisher with an unbounded queue, so a burst of big messages is never cut short."""
    return watcher.engine.run(watcher.node.advertise(topic, U8), timeout=DEADLINE)


def _publish(watcher: Watcher, messages: list[Message]) -> None:
    pub = _publisher(watcher, "/blob")
    wait_until(lambda: pub.get_num_connections() > 0, "the recorder to connect to /blob")
    for _, _, data in messages:
        pub.publish(U8.deserialize(data))


def test_rostui_reads_what_rosbag_record_lz4_writes(tmp_path: Path, ros_env: dict[str, str], real_roscore: Any,
                                                    spawn: Spawn) -> None:
    need_command("rosbag")
    messages = varied_messages(20, seed=6, topics=("/blob",))
    path = tmp_path / "theirs.bag"
    record = spawn(["rosbag", "record", "--lz4", "--chunksize=5120", f"--limit={len(messages)}", "-O", str(path),
                    "/blob"], label="rosbag_record")
    watcher = Watcher()
    try:
        _publish(watcher, messages)
        assert record.wait_exit(timeout=120) == 0, record.describe()
    finally:
        watcher.close()
    theirs = chunks(path)
    assert {kind for kind, _, _ in theirs} == {"lz4"} and max(size for _, size, _ in theirs) > MiB
    assert all(frame_layout(data)[0] == ROSLZ4_HEADER for _, _, data in theirs)
    assert [(topic, data) for topic, _, data in read_ours(path)] == [(topic, data) for topic, _, data in messages]


OLD_FRAMES: dict[str, Callable[[bytes], bytes]] = {
    # rostui's first .bag writer: python-lz4's defaults (64 KiB linked blocks, content size, no checksum)
    "defaults": lambda data: bytes(lz4.frame.compress(data)),
    # rostui until issue 18: 1 MiB linked blocks, content checksum, no content size
    "linked-1mib": lambda data: bytes(lz4.frame.compress(data, block_size=lz4.frame.BLOCKSIZE_MAX1MB,
                                                         content_checksum=True, store_size=False)),
}


@pytest.mark.parametrize("form", sorted(OLD_FRAMES))
def test_rostui_reads_its_older_lz4_chunks_and_converts_them_for_rosbag(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, form: str) -> None:
    monkeypatch.setattr(rosbag2_0, "_roslz4_frame", OLD_FRAMES[form])
    messages = varied_messages(30, seed=7)
    path = tmp_path / "older.bag"
    write_ours(path, messages)
    monkeypatch.undo()
    frames = chunks(path)
    assert any(size > MiB and not data[4] & 0x20 for _, size, data in frames), "no chunk with linked blocks"
    assert read_ours(path) == messages
    # what docs/bag.md tells a user whose old bag rosbag cannot read
    _rosbag_python()
    assert convert(str(path), str(tmp_path / "rewritten.bag"), "lz4") == len(messages)
    assert rosbag_api_read(tmp_path / "rewritten.bag", tmp_path) == messages


def test_rostui_bag_record_lz4_writes_chunks_rosbag_reads(tmp_path: Path, ros_env: dict[str, str],
                                                          real_roscore: Any, spawn: Spawn) -> None:
    _rosbag_python()
    messages = varied_messages(20, seed=8, topics=("/blob",))
    path = tmp_path / "recorded.bag"
    record = spawn(rostui_cmd("bag", "record", "-O", str(path), "--lz4", "/blob"), label="rostui_record")
    watcher = Watcher()
    try:
        _publish(watcher, messages)

        def all_recorded() -> bool:
            assert record.proc.poll() is None, record.describe()
            return path.exists() and path.stat().st_size > FIRST_CHUNK and len(read_ours(path)) == len(messages)
        wait_until(all_recorded, f"rostui bag record to write {len(messages)} messages", timeout=60)
    finally:
        watcher.close()
    record.proc.send_signal(2)
    assert record.wait_exit() == 0, record.describe()
    recorded = chunks(path)
    assert {kind for kind, _, _ in recorded} == {"lz4"} and max(size for _, size, _ in recorded) > MiB
    assert all(frame_layout(data)[0] == ROSLZ4_HEADER for _, _, data in recorded)
    sent = [(topic, data) for topic, _, data in messages]
    assert [(topic, data) for topic, _, data in rosbag_api_read(path, tmp_path)] == sent
    assert [(topic, data) for topic, _, data in read_ours(path)] == sent
