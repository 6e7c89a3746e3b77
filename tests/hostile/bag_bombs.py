"""Hostile bag files built byte by byte: decompression bombs whose chunks declare a small size, an honest bomb, and
an unclosed bag followed by a long run of zeros.

Each builder writes a file every reader must accept as far as its headers go (a rosbag v2.0 file with its index,
or an MCAP file with or without its summary); only what a chunk decompresses to lies.  The bombs are built from
compressed runs of zeros, cheaply: bz2 as a series of streams (``bz2.decompress``, rosbag's reader, reads them
all), lz4 as one frame of independent blocks (the only form roslz4 reads), zstd as one frame.
"""

from __future__ import annotations

import bz2
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Any

MiB = 1024 * 1024
BAG_MAGIC = b"#ROSBAG V2.0\n"
MCAP_MAGIC = b"\x89MCAP0\r\n"
STRING_DEF = "string data\n"
STRING_MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"
TOPIC = "/bomb"
START_NS = 1_700_000_000 * 1_000_000_000
_U32 = struct.Struct("<I")


def _field(name: str, value: bytes) -> bytes:
    item = name.encode() + b"=" + value
    return _U32.pack(len(item)) + item


def _record(fields: dict[str, bytes], data: bytes) -> bytes:
    header = b"".join(_field(k, v) for k, v in fields.items())
    return _U32.pack(len(header)) + header + _U32.pack(len(data)) + data


