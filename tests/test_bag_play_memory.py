"""bag play holds a bounded number of decompressed chunks, whatever the bag's size and however many files, and
loads no module it does not use."""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

from rostui.core.bag.files import merged_messages, open_writer
from rostui.core.bag.model import Connection
from rostui.tools.bag.player import PLAY_CACHE_BYTES, open_bags

from conftest import rostui_cmd, stop_process
from interop_helpers import wait_for_publisher

T0 = 1_700_000_000_000_000_000
BLOB = 200_000  # bytes a message: four to a chunk, 40 MB in all (over the bound, under the old 64 MB a file)


def write_blobs(path: Path, count: int, offset_ns: int) -> None:
    """``count`` messages of BLOB bytes on /blob, 10 ms apart from ``offset_ns``."""
    writer = open_writer(str(path))
    writer.add_connection(Connection(0, "/blob", "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1",
                                     "string data\n", "/test"))
    for i in range(count):
        writer.write(0, T0 + offset_ns + i * 10_000_000, (BLOB - 4).to_bytes(4, "little") + bytes(BLOB - 4))
    writer.close()


def test_playing_two_big_files_keeps_a_bounded_cache(tmp_path: Path) -> None:
    paths = [tmp_path / "a.bag", tmp_path / "b.bag"]
    for k, path in enumerate(paths):
        write_blobs(path, 100, k * 5_000_000)  # 20 MB each, their messages interleaved in time
    readers, _ = open_bags([str(p) for p in paths], warn=lambda _line: None)
    try:
        most = 0
        played = 0
        for _conn, _t, data, _file in merged_messages(readers):
            played += 1
            assert len(data) == BLOB
            most = max(most, sum(r.cache.held_bytes for r in readers))
        assert played == 200
        assert most <= PLAY_CACHE_BYTES + 2 * 1024 * 1024  # the last chunk of each file is always kept
    finally:
        for reader in readers:
            reader.close()


def test_a_player_loads_neither_uvloop_nor_openssl(ros_env: dict[str, str], rostui_core: Any, tmp_path: Path) -> None:
    """bag play runs on asyncio's loop: uvloop and the OpenSSL it loads (5 MB, 8 ms of every start) stay out
    of the process, as /proc/PID/maps shows while it plays; so do the writers' bz2 and ctypes (a reader
    decompresses bz2 chunks only when a bag has them)."""
    path = tmp_path / "blobs.bag"
    write_blobs(path, 3, 0)
    player = subprocess.Popen(rostui_cmd("bag", "play", "-q", "--pause", str(path)), env=ros_env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_publisher(ros_env, "/blob")
        maps = Path(f"/proc/{player.pid}/maps").read_text()
        assert "uvloop" not in maps and "libssl" not in maps and "_ssl" not in maps
        assert "_bz2" not in maps and "_ctypes" not in maps
    finally:
        stop_process(player)
