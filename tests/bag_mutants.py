"""Mutants of real bags for the bag readers' fuzz test: bit flips, smashed spans, truncations, zeros after a cut,
spliced spans, and lies in the length, count, size, offset and id fields each format keeps.

The bases are the real files in ``tests/bag_corpus`` (see its README) and small files derived from them by
other people's writers: Debian's ``rosbag`` (its Python API, with tiny chunks, uncompressed, bz2 and lz4) and
the ``mcap`` library's writer (ROS 1 profile, uncompressed, lz4 and zstd).  Fields are found by walkers written
here from the two formats' specifications, independent of rostui's readers.  Everything is seeded.
"""

from __future__ import annotations

import random
import struct
import subprocess
from dataclasses import dataclass
from pathlib import Path

CORPUS = Path(__file__).parent / "bag_corpus"
BAG_MAGIC = b"#ROSBAG V2.0\n"
MCAP_MAGIC = b"\x89MCAP0\r\n"
SMALL_MESSAGES = 120
"""How many messages of the real example bag the derived files keep (seven of its nine topics: rosout, tf,
tf_static, the turtles' poses and colour sensors)."""


@dataclass(frozen=True)
class Slot:
    """A number stored in a file: where, how wide (1, 2, 4 or 8 bytes), what it says and what it is."""

    pos: int
    width: int
    value: int
    name: str


@dataclass(frozen=True)
class Mutant:
    """One mutated file: its name (base, operator, detail) and bytes."""

    name: str
    data: bytes


# -- the bases ---------------------------------------------------------------------------------------------

_DEBIAN_WRITER = r"""
import sys, rosbag
source, out_dir, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
items = []
with rosbag.Bag(source) as bag:
    for i, (topic, raw, t) in enumerate(bag.read_messages(raw=True)):
        if i >= count:
            break
        items.append((topic, raw, t))
for compression in ("none", "bz2", "lz4"):
    with rosbag.Bag(f"{out_dir}/debian-{compression}.bag", "w", compression=compression,
                    chunk_threshold=2048) as out:
        for topic, raw, t in items:
            out.write(topic, raw, t, raw=True)
"""


def debian_bags(dest: Path) -> list[Path]:
    """Three small ``.bag`` files Debian's rosbag writes from the first messages of the real example bag."""
    subprocess.run(["/usr/bin/python3", "-c", _DEBIAN_WRITER, str(CORPUS / "example-lz4.bag"), str(dest),
                    str(SMALL_MESSAGES)], check=True, capture_output=True, timeout=60)
    return [dest / f"debian-{c}.bag" for c in ("none", "bz2", "lz4")]


def mcap_library_files(source: Path, dest: Path) -> list[Path]:
    """The messages of ``source`` (a real ``.bag``) in MCAP files the ``mcap`` library writes (ROS 1 profile,
    small chunks), uncompressed, lz4 and zstd."""
    from mcap.writer import CompressionType, Writer

    from rostui.core.bag.files import open_reader

    reader = open_reader(str(source))
    try:
        items = list(reader.messages())
    finally:
        reader.close()
    out = []
    for compression in (CompressionType.NONE, CompressionType.LZ4, CompressionType.ZSTD):
        path = dest / f"mcaplib-{compression.name.lower()}.mcap"
        with open(path, "wb") as f:
            writer = Writer(f, chunk_size=2048, compression=compression)
            writer.start(profile="ros1", library="mcap python")
            schemas: dict[str, int] = {}
            channels: dict[int, int] = {}
            for conn, t, data in items:
                if conn.type not in schemas:
                    schemas[conn.type] = writer.register_schema(conn.type, "ros1msg", conn.definition.encode())
                if conn.id not in channels:
                    channels[conn.id] = writer.register_channel(conn.topic, "ros1", schemas[conn.type],
                                                                {"md5sum": conn.md5sum, "callerid": conn.callerid})
                writer.add_message(channels[conn.id], t, data, t)
            writer.finish()
        out.append(path)
    return out


# -- where the numbers are ---------------------------------------------------------------------------------

def _bag_header_slots(raw: bytes, base: int, out: list[Slot]) -> None:
    """The field lengths and the numeric fields of a ``.bag`` record header starting at ``base``."""
    widths = {"op": 1, "conn": 4, "count": 4, "size": 4, "ver": 4, "chunk_count": 4, "conn_count": 4,
              "index_pos": 8, "chunk_pos": 8, "time": 4, "start_time": 4, "end_time": 4}
    pos = 0
    while pos + 4 <= len(raw):
        (length,) = struct.unpack_from("<I", raw, pos)
        out.append(Slot(base + pos, 4, length, "field length"))
        item = raw[pos + 4:pos + 4 + length]
        name, _, value = item.partition(b"=")
        width = widths.get(name.decode("latin-1"))
        value_at = base + pos + 4 + len(name) + 1
        if width is not None and len(value) >= width:
            out.append(Slot(value_at, width, int.from_bytes(value[:width], "little"), name.decode()))
        pos += 4 + length


def bag_slots(data: bytes, start: int = len(BAG_MAGIC), end: int | None = None) -> list[Slot]:
    """Every record's header and data lengths, field lengths and numeric fields in ``data[start:end]`` (the
    records of uncompressed chunks too)."""
    out: list[Slot] = []
    pos, end = start, len(data) if end is None else end
    while pos + 4 <= end:
        (hlen,) = struct.unpack_from("<I", data, pos)
        if pos + 8 + hlen > end:
            break
        out.append(Slot(pos, 4, hlen, "header length"))
        header = data[pos + 4:pos + 4 + hlen]
        _bag_header_slots(header, pos + 4, out)
        (dlen,) = struct.unpack_from("<I", data, pos + 4 + hlen)
        out.append(Slot(pos + 4 + hlen, 4, dlen, "data length"))
        body = pos + 8 + hlen
        if b"op=\x05" in header and b"compression=none" in header:
            out += bag_slots(data, body, min(end, body + dlen))
        pos = body + dlen
    return out


