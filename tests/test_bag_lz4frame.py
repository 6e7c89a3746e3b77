"""rostui's own lz4 frame reader and writer (core/bag/lz4frame.py), checked against python-lz4 and roslz4.

Every frame form python-lz4 writes (block sizes, linked or independent blocks, block and content checksums,
with and without the content size) reads back byte for byte without python-lz4's frame decoder, as do the
frames of roslz4, rosbag's lz4 library, which the system Python runs (Debian python3-roslz4). The frames rostui
writes for .bag chunks are the bytes python-lz4's frame compressor writes in roslz4's form, and roslz4 reads
them. Broken frames (a flipped byte under any checksum, a frame cut short, a chunk that declares fewer bytes
than its frame holds) are malformed records; forms it does not read go to python-lz4 and still read.
"""

from __future__ import annotations

import random
import struct
import subprocess

import lz4.block
import lz4.frame
import pytest
import xxhash

from rostui.core.bag.inflate import inflate
from rostui.core.bag.lz4frame import FrameError, compress_frame, decompress_frame, decompress_frame_into
from rostui.core.bag.model import MalformedRecord

from conftest import SYSTEM_PYTHON, need_peer

_rng = random.Random(35)
NOISE = _rng.randbytes(3 << 20)
SAMPLES = {
    "empty": b"",
    "one byte": b"x",
    "flat 300 KB": bytes(300_000),
    "noise 200 KB (stored blocks)": NOISE[:200_000],
    "half noise 5 MB": b"".join(NOISE[i * 10_000:i * 10_000 + 10_000] + bytes(10_000) for i in range(250)),
}


def _read(frame: bytes, limit: int | None = None) -> bytes:
    """What decompress_frame reads from ``frame`` (it must read it: not hand it to python-lz4)."""
    read = decompress_frame(frame, limit if limit is not None else 1 << 30)
    assert read is not None, "the frame went to python-lz4"
    parts, ended = read
    assert ended
    return b"".join(parts)


@pytest.mark.parametrize("name", list(SAMPLES))
@pytest.mark.parametrize("block_size", [lz4.frame.BLOCKSIZE_MAX64KB, lz4.frame.BLOCKSIZE_MAX256KB,
                                        lz4.frame.BLOCKSIZE_MAX1MB, lz4.frame.BLOCKSIZE_MAX4MB])
@pytest.mark.parametrize("linked", [True, False], ids=["linked", "independent"])
@pytest.mark.parametrize("checksums", [(False, False), (True, False), (False, True), (True, True)],
                         ids=["no checksum", "content checksum", "block checksums", "both checksums"])
def test_every_frame_python_lz4_writes_reads_back(name: str, block_size: int, linked: bool,
                                                  checksums: tuple[bool, bool]) -> None:
    data = SAMPLES[name]
    for store_size in (True, False):
        frame = lz4.frame.compress(data, block_size=block_size, block_linked=linked, content_checksum=checksums[0],
                                   block_checksum=checksums[1], store_size=store_size)
        assert _read(frame) == data
        assert inflate("lz4", frame, len(data), path="x.bag", offset=0) == data


def test_roslz4_frames_read_back_without_python_lz4s_frame_decoder() -> None:
    """Frames of roslz4 (what ``rosbag record --lz4`` writes), of each sample."""
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import roslz4"], capture_output=True)
    need_peer(probe.returncode == 0, "roslz4 (Debian python3-roslz4)")
    for name, data in SAMPLES.items():
        frame = subprocess.run([SYSTEM_PYTHON, "-c", "import sys, roslz4; "
                                "sys.stdout.buffer.write(roslz4.compress(sys.stdin.buffer.read()))"],
                               input=data, capture_output=True, check=True).stdout
        assert frame[:7] == bytes.fromhex("04224d18646085"), name  # independent 1 MiB blocks, content checksum
        assert _read(frame) == data, name


WRITTEN = {**SAMPLES, "noise 2.5 MB (three blocks, stored)": NOISE[:2_500_000],
           "exactly one block": (NOISE[:300_000] + bytes(200_000)) * 2 + bytes(48_576)}


def test_the_frames_rostui_writes_are_python_lz4s_in_roslz4s_form_and_roslz4_reads_them() -> None:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import roslz4"], capture_output=True)
    need_peer(probe.returncode == 0, "roslz4 (Debian python3-roslz4)")
    for name, data in WRITTEN.items():
        frame = compress_frame(data)
        reference = lz4.frame.LZ4FrameCompressor(block_size=lz4.frame.BLOCKSIZE_MAX1MB, block_linked=False,
                                                 content_checksum=True, auto_flush=True)
        assert frame == reference.begin() + reference.compress(data) + reference.flush(), name
        assert _read(frame) == data, name
        back = subprocess.run([SYSTEM_PYTHON, "-c", "import sys, roslz4; "
                               "sys.stdout.buffer.write(roslz4.decompress(sys.stdin.buffer.read()))"],
                              input=frame, capture_output=True, check=True).stdout
        assert back == data, name


def _malformed(frame: bytes, declared: int) -> str:
    """The error of ``frame`` as a chunk declaring ``declared`` bytes: the same whether or not it is first tried
    straight into a buffer (as a player reads), since a frame that does not read into one is read again."""
    with pytest.raises(MalformedRecord) as caught:
        inflate("lz4", frame, declared, path="x.bag", offset=4117)
    with pytest.raises(MalformedRecord) as into_buffer:
        inflate("lz4", frame, declared, path="x.bag", offset=4117, buffer=bytearray)
    assert str(into_buffer.value) == str(caught.value)
    assert "x.bag" in str(caught.value) and "4117" in str(caught.value)
    return str(caught.value)


