"""MCAP files in the ROS 1 profile (schema encoding ``ros1msg``, message encoding ``ros1``), via ``mcap``.

Each bag connection is one MCAP channel; its schema is the message type with
its full definition; the channel metadata keeps md5sum, callerid and latching.
The writer closes a chunk at least every ``max_chunk_age`` seconds so a killed
recording keeps all but its last moments. The reader uses the summary when the
file was closed and otherwise streams records up to the first incomplete one.
"""

from __future__ import annotations

import io
import logging
import os
import struct
import time
import zlib
from collections.abc import Callable, Iterator
from typing import Any

from mcap.data_stream import ReadDataStream, RecordBuilder
from mcap.opcode import Opcode
from mcap.records import Channel, ChunkIndex, DataEnd, Footer, Header, MessageIndex, Schema, Statistics, SummaryOffset

from rostui.core.bag.fileindex import NO_CHUNK, ChunkedFile, ChunkEntries, FileIndex
from rostui.core.bag.iov import Parts
from rostui.core.bag.model import BagError, BagSummary, Connection
from rostui.core.bag.sink import open_append

MAGIC = b"\x89MCAP0\r\n"
COMPRESSIONS = ("none", "lz4", "zstd")
PROFILE = "ros1"


_MESSAGE_HEAD = struct.Struct("<BQHIQQ")  # opcode, record length, channel, sequence, log time, publish time
_CHUNK_HEAD = struct.Struct("<BQQQQI")  # opcode, record length, start, end, uncompressed size, uncompressed crc
_U32 = struct.Struct("<I")
_U64 = struct.Struct("<Q")
OP_CHUNK, OP_MESSAGE = 0x06, 0x05
_MESSAGE_FIELDS = struct.Struct("<HIQ")  # channel, sequence, log time (publish time follows)
_INDEX_ENTRY = [("time", "<u8"), ("offset", "<u8")]
OP_PADDING = 0x80
"""A private record (the spec leaves 0x80-0xFF to applications; readers skip them): zeros before a chunk that
put its big message on a block boundary, so the recorder's direct writes take it without a copy."""


def _padding_record(size: int) -> bytes:
    """A padding record of exactly ``size`` bytes (at least 9: opcode and length)."""
    return bytes([OP_PADDING]) + _U64.pack(size - 9) + bytes(size - 9)


def _compress(kind: str, data: bytes) -> bytes:
    if kind == "lz4":
        import lz4.frame

        packed: bytes = lz4.frame.compress(data)
        return packed
    import zstandard

    return zstandard.compress(data)


def _decompress(kind: str, data: bytes) -> bytes:
    if kind in ("", "none"):
        return data
    if kind == "lz4":
        import lz4.frame

        plain: bytes = lz4.frame.decompress(data)
        return plain
    if kind == "zstd":
        import zstandard

        return zstandard.ZstdDecompressor().decompressobj().decompress(data)
    raise BagError(f"unsupported chunk compression '{kind}'")


def _walk(records: bytes) -> Iterator[tuple[int, int, bytes]]:
    """``(offset, opcode, body)`` of each record in a chunk's records."""
    pos, end = 0, len(records)
    while pos + 9 <= end:
        opcode = records[pos]
        (length,) = _U64.unpack_from(records, pos + 1)
        if pos + 9 + length > end:
            raise BagError("a record runs past the end of its chunk")
        yield pos, opcode, records[pos + 9:pos + 9 + length]
        pos += 9 + length


def _built(builder: RecordBuilder) -> bytes:
    """The records written to ``builder`` so far; it starts empty again."""
    data: bytes = builder.end()  # type: ignore[no-untyped-call]  # mcap leaves end() unannotated
    return data