_MCAP_FIXED: dict[int, list[tuple[int, int, str]]] = {
    # opcode: (offset in the record's body, width, name) of the numbers worth lying about
    0x02: [(0, 8, "summary start"), (8, 8, "summary offset start")],
    0x03: [(0, 2, "schema id"), (2, 4, "schema name length")],
    0x04: [(0, 2, "channel id"), (2, 2, "channel schema id"), (4, 4, "topic length")],
    0x05: [(0, 2, "message channel id")],
    0x06: [(16, 8, "uncompressed size"), (24, 4, "uncompressed crc"), (28, 4, "compression length")],
    0x07: [(0, 2, "index channel id"), (2, 4, "index records length")],
    0x08: [(16, 8, "chunk start offset"), (24, 8, "chunk length"), (32, 4, "index offsets length")],
    0x0B: [(0, 8, "message count"), (22, 4, "chunk count"), (46, 4, "channel counts length")],
    0x0E: [(1, 8, "group start"), (9, 8, "group length")],
}


def mcap_slots(data: bytes, start: int = len(MCAP_MAGIC), end: int | None = None) -> list[Slot]:
    """Every record's length and the numbers :data:`_MCAP_FIXED` names in ``data[start:end]`` (the records of
    uncompressed chunks too, and a chunk's stored length)."""
    out: list[Slot] = []
    pos, end = start, len(data) if end is None else end
    while pos + 9 <= end:
        opcode = data[pos]
        (length,) = struct.unpack_from("<Q", data, pos + 1)
        if pos + 9 + length > end:
            break
        out.append(Slot(pos + 1, 8, length, f"record length (op {opcode:#x})"))
        body = pos + 9
        for offset, width, name in _MCAP_FIXED.get(opcode, []):
            if offset + width <= length:
                out.append(Slot(body + offset, width, int.from_bytes(data[body + offset:body + offset + width],
                                                                     "little"), name))
        if opcode == 0x06 and length >= 32:
            (name_length,) = struct.unpack_from("<I", data, body + 28)
            stored_at = body + 32 + name_length
            if stored_at + 8 <= body + length:
                (stored,) = struct.unpack_from("<Q", data, stored_at)
                out.append(Slot(stored_at, 8, stored, "chunk stored length"))
                if name_length == 0:
                    out += mcap_slots(data, stored_at + 8, min(body + length, stored_at + 8 + stored))
        pos = body + length
    return out


# -- the operators -----------------------------------------------------------------------------------------

def _lies(slot: Slot, size: int) -> list[int]:
    """Values a lying field takes: off by one, zero, the file's size, and the format's extremes."""
    top = (1 << (8 * slot.width)) - 1
    values = {0, 1, slot.value + 1, max(slot.value - 1, 0), slot.value * 2 + 7, size, top, top >> 1, 4242}
    if slot.width == 8:
        values |= {1 << 62, 1 << 32, (1 << 31) - 1}
    return sorted(v for v in values if 0 <= v <= top and v != slot.value)


def _put(data: bytearray, slot: Slot, value: int) -> None:
    data[slot.pos:slot.pos + slot.width] = value.to_bytes(slot.width, "little")


def mutate(name: str, data: bytes, rng: random.Random, count: int) -> list[Mutant]:
    """``count`` mutants of the file ``name`` holding ``data``, drawn with ``rng``."""
    slots = mcap_slots(data) if data.startswith(MCAP_MAGIC) else bag_slots(data)
    size = len(data)
    out: list[Mutant] = []
    operators = ["lie"] * 5 + ["flip"] * 3 + ["smash", "truncate", "zeros", "splice"] * 1
    for n in range(count):
        op = rng.choice(operators) if slots else rng.choice(["flip", "smash", "truncate"])
        buf = bytearray(data)
        if op == "lie":
            slot = rng.choice(slots)
            value = rng.choice(_lies(slot, size))
            _put(buf, slot, value)
            detail = f"{slot.name}@{slot.pos}={value}"
        elif op == "flip":
            flips = [rng.randrange(8 * size) for _ in range(rng.choice([1, 1, 2, 8]))]
            for bit in flips:
                buf[bit // 8] ^= 1 << (bit % 8)
            detail = ",".join(str(b) for b in flips)
        elif op == "smash":
            at = rng.randrange(size)
            width = rng.choice([1, 4, 16, 64])
            fill = rng.choice([b"\x00", b"\xff", None])
            buf[at:at + width] = fill * width if fill is not None else rng.randbytes(width)
            detail = f"{at}+{width}"
        elif op == "truncate":
            at = rng.randrange(size)
            del buf[at:]
            detail = str(at)
        elif op == "zeros":
            at = rng.randrange(size // 2, size)
            del buf[at:]
            buf += bytes(rng.choice([4096, 65536, 1 << 20]))
            detail = f"{at}+zeros"
        else:
            at, length, into = rng.randrange(size), rng.randrange(1, 512), rng.randrange(size)
            buf[into:into] = data[at:at + length]
            detail = f"{at}+{length}>{into}"
        out.append(Mutant(f"{name}~{n}-{op}-{detail}", bytes(buf)))
    return out