@pytest.mark.parametrize("name", list(SAMPLES))
@pytest.mark.parametrize("block_size", [lz4.frame.BLOCKSIZE_MAX64KB, lz4.frame.BLOCKSIZE_MAX4MB])
@pytest.mark.parametrize("checksums", [(False, False), (True, True)], ids=["no checksum", "both checksums"])
def test_independent_blocks_decompress_straight_into_a_buffer_of_the_chunks_size(
        name: str, block_size: int, checksums: tuple[bool, bool]) -> None:
    """What a player reads: every block in its place in one buffer, which must come out exactly full; a buffer a
    byte short or long, or linked blocks, are not read that way (the chunk is then read the general way)."""
    data = SAMPLES[name]
    for frame in (lz4.frame.compress(data, block_size=block_size, block_linked=False,
                                     content_checksum=checksums[0], block_checksum=checksums[1]),
                  compress_frame(data)):
        out = bytearray(b"\xee" * len(data))
        assert decompress_frame_into(frame, out) and out == data
        assert inflate("lz4", frame, len(data), path="x.bag", offset=0, buffer=bytearray) == data
        assert not decompress_frame_into(frame, bytearray(len(data) + 1))
        if data:
            assert not decompress_frame_into(frame, bytearray(len(data) - 1))
    linked = lz4.frame.compress(data, block_size=block_size, block_linked=True)
    if not linked[4] & 0x20:  # (python-lz4 marks a frame of one block independent)
        assert not decompress_frame_into(linked, bytearray(len(data)))
    assert inflate("lz4", linked, len(data), path="x.bag", offset=0, buffer=bytearray) == data


def test_a_flipped_byte_under_a_checksum_is_a_malformed_chunk() -> None:
    data = SAMPLES["half noise 5 MB"]
    content = bytearray(lz4.frame.compress(data, block_linked=False, content_checksum=True))
    content[-4] ^= 1  # the content checksum itself
    assert "content checksum does not match" in _malformed(bytes(content), len(data))
    stored = bytearray(lz4.frame.compress(NOISE[:100_000], block_linked=False, content_checksum=True))
    stored[5000] ^= 0x40  # a byte of a stored block: every block decodes, the checksum tells
    assert "content checksum does not match" in _malformed(bytes(stored), 100_000)
    blocks = bytearray(lz4.frame.compress(NOISE[:100_000], block_checksum=True))
    blocks[5000] ^= 0x40
    assert "a block's checksum does not match" in _malformed(bytes(blocks), 100_000)
    header = bytearray(lz4.frame.compress(b"abc"))
    header[5] ^= 0x10  # a block size id the header checksum does not cover
    assert "header checksum does not match" in _malformed(bytes(header), 3)


def test_cut_short_and_wrong_sizes_are_malformed_chunks() -> None:
    data = SAMPLES["half noise 5 MB"]
    frame = lz4.frame.compress(data, block_linked=False, content_checksum=True)
    for cut in (10, len(frame) // 2, len(frame) - 5, len(frame) - 1):
        read = decompress_frame(frame[:cut], len(data) + 1)
        assert read is not None and not read[1]
        assert f"of the {len(data)} bytes it declares" in _malformed(frame[:cut], len(data))
    assert "decompresses past the 1000 bytes" in _malformed(frame, 1000)
    assert f"to {len(data)} of the {len(data) + 1} bytes" in _malformed(frame, len(data) + 1)
    sized = bytearray(lz4.frame.compress(b"abcdef", store_size=True))
    sized[6] += 1  # the content size field: 7 bytes declared, 6 held
    sized[14] = (xxhash.xxh32_intdigest(bytes(sized[4:14])) >> 8) & 0xFF
    with pytest.raises(FrameError, match="holds 6 bytes and declares 7"):
        decompress_frame(bytes(sized), 100)


def test_a_frame_of_many_tiny_blocks_reads_block_by_block() -> None:
    """10 000 blocks of one byte each, compressed and stored: each gets a buffer of its own size, not 4 MiB."""
    body = bytearray()
    for i in range(10_000):
        block = lz4.block.compress(bytes([i % 251]), store_size=False) if i % 2 else bytes([i % 251])
        body += struct.pack("<I", len(block) | (0 if i % 2 else 0x80000000)) + block
    descriptor = bytes([0x60, 0x70])  # version 1, independent blocks, 4 MiB blocks
    frame = (b"\x04\x22\x4d\x18" + descriptor + bytes([(xxhash.xxh32_intdigest(descriptor) >> 8) & 0xFF])
             + bytes(body) + b"\0\0\0\0")
    assert _read(frame) == bytes(i % 251 for i in range(10_000))


def test_forms_it_does_not_read_go_to_python_lz4() -> None:
    """A linked block after a short one (its window spans two blocks), a dictionary id, another magic."""
    first, second = b"0123456789", b"0123456789" * 500
    linked_body = (struct.pack("<I", len(first) | 0x80000000) + first)
    packed = lz4.block.compress(second, store_size=False, dict=first)
    linked_body += struct.pack("<I", len(packed)) + packed
    descriptor = bytes([0x40, 0x40])  # version 1, linked blocks, 64 KiB blocks
    frame = (b"\x04\x22\x4d\x18" + descriptor + bytes([(xxhash.xxh32_intdigest(descriptor) >> 8) & 0xFF])
             + linked_body + b"\0\0\0\0")
    assert decompress_frame(frame, 1 << 20) is None
    assert inflate("lz4", frame, len(first + second), path="x.bag", offset=0) == first + second
    with_dict_id = bytes([0x61, 0x40]) + b"\1\0\0\0"
    assert decompress_frame(b"\x04\x22\x4d\x18" + with_dict_id + b"\0" * 9, 100) is None
    assert decompress_frame(b"\x50\x2a\x4d\x18" + b"\0" * 12, 100) is None