def _time(ns: int) -> bytes:
    return struct.pack("<II", ns // 1_000_000_000, ns % 1_000_000_000)


def _string(text: str) -> bytes:
    raw = text.encode()
    return _U32.pack(len(raw)) + raw


def _connection_record(conn: int, topic: str) -> bytes:
    info = {"topic": topic.encode(), "type": b"std_msgs/String", "md5sum": STRING_MD5.encode(),
            "message_definition": STRING_DEF.encode()}
    data = b"".join(_field(k, v) for k, v in info.items())
    return _record({"op": b"\x07", "conn": _U32.pack(conn), "topic": topic.encode()}, data)


def bag_records(conn: int, topic: str, texts: list[str], start_ns: int) -> tuple[bytes, list[tuple[int, int]]]:
    """A chunk's plain records (the connection, then one String message per text, 10 ms apart) and the
    ``(time, offset)`` of each message."""
    out = bytearray(_connection_record(conn, topic))
    entries = []
    for i, text in enumerate(texts):
        t = start_ns + i * 10_000_000
        entries.append((t, len(out)))
        out += _record({"op": b"\x02", "conn": _U32.pack(conn), "time": _time(t)}, _string(text))
    return bytes(out), entries


@dataclass(frozen=True)
class BagChunk:
    """One chunk of a hand-built ``.bag``: its compression, stored bytes, the size it declares, the ``(time,
    offset)`` of its messages, and their connection."""

    compression: str
    stored: bytes
    declared: int
    entries: list[tuple[int, int]]
    conn: int = 0


def write_bag(path: Path, chunks: list[BagChunk], topics: dict[int, str], *, closed: bool = True) -> Path:
    """A rosbag v2.0 file of ``chunks`` (``topics``: each connection's topic) with its index (connection and
    chunk info records) when ``closed``; else with an index position of 0, as a recorder killed mid-way
    leaves it."""
    body = bytearray()
    infos = []
    head_size = len(BAG_MAGIC) + 4 + 4096 + 4
    for chunk in chunks:
        position = head_size + len(body)
        body += _record({"op": b"\x05", "compression": chunk.compression.encode(),
                         "size": _U32.pack(chunk.declared)}, chunk.stored)
        index = b"".join(_time(t) + _U32.pack(off) for t, off in chunk.entries)
        body += _record({"op": b"\x04", "ver": _U32.pack(1), "conn": _U32.pack(chunk.conn),
                         "count": _U32.pack(len(chunk.entries))}, index)
        infos.append((position, chunk))
    index_pos = head_size + len(body) if closed else 0
    tail = bytearray()
    if closed:
        for conn, topic in topics.items():
            tail += _connection_record(conn, topic)
        for position, chunk in infos:
            times = [t for t, _ in chunk.entries]
            tail += _record({"op": b"\x06", "ver": _U32.pack(1), "chunk_pos": struct.pack("<Q", position),
                             "start_time": _time(min(times)), "end_time": _time(max(times)),
                             "count": _U32.pack(1)}, _U32.pack(chunk.conn) + _U32.pack(len(chunk.entries)))
    header = b"".join(_field(k, v) for k, v in {
        "op": b"\x03", "index_pos": struct.pack("<Q", index_pos),
        "conn_count": _U32.pack(len(topics) if closed else 0),
        "chunk_count": _U32.pack(len(chunks) if closed else 0)}.items())
    file_header = _U32.pack(len(header)) + header + _U32.pack(4096 - len(header)) + b" " * (4096 - len(header))
    path.write_bytes(BAG_MAGIC + file_header + bytes(body) + bytes(tail))
    return path


def bz2_bomb(prefix: bytes, zero_streams: int) -> bytes:
    """``prefix`` compressed, then ``zero_streams`` bz2 streams of 45 MB of zeros each (50 bytes apiece)."""
    zeros = bz2.compress(bytes(45_000_000), 9)
    return bz2.compress(prefix) + zeros * zero_streams


def lz4_bomb(prefix: bytes, zero_mib: int) -> bytes:
    """One lz4 frame as roslz4 writes them (independent 4 MiB blocks, a content checksum): ``prefix`` and then
    ``zero_mib`` MiB of zeros (about 4 KiB of frame for every MiB)."""
    import lz4.frame

    frame = lz4.frame.LZ4FrameCompressor(block_size=lz4.frame.BLOCKSIZE_MAX4MB, block_linked=False,
                                         block_checksum=False, content_checksum=True)
    zeros = bytes(4 * MiB)
    parts = [frame.begin(), frame.compress(prefix)]
    parts += [frame.compress(zeros) for _ in range(zero_mib // 4)]
    parts.append(frame.flush())
    return b"".join(parts)


def zstd_bomb(prefix: bytes, zero_mib: int) -> bytes:
    """One zstd frame of ``prefix`` and ``zero_mib`` MiB of zeros, without a content size (about 33 bytes a
    MiB)."""
    import zstandard

    stream = zstandard.ZstdCompressor(level=1).compressobj()
    zeros = bytes(16 * MiB)
    parts = [stream.compress(prefix)]
    parts += [stream.compress(zeros) for _ in range(zero_mib // 16)]
    parts.append(stream.flush())
    return b"".join(parts)


GOOD_TOPIC = "/good"
GOOD_COUNT = 20


def good_chunk() -> BagChunk:
    """An uncompressed chunk of :data:`GOOD_COUNT` real String messages on :data:`GOOD_TOPIC` (connection 0),
    10 ms apart from :data:`START_NS`."""
    plain, entries = bag_records(0, GOOD_TOPIC, [f"good {i}" for i in range(GOOD_COUNT)], START_NS)
    return BagChunk("none", plain, len(plain), entries, 0)


def bag_bomb(path: Path, compression: str, zero_mib: int) -> Path:
    """A closed ``.bag``: the :func:`good_chunk`, then a ``compression`` (bz2 or lz4) chunk on :data:`TOPIC`
    (connection 1, one second later) declaring the size of its 20 real records while its data goes on with
    ``zero_mib`` MiB of zeros."""
    plain, entries = bag_records(1, TOPIC, [f"bomb {i}" for i in range(20)], START_NS + 1_000_000_000)
    stored = bz2_bomb(plain, max(1, zero_mib // 43)) if compression == "bz2" else lz4_bomb(plain, zero_mib)
    return write_bag(path, [good_chunk(), BagChunk(compression, stored, len(plain), entries, 1)],
                     {0: GOOD_TOPIC, 1: TOPIC})


def unclosed_with_zeros(path: Path, zero_mib: int) -> Path:
    """An unclosed ``.bag`` (index position 0) of the :func:`good_chunk`, followed by ``zero_mib`` MiB of zeros (a
    sparse run: no disk is spent on it)."""
    write_bag(path, [good_chunk()], {0: GOOD_TOPIC}, closed=False)
    with open(path, "r+b") as f:
        f.truncate(path.stat().st_size + zero_mib * MiB)
    return path


def _schema() -> Any:
    from mcap.records import Schema

    return Schema(id=1, name="std_msgs/String", encoding="ros1msg", data=STRING_DEF.encode())


def _channel() -> Any:
    from mcap.records import Channel

    return Channel(id=1, schema_id=1, topic=TOPIC, message_encoding="ros1", metadata={"md5sum": STRING_MD5})


def _mcap_records(texts: list[str]) -> tuple[bytes, list[tuple[int, int]]]:
    """A chunk's plain records (schema 1, channel 1 on /bomb, one message per text, 10 ms apart) and each
    message's ``(log time, offset)``."""
    from mcap.data_stream import RecordBuilder
    from mcap.records import Message

    builder = RecordBuilder()
    _schema().write(builder)
    _channel().write(builder)
    entries = []
    for i, text in enumerate(texts):
        t = START_NS + i * 10_000_000
        entries.append((t, builder.count))
        Message(channel_id=1, sequence=i, log_time=t, publish_time=t, data=_string(text)).write(builder)
    plain: bytes = builder.end()  # type: ignore[no-untyped-call]
    return plain, entries


def mcap_bomb(path: Path, zero_mib: int, *, summary: bool, honest: bool = False, texts: int = 20) -> Path:
    """An MCAP file of one zstd chunk: the real records of ``texts`` messages, then ``zero_mib`` MiB of zeros.

    The chunk declares the size of its real records (or, ``honest``, all it decompresses to).  With
    ``summary`` the file ends as the writer closes it (schemas, channels, statistics, a chunk index and
    message index): a reader needs no chunk to say what the file holds.  Without, it ends after the chunk, as
    a recorder killed mid-way leaves it.
    """
    from mcap.data_stream import RecordBuilder
    from mcap.opcode import Opcode
    from mcap.records import Chunk, ChunkIndex, DataEnd, Footer, Header, MessageIndex, Statistics, SummaryOffset

    plain, entries = _mcap_records([f"bomb {i}" for i in range(texts)])
    stored = zstd_bomb(plain, zero_mib)
    declared = len(plain) + zero_mib * MiB if honest else len(plain)
    out = RecordBuilder()
    Header(profile="ros1", library="hostile").write(out)
    start, end = entries[0][0], entries[-1][0]
    chunk_start = len(MCAP_MAGIC) + out.count
    Chunk(compression="zstd", data=stored, message_start_time=start, message_end_time=end, uncompressed_crc=0,
          uncompressed_size=declared).write(out)
    chunk_length = len(MCAP_MAGIC) + out.count - chunk_start
    index_start = len(MCAP_MAGIC) + out.count
    MessageIndex(channel_id=1, records=entries).write(out)
    index_length = len(MCAP_MAGIC) + out.count - index_start
    if not summary:
        path.write_bytes(MCAP_MAGIC + out.end())  # type: ignore[no-untyped-call]
        return path
    DataEnd(data_section_crc=0).write(out)
    summary_start = len(MCAP_MAGIC) + out.count
    groups = []
    statistics = Statistics(message_count=texts, schema_count=1, channel_count=1, attachment_count=0,
                            metadata_count=0, chunk_count=1, message_start_time=start, message_end_time=end,
                            channel_message_counts={1: texts})
    chunk_index = ChunkIndex(message_start_time=start, message_end_time=end, chunk_start_offset=chunk_start,
                             chunk_length=chunk_length, message_index_offsets={1: index_start},
                             message_index_length=index_length, compression="zstd", compressed_size=len(stored),
                             uncompressed_size=declared)
    for opcode, record in ((Opcode.SCHEMA, _schema()), (Opcode.CHANNEL, _channel()),
                           (Opcode.STATISTICS, statistics), (Opcode.CHUNK_INDEX, chunk_index)):
        at = len(MCAP_MAGIC) + out.count
        record.write(out)
        groups.append(SummaryOffset(group_opcode=opcode, group_start=at, group_length=len(MCAP_MAGIC) + out.count - at))
    offsets_start = len(MCAP_MAGIC) + out.count
    for group in groups:
        group.write(out)
    Footer(summary_start=summary_start, summary_offset_start=offsets_start, summary_crc=0).write(out)
    path.write_bytes(MCAP_MAGIC + out.end() + MCAP_MAGIC)  # type: ignore[no-untyped-call]
    return path
