"""What every bag format stores: connections and time-stamped raw messages."""

from __future__ import annotations

import struct
from typing import Union

from rostui.core.file_region import FileRegion
from rostui.core.records import FrozenRecord, Record

_FRAME_LENGTH = struct.Struct("<I")

Frame = Union[bytes, memoryview, FileRegion]
"""A message as TCPROS frames it (its 4-byte length, then its bytes): in memory, or where it lies in a file."""

MCAP_MAGIC = b"\x89MCAP0\r\n"
"""The bytes an MCAP file starts and ends with."""
MCAP_COMPRESSIONS = ("none", "lz4", "zstd")
"""The chunk compressions rostui writes and reads in MCAP files."""


def frame_of(data: bytes) -> bytes:
    """``data`` as TCPROS frames a message: its length in 4 little-endian bytes, then the bytes."""
    return _FRAME_LENGTH.pack(len(data)) + data


class BagError(Exception):
    """A bag cannot be read or written; the message is one line for the user."""


class MalformedRecord(BagError):
    """A record of a bag file is not what its format allows: one line naming the file, the byte offset where the
    record starts (for a record inside a chunk, the chunk's own) and what is wrong."""

    def __init__(self, path: str, offset: int, what: str) -> None:
        super().__init__(f"{path}: {what} (byte {offset})")
        self.path = path
        self.offset = offset
        self.what = what

    @property
    def where(self) -> str:
        """What is wrong and at which byte, without the file's name."""
        return f"{self.what} at byte {self.offset}"


class Connection(FrozenRecord):
    """One publisher connection as recorded: its topic, type, md5sum, definition, callerid and latching.

    A record rather than a dataclass (:mod:`rostui.core.records` says why): every bag command and every player
    makes its connections before its first message."""

    _fields = ("id", "topic", "type", "md5sum", "definition", "callerid", "latching")
    id: int
    topic: str
    type: str
    md5sum: str
    definition: str
    callerid: str
    latching: bool

    def __init__(self, id: int, topic: str, type: str, md5sum: str, definition: str,
                 callerid: str = "", latching: bool = False) -> None:
        self._set(id, topic, type, md5sum, definition, callerid, latching)

    def header_fields(self) -> dict[str, str]:
        """The connection-header fields a rosbag connection record carries."""
        fields = {"topic": self.topic, "type": self.type, "md5sum": self.md5sum,
                  "message_definition": self.definition}
        if self.callerid:
            fields["callerid"] = self.callerid
        if self.latching:
            fields["latching"] = "1"
        return fields


class BagSummary(Record):
    """What ``info`` shows: times, counts per connection, compression, and whether the file was closed.

    ``chunk_bytes``: per compression kind, (uncompressed, stored) bytes of all its chunks. ``info_span``: rosbag
    info's start and end, the first chunk's start time and the last chunk's end time, chunks in file order (a
    ``.bag``'s chunk infos); unlike ``start_ns``/``end_ns`` (the earliest and latest message) they can be inside
    the bag's time range when chunks are out of time order; None where a format has no such records."""

    _fields = ("path", "format", "version", "size", "connections", "counts", "start_ns", "end_ns",
               "chunk_compression", "chunk_bytes", "closed", "problem", "info_span")

    def __init__(self, path: str, format: str, version: str, size: int,
                 connections: list[Connection] | None = None, counts: dict[int, int] | None = None,
                 start_ns: int = 0, end_ns: int = 0, chunk_compression: dict[str, int] | None = None,
                 chunk_bytes: dict[str, tuple[int, int]] | None = None, closed: bool = True, problem: str = "",
                 info_span: tuple[int, int] | None = None) -> None:
        self.path = path
        self.format = format
        self.version = version
        self.size = size
        self.connections: list[Connection] = [] if connections is None else connections
        self.counts: dict[int, int] = {} if counts is None else counts
        self.start_ns = start_ns
        self.end_ns = end_ns
        self.chunk_compression: dict[str, int] = {} if chunk_compression is None else chunk_compression
        self.chunk_bytes: dict[str, tuple[int, int]] = {} if chunk_bytes is None else chunk_bytes
        self.closed = closed
        self.problem = problem
        self.info_span = info_span

    def add_chunk(self, kind: str, uncompressed: int, stored: int) -> None:
        """Count one chunk of ``kind`` (``none``, ``lz4``, ...) and its sizes."""
        self.chunk_compression[kind] = self.chunk_compression.get(kind, 0) + 1
        plain, packed = self.chunk_bytes.get(kind, (0, 0))
        self.chunk_bytes[kind] = (plain + uncompressed, packed + stored)

    @property
    def message_count(self) -> int:
        """All messages in the file."""
        return sum(self.counts.values())

    @property
    def chunk_count(self) -> int:
        """All chunks in the file."""
        return sum(self.chunk_compression.values())


def connection_key(topic: str, header: dict[str, str]) -> tuple[str, str, str, str, bool]:
    """What makes two publishers' connections one bag connection: topic, type, md5, callerid, latching."""
    return (topic, header.get("type", ""), header.get("md5sum", ""), header.get("callerid", ""),
            header.get("latching", "0") == "1")
