"""The recorder's hot path without a ROS graph: raw frame reassembly, pooled buffers, gathered writes,
rosbag's --duration forms, and `info`'s compression lines next to real `rosbag info`."""

from __future__ import annotations

import asyncio
import os
import random
import shutil
import subprocess
import zlib
from pathlib import Path
from typing import Any

import pytest

from rostui.core.bag.files import open_reader, open_writer
from rostui.core.bag.iov import Parts, write_all
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.receive import BIG_FRAME, BufferPool, RawFrameConnection
from rostui.tools.bag.recorder import parse_duration
from rostui.core.tcpros import encode_header

from cli_helpers import rostui
from conftest import need_peer

STRING_MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"


class FakeTransport:
    """What RawFrameConnection uses of an asyncio transport."""

    def __init__(self) -> None:
        self.sent = b""
        self.closed = False

    def write(self, data: bytes) -> None:
        self.sent += data

    def close(self) -> None:
        self.closed = True

    def is_closing(self) -> bool:
        return self.closed

    def get_extra_info(self, name: str, default: Any = None) -> Any:
        return default


def framed(payload: bytes) -> bytes:
    return len(payload).to_bytes(4, "little") + payload


def feed(stream: bytes, cut: Any, allocate: Any = bytearray, release: Any = None) -> tuple[list[bytes], Any]:
    """Push ``stream`` through a RawFrameConnection in reads whose sizes ``cut(room)`` chooses."""
    got: list[bytes] = []

    def on_frame(payload: Any, header: dict[str, str]) -> None:
        assert header["md5sum"] == STRING_MD5
        got.append(bytes(payload))
        if release is not None:
            release(payload)

    async def run() -> RawFrameConnection:
        proto = RawFrameConnection({"topic": "/t"}, lambda h: None, on_frame, lambda reason: None, allocate)
        proto.connection_made(FakeTransport())  # type: ignore[arg-type]
        pos = 0
        while pos < len(stream) and not proto.transport.is_closing():  # type: ignore[union-attr]
            buf = proto.get_buffer(-1)
            assert len(buf) > 0
            n = min(len(buf), cut(len(buf)), len(stream) - pos)
            buf[:n] = stream[pos:pos + n]
            pos += n
            proto.buffer_updated(n)
        proto.connection_lost(None)
        return proto

    return got, asyncio.run(run())


def publisher_stream(payloads: list[bytes]) -> bytes:
    header = encode_header({"type": "std_msgs/String", "md5sum": STRING_MD5, "callerid": "/pub", "latching": "0"})
    return header + b"".join(framed(p) for p in payloads)


SIZES = [0, 1, 10, 500, BIG_FRAME - 1, BIG_FRAME, BIG_FRAME + 3, 300_000, 1_000_000, 7, 2_500_000, 64]


