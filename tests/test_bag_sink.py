"""The bag writers' file sink: appends land byte for byte, through the page cache or with O_DIRECT."""

from __future__ import annotations

import errno
import os
import random
from pathlib import Path

import pytest

from rostui.core.bag import sink
from rostui.core.bag.files import open_reader, open_writer
from rostui.core.bag.model import Connection
from rostui.core.bag.sink import AppendFile, DirectAppendFile, open_append

SIZES = [1, 13, 4095, 4096, 4097, 70_000, 1_000_000, 5_000_000]


def random_pieces(seed: int, count: int) -> list[bytes]:
    """Pieces of awkward sizes (around the block and staging sizes), each of its own byte; every other one
    a bytearray (big writable pieces are copied without the GIL, read-only ones by slice assignment)."""
    rnd = random.Random(seed)
    pieces = [bytes([i % 251]) * rnd.choice(SIZES) for i in range(count)]
    return [bytearray(piece) if i % 2 else piece for i, piece in enumerate(pieces)]


@pytest.mark.parametrize("direct", [True, False])
def test_appends_syncs_and_rewrite_land_exactly(tmp_path: Path, direct: bool) -> None:
    """Whatever the sizes, the file is the appended bytes in order, with the rewritten header in place."""
    path = tmp_path / "out.bin"
    out = open_append(str(path), direct=direct)
    expect = bytearray()
    for i, piece in enumerate(random_pieces(1, 120)):
        out.append([memoryview(piece)[1:] if i % 4 == 1 else piece, b"record %d" % i])
        expect += (piece[1:] if i % 4 == 1 else piece) + b"record %d" % i
        assert out.end == len(expect)
        if i % 7 == 0 and isinstance(out, DirectAppendFile):
            out.sync()
            assert path.read_bytes() == expect, "after a sync the file holds every byte appended"
    out.rewrite(b"HEAD", 5)
    expect[5:9] = b"HEAD"
    out.append([b"after the rewrite"])
    expect += b"after the rewrite"
    out.close()
    assert path.read_bytes() == expect


def test_direct_io_is_used_where_the_file_system_takes_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The recorder's files bypass the page cache unless ROSTUI_BAG_DIRECT_IO=0 or the file system refuses."""
    probe = tmp_path / "probe"
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | getattr(os, "O_DIRECT", 0))
    except OSError as exc:
        assert exc.errno == errno.EINVAL
        supported = False
    else:
        supported = sink._direct_write_works(fd)
        os.close(fd)
    out = open_append(str(tmp_path / "a.bin"), direct=True)
    assert isinstance(out, DirectAppendFile) == supported
    out.close()
    monkeypatch.setenv("ROSTUI_BAG_DIRECT_IO", "0")
    out = open_append(str(tmp_path / "b.bin"), direct=True)
    assert type(out) is AppendFile
    out.close()


def _staging_file(path: Path) -> DirectAppendFile:
    # the staging logic is the same without the O_DIRECT flag, so these run on any file system
    return DirectAppendFile(str(path), os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644))


def _refuse(*_args: object) -> None:
    raise OSError(errno.EIO, "the device refuses")


def test_a_failed_direct_write_goes_on_through_the_page_cache(tmp_path: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """A direct write failing costs no byte: what was staged is written through the page cache, and so is
    everything after."""
    path = tmp_path / "out.bin"
    out = _staging_file(path)
    first = b"a" * 5_000_000 + b"b" * 1234  # one full staging buffer sent, the rest staged
    out.append([first])
    monkeypatch.setattr(sink, "_write_direct", _refuse)
    out.append([b"c" * 5_000_000])
    out.sync()
    assert not out.direct
    out.append([b"tail"])
    out.close()
    assert path.read_bytes() == first + b"c" * 5_000_000 + b"tail"


def test_a_full_disk_keeps_every_append_that_fitted(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """When the page cache write fails too, the error is raised and the file ends where the disk did."""
    path = tmp_path / "out.bin"
    out = _staging_file(path)
    first = b"a" * 5_000_000 + b"b" * 1234
    out.append([first])
    limit = len(first) + 100
    real_pwrite = os.pwrite

    def disk_of(fd: int, data: bytes, offset: int) -> int:
        if offset >= limit:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_pwrite(fd, memoryview(data)[:limit - offset], offset)

    monkeypatch.setattr(sink, "_write_direct", _refuse)
    monkeypatch.setattr(os, "pwrite", disk_of)
    with pytest.raises(OSError) as raised:
        out.append([b"c" * 5_000_000])
        out.sync()
    assert raised.value.errno == errno.ENOSPC
    assert out.end == limit
    out.cut(len(first))
    monkeypatch.undo()
    out.append([b"tail"])
    out.close()
    assert path.read_bytes() == first + b"tail"


@pytest.mark.parametrize("name", ["direct.bag", "direct.mcap"])
def test_writers_on_the_direct_sink_read_back(tmp_path: Path, name: str) -> None:
    """A bag written the recorder's way (direct) reads back with every message, big and small."""
    path = tmp_path / name
    writer = open_writer(str(path), direct=True)
    writer.add_connection(Connection(0, "/big", "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1",
                                     "string data\n", "/test"))
    payloads = [len(p).to_bytes(4, "little") + p for p in random_pieces(2, 40)]
    for i, data in enumerate(payloads):
        writer.write(0, 1_000_000_000 + i * 1000, data)
        writer.flush_if_old()
    writer.close()
    reader = open_reader(str(path))
    try:
        assert [bytes(data) for _conn, _t, data in reader.messages()] == payloads
        assert not reader.truncated
    finally:
        reader.close()