class McapBagWriter:
    """Writes an MCAP (ros1 profile) file; ``close()`` writes the summary (indexes, statistics).

    Records are laid out as the ``mcap`` library lays them out (schemas and
    channels inside the chunk that first needs them, a message index per
    channel after each chunk, a summary with schemas, channels, statistics and
    chunk indexes), but an uncompressed chunk is never assembled in memory:
    its record headers and the message buffers go to ``writev`` as they are.
    ``chunk_crcs=False`` leaves the chunk CRC at 0 ("not computed", as the
    MCAP spec allows): the recorder's choice, because a CRC of every byte costs
    more CPU than the write itself; rosbag files carry no checksum at all.
    ``direct`` writes the file around the page cache where it can (see
    :mod:`rostui.core.bag.sink`).
    """

    def __init__(self, path: str, *, compression: str = "none", chunk_bytes: int = 768 * 1024,
                 max_chunk_age: float = 0.5, chunk_crcs: bool = True, direct: bool = False) -> None:
        if compression not in COMPRESSIONS:
            raise BagError(f"an MCAP file cannot use {compression} compression (none, lz4 or zstd)")
        self.path = path
        self.compression = compression
        self.chunk_bytes = chunk_bytes
        self.max_chunk_age = max_chunk_age
        self.chunk_crcs = chunk_crcs
        self.out = open_append(path, direct)
        self.connections: dict[int, Connection] = {}
        self.closed = False
        self.failed = False
        self._schemas: dict[tuple[str, str], Schema] = {}
        self._channels: dict[int, Channel] = {}  # by connection id
        self._written: set[int] = set()  # schema and channel ids whose records reached the file (negative: schemas)
        self._chunk = Parts()
        self._chunk_messages = 0
        self._chunk_started = 0.0
        self._chunk_start_ns = 0
        self._chunk_end_ns = 0
        self._chunk_index: dict[int, list[tuple[int, int]]] = {}
        self._chunk_in: list[int] = []  # schema/channel records in the open chunk (as in _written)
        self.chunk_indexes: list[ChunkIndex] = []
        self.counts: dict[int, int] = {}
        self.start_ns = 0
        self.end_ns = 0
        builder = RecordBuilder()
        Header(PROFILE, "rostui").write(builder)
        self.good_end = 0
        self._append([MAGIC + _built(builder)])

    def _append(self, buffers: list[Any]) -> None:
        """Write at the end of the file; on failure cut back to the last complete record."""
        try:
            self.good_end += self.out.append(buffers)
        except OSError:
            self._cut()
            raise

    def _cut(self) -> None:
        self.out.cut(self.good_end)
        self.good_end = self.out.end

    @property
    def size(self) -> int:
        """Bytes written so far (plus what the open chunk holds)."""
        return self.good_end + self._chunk.size

    @property
    def buffered(self) -> int:
        """Bytes of the open chunk: 0 when no message buffer passed to :meth:`write` is still referenced."""
        return self._chunk.size

    def add_connection(self, conn: Connection) -> None:
        """Register a schema (once per type) and a channel for this connection."""
        key = (conn.type, conn.definition)
        schema = self._schemas.get(key)
        if schema is None:
            schema = Schema(len(self._schemas) + 1, conn.definition.encode(), "ros1msg", conn.type)
            self._schemas[key] = schema
        metadata = {"md5sum": conn.md5sum, "callerid": conn.callerid, "latching": "1" if conn.latching else "0"}
        self._channels[conn.id] = Channel(len(self._channels) + 1, conn.topic, "ros1", metadata, schema.id)
        self.connections[conn.id] = conn

    def _declare(self, conn_id: int) -> int:
        """Put the schema and channel records of a connection into the open chunk if the file lacks them."""
        channel = self._channels[conn_id]
        schema_key = -channel.schema_id
        for key, record in ((schema_key, self._schema_by_id(channel.schema_id)), (channel.id, channel)):
            if key not in self._written and key not in self._chunk_in:
                builder = RecordBuilder()
                record.write(builder)
                self._chunk.add(_built(builder))
                self._chunk_in.append(key)
        return channel.id

    def _schema_by_id(self, schema_id: int) -> Schema:
        for schema in self._schemas.values():
            if schema.id == schema_id:
                return schema
        raise KeyError(schema_id)

    def write(self, conn_id: int, time_ns: int, data: Any) -> None:
        """Append one message (log and publish time are the receive time); closes the chunk when full."""
        channel = self._channels[conn_id]
        channel_id = channel.id if channel.id in self._written and -channel.schema_id in self._written \
            else self._declare(conn_id)
        if self._chunk_messages and self.out.takes_in_place(data):
            self.flush()  # a chunk's padding can line up only its first big message
        chunk = self._chunk
        if not self._chunk_messages:
            self._chunk_started = time.monotonic()
            self._chunk_start_ns = self._chunk_end_ns = time_ns
        elif time_ns < self._chunk_start_ns:
            self._chunk_start_ns = time_ns
        elif time_ns > self._chunk_end_ns:
            self._chunk_end_ns = time_ns
        entries = self._chunk_index.get(channel_id)
        if entries is None:
            entries = self._chunk_index[channel_id] = []
        entries.append((time_ns, chunk.size))
        chunk.add(_MESSAGE_HEAD.pack(OP_MESSAGE, 22 + len(data), channel_id, 0, time_ns, time_ns))
        chunk.add(data)
        self._chunk_messages += 1
        if chunk.size >= self.chunk_bytes:
            self.flush()

    def flush_if_old(self) -> None:
        """Close the open chunk when it is older than ``max_chunk_age``."""
        if self._chunk_messages and time.monotonic() - self._chunk_started >= self.max_chunk_age:
            self.flush()
        self.out.sync_if_old()

    def flush(self) -> None:
        """Write the open chunk and its message indexes."""
        if not self._chunk_messages:
            return
        records = self._chunk.buffers()
        plain_size = self._chunk.size
        crc = 0
        if self.compression == "none":
            body = records
            if self.chunk_crcs:
                for buf in records:
                    crc = zlib.crc32(buf, crc)
            compression = b""
        else:
            plain = b"".join(records)
            crc = zlib.crc32(plain) if self.chunk_crcs else 0
            body = [_compress(self.compression, plain)]
            compression = self.compression.encode()
        stored = sum(len(b) for b in body)
        record_length = 8 + 8 + 8 + 4 + 4 + len(compression) + 8 + stored
        head = (_CHUNK_HEAD.pack(OP_CHUNK, record_length, self._chunk_start_ns, self._chunk_end_ns, plain_size, crc)
                + _U32.pack(len(compression)) + compression + _U64.pack(stored))
        pad = self.out.lend_padding([head, *body], 9)
        lead = [_padding_record(pad)] if pad else []
        chunk_start = self.good_end + pad
        chunk_length = len(head) + stored
        indexes = RecordBuilder()
        offsets: dict[int, int] = {}
        for channel_id, entries in self._chunk_index.items():
            offsets[channel_id] = chunk_start + chunk_length + indexes.count
            MessageIndex(channel_id, entries).write(indexes)
        index_bytes = _built(indexes)
        try:
            self._append([*lead, head, *body, index_bytes])
        except OSError:
            self.failed = True
            self._forget_chunk()
            raise
        for channel_id, entries in self._chunk_index.items():
            self.counts[channel_id] = self.counts.get(channel_id, 0) + len(entries)
        if not self.chunk_indexes:
            self.start_ns, self.end_ns = self._chunk_start_ns, self._chunk_end_ns
        else:
            self.start_ns = min(self.start_ns, self._chunk_start_ns)
            self.end_ns = max(self.end_ns, self._chunk_end_ns)
        self.chunk_indexes.append(ChunkIndex(
            message_start_time=self._chunk_start_ns, message_end_time=self._chunk_end_ns,
            chunk_start_offset=chunk_start, chunk_length=chunk_length, message_index_offsets=offsets,
            message_index_length=len(index_bytes), compression=compression.decode(), compressed_size=stored,
            uncompressed_size=plain_size))
        self._written.update(self._chunk_in)
        self._forget_chunk()

    def _forget_chunk(self) -> None:
        self._chunk.clear()
        self._chunk_messages = 0
        self._chunk_index = {}
        self._chunk_in = []

    def _summary(self) -> bytes:
        """DataEnd, the summary section (schemas, channels, statistics, chunk indexes, offsets) and the footer."""
        builder = RecordBuilder()
        DataEnd(0).write(builder)
        summary_start = self.good_end + builder.count
        offsets: list[SummaryOffset] = []
        used_channels = [c for c in self._channels.values() if c.id in self._written]
        used_schemas = [s for s in self._schemas.values() if -s.id in self._written]
        stats = Statistics(message_count=sum(self.counts.values()), schema_count=len(used_schemas),
                           channel_count=len(used_channels), attachment_count=0, metadata_count=0,
                           chunk_count=len(self.chunk_indexes), message_start_time=self.start_ns,
                           message_end_time=self.end_ns, channel_message_counts=dict(self.counts))
        groups: list[tuple[int, list[Any]]] = [(Opcode.SCHEMA, used_schemas), (Opcode.CHANNEL, used_channels),
                                               (Opcode.STATISTICS, [stats]), (Opcode.CHUNK_INDEX, self.chunk_indexes)]
        summary = RecordBuilder()
        for opcode, records in groups:
            group_start = summary.count
            for record in records:
                record.write(summary)
            offsets.append(SummaryOffset(opcode, summary_start + group_start, summary.count - group_start))
        offset_start = summary_start + summary.count
        for offset in offsets:
            offset.write(summary)
        summary_bytes = _built(summary)
        crc = zlib.crc32(summary_bytes)
        crc = zlib.crc32(struct.pack("<BQQQ", Opcode.FOOTER, 20, summary_start, offset_start), crc)
        footer = RecordBuilder()
        Footer(summary_start, offset_start, crc).write(footer)
        return _built(builder) + summary_bytes + _built(footer) + MAGIC

    def close(self) -> None:
        """Write the summary section and footer; on a full disk end the file without a summary instead."""
        if self.closed:
            return
        self.closed = True
        try:
            try:
                self.flush()
                self._append([self._summary()])
            except OSError:
                self._end_without_summary()
                raise
        finally:
            self.out.close()

    def _end_without_summary(self) -> None:
        """DataEnd, a Footer pointing at no summary, and the closing magic: a valid file without indexes."""
        builder = RecordBuilder()
        DataEnd(0).write(builder)
        Footer(0, 0, 0).write(builder)
        try:
            self.good_end += self.out.append([_built(builder) + MAGIC])
        except OSError:
            self._cut()