@pytest.mark.parametrize("reads", ["whole", "bytewise_prefix", "random", "tiny"])
def test_raw_frames_come_out_whole_however_the_reads_split_them(reads: str) -> None:
    rng = random.Random(reads)
    payloads = [bytes(rng.getrandbits(8) for _ in range(min(n, 50))) * (n // 50 + 1) for n in SIZES]
    payloads = [p[:n] for p, n in zip(payloads, SIZES)]
    cuts = {"whole": lambda room: room, "bytewise_prefix": lambda room: rng.choice([1, 2, 3, room]),
            "random": lambda room: rng.randint(1, room), "tiny": lambda room: rng.randint(1, 9000)}
    got, proto = feed(publisher_stream(payloads), cuts[reads])
    assert got == payloads
    assert proto.error is None and proto.header["callerid"] == "/pub"
    assert proto.transport.sent.startswith(encode_header({"topic": "/t"})[:4])


def test_big_frames_are_read_into_their_own_buffers_from_the_pool_and_reused() -> None:
    pool = BufferPool()
    taken: list[int] = []

    def allocate(size: int) -> memoryview:
        view = pool.take(size)
        taken.append(id(view.obj))
        return view

    payloads = [bytes([i]) * 200_000 for i in range(6)] + [b"small"] + [bytes([9]) * 150_000]
    got, _ = feed(publisher_stream(payloads), lambda room: room, allocate, pool.give)
    assert got == payloads
    # a big frame that arrives whole within one read of the stage is sliced out of it; the others
    # (all after the first few: only length prefixes are read ahead after a big frame) get pooled buffers
    assert len(taken) >= 5
    assert len(set(taken)) < len(taken)  # returned buffers were handed out again


def test_a_frame_over_the_cap_drops_the_connection(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROSTUI_TCPROS_MAX_FRAME", "1000")
    got, proto = feed(publisher_stream([b"ok", b"x" * 5000, b"never"]), lambda room: room)
    assert got == [b"ok"]
    assert "exceeds the cap" in (proto.error or "") and proto.transport.closed


def test_a_refused_publisher_header_drops_the_connection() -> None:
    async def run() -> RawFrameConnection:
        proto = RawFrameConnection({}, lambda h: "md5sum mismatch", lambda p, h: None, lambda r: None)
        proto.connection_made(FakeTransport())  # type: ignore[arg-type]
        data = publisher_stream([b"x"])
        buf = proto.get_buffer(-1)
        buf[:len(data)] = data
        proto.buffer_updated(len(data))
        return proto

    proto = asyncio.run(run())
    assert proto.error == "md5sum mismatch" and proto.transport.closed


def test_gathered_writes_keep_order_and_bytes_across_many_pieces(tmp_path: Path) -> None:
    rng = random.Random(7)
    pieces = [os.urandom(rng.choice([1, 30, 5000, 20_000, 70_000])) for _ in range(3000)]
    parts = Parts()
    for piece in pieces:
        parts.add(bytearray(piece) if rng.random() < 0.5 else memoryview(piece))
    fd = os.open(tmp_path / "out", os.O_WRONLY | os.O_CREAT)
    try:
        assert write_all(fd, parts.buffers()) == parts.size == sum(map(len, pieces))
    finally:
        os.close(fd)
    assert (tmp_path / "out").read_bytes() == b"".join(pieces)


@pytest.mark.parametrize("name,crcs", [("a.mcap", True), ("b.mcap", False), ("c.bag", True)])
def test_writers_take_pooled_buffers_and_big_messages(tmp_path: Path, name: str, crcs: bool) -> None:
    pool = BufferPool()
    writer = open_writer(str(tmp_path / name), chunk_crcs=crcs)
    writer.add_connection(Connection(0, "/big", "std_msgs/String", STRING_MD5, "string data\n", "/p"))
    expected = []
    for i in range(40):
        size = 1_000_000 if i % 4 == 0 else 100 + i
        view = pool.take(size)
        view[:] = (bytes([i]) * size)
        writer.write(0, 1_000 + i, view)
        expected.append(bytes(view))
        if not writer.buffered:
            pool.give(view)
    writer.close()
    reader = open_reader(str(tmp_path / name))
    assert [bytes(d) for _c, _t, d in reader.messages()] == expected
    assert reader.summary().message_count == 40
    reader.close()
    if name.endswith(".mcap"):
        from mcap.reader import make_reader

        with open(tmp_path / name, "rb") as f:
            mcap = make_reader(f, validate_crcs=True)
            assert [m.data for _s, _c, m in mcap.iter_messages()] == expected
            chunk_crcs = {index.chunk_start_offset for index in mcap.get_summary().chunk_indexes}
        with open(tmp_path / name, "rb") as f:
            from mcap.records import Chunk
            from mcap.stream_reader import StreamReader

            crc_values = [r.uncompressed_crc for r in StreamReader(f, emit_chunks=True).records
                          if isinstance(r, Chunk)]
        assert len(crc_values) == len(chunk_crcs)
        assert all(crc != 0 for crc in crc_values) if crcs else all(crc == 0 for crc in crc_values)


def test_mcap_chunk_crcs_are_the_crc_of_the_chunk_records(tmp_path: Path) -> None:
    writer = open_writer(str(tmp_path / "crc.mcap"))
    writer.add_connection(Connection(0, "/t", "std_msgs/String", STRING_MD5, "string data\n", "/p"))
    for i in range(10):
        writer.write(0, i, b"abc" * (i + 1))
    writer.close()
    from mcap.records import Chunk
    from mcap.stream_reader import StreamReader

    with open(tmp_path / "crc.mcap", "rb") as f:
        chunks = [r for r in StreamReader(f, emit_chunks=True).records if isinstance(r, Chunk)]
    assert chunks and all(c.uncompressed_crc == zlib.crc32(c.data) for c in chunks)


@pytest.mark.parametrize("text,seconds", [("30", 30.0), ("30s", 30.0), ("0.5", 0.5), ("5m", 300.0), ("1.5m", 90.0),
                                          ("2h", 7200.0), (" 10s ", 10.0)])
def test_duration_takes_rosbag_forms(text: str, seconds: float) -> None:
    assert parse_duration(text) == seconds


@pytest.mark.parametrize("text", ["", "s", "5x", "10 min", "-3", "0", "1e999", "nan", "m5", "5mm"])
def test_other_durations_are_refused(text: str) -> None:
    with pytest.raises(BagError, match="invalid duration"):
        parse_duration(text)


@pytest.mark.parametrize("args,message", [
    (["--duration", "5x"], "invalid duration '5x' (a positive number of seconds, optionally with s, m or h"),
    (["--split"], "--split needs --size MB or --duration DURATION"),
    (["--size", "0"], "--size must be a positive number of MB, not 0"),
    (["--max-size", "-1"], "--max-size must be a positive number of MB, not -1"),
])
def test_record_refuses_bad_limits_in_one_line(tmp_path: Path, ros_env: dict[str, str], args: list[str],
                                               message: str) -> None:
    result = rostui(["bag", "record", "-O", str(tmp_path / "x.bag"), *args, "/x"], ros_env)
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1 and message in result.stderr, result.stderr
    assert not (tmp_path / "x.bag").exists()


ROSBAG_WRITE = """
import sys, rosbag, rospy
from std_msgs.msg import Int32, String
with rosbag.Bag(sys.argv[1], "w", compression=sys.argv[2]) as bag:
    for i in range(3000):
        bag.write("/count", Int32(data=i), rospy.Time(1000, i * 100000))
        if i % 10 == 0:
            bag.write("/text", String(data="hello %d" % i * 20), rospy.Time(1000, i * 100000))
"""


def _rosbag_tools() -> bool:
    probe = subprocess.run(["/usr/bin/python3", "-c", "import rosbag, roslz4"], capture_output=True)
    return probe.returncode == 0 and shutil.which("rosbag") is not None


@pytest.mark.parametrize("compression", ["lz4", "bz2", "none"])
def test_info_prints_what_rosbag_info_prints_with_compression_ratios(tmp_path: Path, ros_env: dict[str, str],
                                                                      compression: str) -> None:
    need_peer(_rosbag_tools(), "rosbag with its Python API (Debian rosbag, python3-rosbag)")
    path = tmp_path / f"theirs_{compression}.bag"
    written = subprocess.run(["/usr/bin/python3", "-c", ROSBAG_WRITE, str(path), compression],
                             capture_output=True, text=True, timeout=120)
    assert written.returncode == 0, written.stderr
    theirs = subprocess.run(["rosbag", "info", str(path)], capture_output=True, text=True, env=ros_env, timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    ours = rostui(["bag", "info", str(path)], ros_env)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout.rstrip("\n") == theirs.stdout.rstrip("\n")
    if compression != "none":
        assert f"compression:  {compression} [1/1 chunks; " in ours.stdout
        assert "uncompressed: " in ours.stdout and "compressed:   " in ours.stdout


def test_info_of_a_compressed_rostui_mcap_shows_the_ratio_and_sizes(tmp_path: Path, ros_env: dict[str, str]) -> None:
    writer = open_writer(str(tmp_path / "z.mcap"), "zstd")
    writer.add_connection(Connection(0, "/t", "std_msgs/String", STRING_MD5, "string data\n", "/p"))
    for i in range(2000):
        writer.write(0, 1_000_000_000 + i * 1_000_000, b"\x10\x00\x00\x00" + b"repeat me please" * 1)
    writer.close()
    result = rostui(["bag", "info", str(tmp_path / "z.mcap")], ros_env)
    assert result.returncode == 0, result.stderr
    rows = dict(line.split(":", 1) for line in result.stdout.splitlines() if line and not line.startswith(" "))
    compression, uncompressed, compressed = rows["compression"], rows["uncompressed"], rows["compressed"]
    assert compression.strip().startswith("zstd [1/1 chunks; ") and compression.strip().endswith("%]")
    percent = float(compression.split(";")[1].strip(" %]"))
    assert 0 < percent < 20  # 2000 equal messages compress well
    assert "KB @ " in uncompressed and f"({percent:.2f}%)" in compressed


@pytest.mark.parametrize("loop_kind", ["uvloop", "asyncio"])
def test_a_real_socket_delivers_every_frame_even_when_the_publisher_goes_quiet(loop_kind: str) -> None:
    """Big frames sent in trickles, each followed by silence: the low-water mark never waits for bytes
    that are not coming (every frame arrives before the next is sent)."""
    import socket
    import threading

    from rostui.core.node.engine import new_event_loop

    rng = random.Random(3)
    payloads = [bytes([i % 256]) * size for i, size in
                enumerate([70_000, 1_000_000, 5, 600_000, 2_000_000, BIG_FRAME, 300])]
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    got: list[bytes] = []
    arrived = threading.Semaphore(0)

    def publisher() -> None:
        conn, _ = server.accept()
        with conn:
            conn.recv(65536)  # the subscriber's header
            stream = publisher_stream([])
            conn.sendall(stream)
            for payload in payloads:
                data = framed(payload)
                pos = 0
                while pos < len(data):
                    step = rng.choice([1, 3, 4000, 100_000, 700_000])
                    conn.sendall(data[pos:pos + step])
                    pos += step
                assert arrived.acquire(timeout=30), "a frame did not arrive while the publisher was quiet"

    thread = threading.Thread(target=publisher, daemon=True)
    thread.start()

    async def run() -> None:
        done = asyncio.get_running_loop().create_future()

        def on_frame(payload: Any, header: dict[str, str]) -> None:
            got.append(bytes(payload))
            arrived.release()
            if len(got) == len(payloads):
                done.set_result(None)

        loop = asyncio.get_running_loop()
        transport, _proto = await loop.create_connection(
            lambda: RawFrameConnection({"topic": "/t"}, lambda h: None, on_frame, lambda r: None, BufferPool().take),
            "127.0.0.1", server.getsockname()[1])
        try:
            await asyncio.wait_for(done, 60)
        finally:
            transport.close()

    loop = new_event_loop() if loop_kind == "uvloop" else asyncio.new_event_loop()
    try:
        loop.run_until_complete(run())
    finally:
        loop.close()
        server.close()
    thread.join(10)
    assert got == payloads


@pytest.mark.parametrize("direct", [False, True])
@pytest.mark.parametrize("name", ["r.bag", "r.mcap"])
def test_blocks_reserved_ahead_are_given_back_at_close(tmp_path: Path, name: str, direct: bool) -> None:
    path = tmp_path / name
    writer = open_writer(str(path), direct=direct)
    writer.add_connection(Connection(0, "/big", "std_msgs/String", STRING_MD5, "string data\n", "/p"))
    for i in range(5):
        writer.write(0, 1_000 + i, bytes(1_000_000))
    writer.flush()
    reserving = writer.out.reservation.enabled  # type: ignore[attr-defined]
    if reserving:
        assert os.stat(path).st_blocks * 512 >= 32 * 1024 * 1024 > os.stat(path).st_size
    writer.close()
    final = os.stat(path)
    assert final.st_blocks * 512 < final.st_size + 1024 * 1024
    reader = open_reader(str(path))
    assert reader.summary().message_count == 5
    reader.close()