_log = logging.getLogger("rostui.bag")


def _connection_of(channel: Any, schema: Any, md5sum: str) -> Connection:
    """The bag connection of an MCAP channel; ``md5sum`` is used when the channel's metadata has none."""
    meta = dict(channel.metadata or {})
    definition = schema.data.decode("utf-8", "replace") if schema is not None else ""
    return Connection(channel.id, channel.topic, schema.name if schema is not None else "",
                      meta.get("md5sum") or md5sum, definition, meta.get("callerid", ""),
                      meta.get("latching", "0") == "1")


class McapBagReader(ChunkedFile):
    """Reads an MCAP (ros1 profile) file in file order, or through its index; one cut short reads up to its
    last complete record."""

    def __init__(self, path: str) -> None:
        super().__init__()
        self.path = path
        try:
            self.file = open(path, "rb")
        except OSError as exc:
            raise BagError(f"cannot open {path}: {exc.strerror}") from None
        self.size = os.fstat(self.file.fileno()).st_size
        if self.file.read(len(MAGIC)) != MAGIC:
            self.file.close()
            raise BagError(f"{path} is not an MCAP file (bad magic)")
        self.file.seek(0)
        self.connections: dict[int, Connection] = {}
        self.truncated = ""
        self._md5s: dict[int, str] = {}  # by schema id (0: no schema), for channels without md5sum metadata
        self._scanned_schemas: dict[int, Any] = {}
        """Schema records met while reading chunks: a later chunk's channel may use one an earlier chunk held."""
        self._summary = self._read_summary()

    def close(self) -> None:
        """Close the file."""
        self.file.close()

    def _connection(self, channel: Any, schema: Any) -> Connection:
        """The connection of a channel, its md5sum computed from the schema when the metadata lacks one."""
        if (channel.metadata or {}).get("md5sum"):
            return _connection_of(channel, schema, "")
        return _connection_of(channel, schema, self._schema_md5(channel, schema))

    def _schema_md5(self, channel: Any, schema: Any) -> str:
        """The md5sum of a schema's definition, once per schema; a one-line warning when it cannot be had."""
        from rostui.core.bag.schema_md5 import UNKNOWN_MD5, schema_md5

        key = schema.id if schema is not None else 0
        md5 = self._md5s.get(key)
        if md5 is not None:
            return md5
        if schema is None:
            md5, problem, what = UNKNOWN_MD5, "it has no schema", f"channel {channel.topic}"
        else:
            md5, problem = schema_md5(schema.name, schema.encoding, schema.data)
            what = f"type {schema.name or '(unnamed)'}"
        if problem:
            _log.warning("%s: no md5sum for %s (%s): using the wildcard '%s'", self.path, what, problem, UNKNOWN_MD5)
        self._md5s[key] = md5
        return md5

    def _read_summary(self) -> Any:
        from mcap.reader import SeekingReader

        if self.size < 2 * len(MAGIC) + 30:
            return None
        self.file.seek(-len(MAGIC), os.SEEK_END)
        if self.file.read(len(MAGIC)) != MAGIC:
            return None
        self.file.seek(0)
        try:
            summary = SeekingReader(self.file).get_summary()
        except Exception:
            return None
        finally:
            self.file.seek(0)
        return summary

    @property
    def closed_properly(self) -> bool:
        """True when the file ends with a summary section (the writer finished it)."""
        return self._summary is not None

    def _read_index(self) -> FileIndex | None:
        # the summary's chunk indexes and the message indexes after each chunk (a chunk without message
        # indexes is read instead); None without a summary, or with messages outside chunks
        summary = self._summary
        if summary is None:
            return None
        stats = summary.statistics
        if not summary.chunk_indexes and (stats is None or stats.message_count):
            return None
        try:
            return self._read_file_index(summary)
        except (BagError, EOFError, struct.error, KeyError, ValueError) as exc:
            self.truncated = self.truncated or f"its index cannot be read ({exc})"
            return None

    def _read_file_index(self, summary: Any) -> FileIndex:
        import numpy as np

        for cid, channel in summary.channels.items():
            self.connections[cid] = self._connection(channel, summary.schemas.get(channel.schema_id))
        self.chunk_table = []
        parts: list[ChunkEntries] = []
        for number, index in enumerate(sorted(summary.chunk_indexes, key=lambda i: i.chunk_start_offset)):
            self.chunk_table.append(self._chunk_location(index.chunk_start_offset))
            if not index.message_index_offsets:
                parts.append(self._chunk_part(number))
                continue
            self.file.seek(index.chunk_start_offset + index.chunk_length)
            block = self.file.read(index.message_index_length)
            pos = 0
            while pos + 9 <= len(block):
                opcode = block[pos]
                (length,) = _U64.unpack_from(block, pos + 1)
                body = block[pos + 9:pos + 9 + length]
                pos += 9 + length
                if opcode != Opcode.MESSAGE_INDEX or len(body) < 6:
                    continue
                channel_id = struct.unpack_from("<H", body)[0]
                (records_length,) = _U32.unpack_from(body, 2)
                entries = np.frombuffer(body, dtype=_INDEX_ENTRY, count=records_length // 16, offset=6)
                if channel_id in self.connections:
                    parts.append(ChunkEntries(entries["time"].astype(np.int64),
                                              np.full(len(entries), channel_id, dtype=np.uint32),
                                              entries["offset"], number))
        return FileIndex.build(parts)

    def _chunk_location(self, at: int) -> tuple[int, int, str]:
        """(records' position, stored length, compression) of the chunk record at ``at``."""
        self.file.seek(at)
        head = self.file.read(_CHUNK_HEAD.size + 4)
        if len(head) < _CHUNK_HEAD.size + 4 or head[0] != OP_CHUNK:
            raise BagError(f"no chunk at byte {at}")
        (name_length,) = _U32.unpack_from(head, _CHUNK_HEAD.size)
        compression = self.file.read(name_length).decode()
        (stored,) = _U64.unpack(self.file.read(8))
        return self.file.tell(), stored, compression

    def _chunk_part(self, number: int) -> ChunkEntries:
        """The entries of chunk ``number`` found by reading its records (schemas and channels taken in)."""
        times, conn_ids, offsets = [], [], []
        schemas = self._scanned_schemas
        for at, opcode, body in _walk(self.cache.get(number)):
            if opcode == OP_MESSAGE:
                channel_id, _seq, log_time = _MESSAGE_FIELDS.unpack_from(body)
                if channel_id in self.connections:
                    times.append(log_time)
                    conn_ids.append(channel_id)
                    offsets.append(at)
            else:
                self._take_definition(opcode, body, schemas)
        return ChunkEntries(times, conn_ids, offsets, number)

    def _take_definition(self, opcode: int, body: bytes, schemas: dict[int, Any]) -> None:
        """Remember a schema record; turn a channel record into a connection."""
        if opcode == Opcode.SCHEMA:
            schema = Schema.read(ReadDataStream(io.BytesIO(body)))
            schemas[schema.id] = schema
        elif opcode == Opcode.CHANNEL:
            channel = Channel.read(ReadDataStream(io.BytesIO(body)))
            if channel.id not in self.connections:
                self.connections[channel.id] = self._connection(channel, schemas.get(channel.schema_id))

    def scan_index(self, progress: Callable[[int], None] | None = None) -> FileIndex:
        """Where every readable message lies, by reading every chunk once (payloads are not kept); a
        file cut short is read up to its last complete record. ``progress(bytes_read)`` after each chunk."""
        self.chunk_table = []
        parts: list[ChunkEntries] = []
        loose: tuple[list[int], list[int], list[int]] = ([], [], [])
        schemas = self._scanned_schemas
        self.file.seek(len(MAGIC))
        pos = len(MAGIC)
        while pos + 9 <= self.size:
            self.file.seek(pos)
            head = self.file.read(9)
            opcode = head[0]
            (length,) = _U64.unpack_from(head, 1)
            if pos + 9 + length > self.size:
                self.truncated = f"the file ends in an incomplete record at byte {pos}"
                break
            if opcode == OP_CHUNK:
                location = self._chunk_location(pos)
                number = len(self.chunk_table)
                self.chunk_table.append(location)
                try:
                    parts.append(self._chunk_part(number))
                except Exception as exc:  # bad compression or a damaged chunk: what came before stays
                    self.chunk_table.pop()
                    self.truncated = f"a chunk at byte {pos} cannot be read ({type(exc).__name__})"
                    break
                if progress is not None:
                    progress(pos + 9 + length)
            elif opcode == OP_MESSAGE:
                body = self.file.read(_MESSAGE_FIELDS.size)
                channel_id, _seq, log_time = _MESSAGE_FIELDS.unpack_from(body)
                if channel_id in self.connections:
                    loose[0].append(log_time)
                    loose[1].append(channel_id)
                    loose[2].append(pos)
            elif opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
                self._take_definition(opcode, self.file.read(length), schemas)
            elif opcode in (Opcode.DATA_END, Opcode.FOOTER):
                break
            pos += 9 + length
        if loose[0]:
            parts.append(ChunkEntries(*loose, NO_CHUNK))
        return FileIndex.build(parts, from_file_index=False)

    def _decompress_chunk(self, kind: str, data: bytes) -> bytes:
        return _decompress(kind, data)

    def payload(self, chunk: int, offset: int) -> bytes:
        """The serialised message whose record starts at ``offset`` of chunk ``chunk``'s records (or of
        the file, for a message outside any chunk), as a :class:`FileIndex` locates it."""
        if chunk == NO_CHUNK:
            self.file.seek(offset)
            head = self.file.read(9)
            (length,) = _U64.unpack_from(head, 1)
            body: bytes = self.file.read(length)
            return body[_MESSAGE_FIELDS.size + 8:]
        records = self.cache.get(chunk)
        (length,) = _U64.unpack_from(records, offset + 1)
        return records[offset + 9 + _MESSAGE_FIELDS.size + 8:offset + 9 + length]

    def messages(self) -> Iterator[tuple[Connection, int, bytes]]:
        """``(connection, time_ns, data)`` in file order; stops at the first incomplete record."""
        from mcap.records import Channel, Message, Schema
        from mcap.stream_reader import StreamReader

        self.file.seek(0)
        schemas: dict[int, Any] = {}
        records = StreamReader(self.file, skip_magic=False, validate_crcs=True).records
        while True:
            try:
                record = next(records)
            except StopIteration:
                return
            except Exception as exc:  # the mcap reader's own errors, struct errors, bad compression
                self.truncated = f"the file ends in an incomplete record ({type(exc).__name__})"
                return
            if isinstance(record, Message):
                conn = self.connections.get(record.channel_id)
                if conn is not None:
                    yield conn, record.log_time, record.data
            elif isinstance(record, Schema):
                schemas[record.id] = record
            elif isinstance(record, Channel):
                if record.id not in self.connections:
                    self.connections[record.id] = self._connection(record, schemas.get(record.schema_id))

    def summary(self) -> BagSummary:
        """Counts and times from the summary section, or from reading every record when there is none."""
        out = BagSummary(self.path, "mcap", "0 (ros1 profile)", self.size, closed=self.closed_properly)
        summary = self._summary
        if summary is not None and summary.statistics is not None:
            for cid, channel in summary.channels.items():
                self.connections[cid] = self._connection(channel, summary.schemas.get(channel.schema_id))
            stats = summary.statistics
            out.counts = {cid: n for cid, n in stats.channel_message_counts.items()}
            out.start_ns, out.end_ns = stats.message_start_time, stats.message_end_time
            for index in summary.chunk_indexes:
                out.add_chunk(index.compression or "none", index.uncompressed_size, index.compressed_size)
        else:
            first = last = None
            for conn, t, _data in self.messages():
                out.counts[conn.id] = out.counts.get(conn.id, 0) + 1
                first = t if first is None else min(first, t)
                last = t if last is None else max(last, t)
            out.start_ns, out.end_ns = first or 0, last or 0
            out.problem = self.truncated
        out.connections = [self.connections[c] for c in sorted(self.connections)]
        return out
