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

from rostui.core.bag.fileindex import NO_CHUNK, ChunkedFile, ChunkEntries, ChunkPlace
from rostui.core.bag.iov import Parts
from rostui.core.bag.model import MCAP_COMPRESSIONS, MCAP_MAGIC, BagError, BagSummary, Connection, MalformedRecord
from rostui.core.bag.sink import open_append

MAGIC = MCAP_MAGIC
COMPRESSIONS = MCAP_COMPRESSIONS
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


def _walk(records: bytes, path: str, chunk_at: int) -> Iterator[tuple[int, int, memoryview]]:
    """``(offset, opcode, body)`` of each record in the plain records of the chunk at ``chunk_at``; a record that
    does not fit, or one of opcode 0 (reserved: never written, a run of zeros), is a MalformedRecord."""
    view = memoryview(records)
    pos, end = 0, len(records)
    while pos < end:
        if end - pos < 9:
            raise MalformedRecord(path, chunk_at, f"a record is cut short, {pos} bytes into the chunk")
        opcode = records[pos]
        (length,) = _U64.unpack_from(records, pos + 1)
        if opcode == 0:
            raise MalformedRecord(path, chunk_at, f"a record of opcode 0, {pos} bytes into the chunk")
        if length > end - pos - 9:
            raise MalformedRecord(path, chunk_at, f"a record of {length} bytes runs past the end of the chunk, "
                                                  f"{pos} bytes into it")
        yield pos, opcode, view[pos + 9:pos + 9 + length]
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


_FOOTER = struct.Struct("<BQQQI")  # opcode, record length (20), summary start, summary offset start, summary crc
_CHUNK_FIXED = struct.Struct("<QQQII")  # start, end, uncompressed size, uncompressed crc, compression length
_MESSAGE_BODY = 22  # channel, sequence, log time, publish time: the data follows
_SUMMARY_RECORDS = (Opcode.SCHEMA, Opcode.CHANNEL, Opcode.STATISTICS, Opcode.CHUNK_INDEX)


def _parsed(kind: Any, body: bytes | memoryview, error: Callable[[str], MalformedRecord]) -> Any:
    """A record of the ``mcap`` library's ``kind`` read from ``body``; ``error`` makes the line when it does not
    parse."""
    from mcap.exceptions import McapError

    try:
        return kind.read(ReadDataStream(io.BytesIO(body)))
    except (McapError, struct.error, UnicodeDecodeError) as exc:
        raise error(f"a {kind.__name__.lower()} record does not parse ({type(exc).__name__})") from None


class McapBagReader(ChunkedFile):
    """Reads an MCAP (ros1 profile) file in file order, or through its index; one cut short reads up to its
    last complete record.

    The summary section (schemas, channels, statistics, chunk indexes) is read record by record with every
    length checked, and nothing in a chunk is needed for it. Every other length is checked against what holds
    it before anything is read, chunks are decompressed within their declared size
    (:mod:`rostui.core.bag.inflate`) and checked against their CRC: a record that breaks any of that is a
    :class:`~rostui.core.bag.model.MalformedRecord`, an error in a file with a summary, and the end of what is
    readable in one without (a record of opcode 0, as a run of zeros starts, stops it at once).
    """

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
        self.profile = self._read_profile()
        """The header record's profile (``ros1``, ``ros2``...); empty when it names none or cannot be read."""
        self.file.seek(0)
        self.connections: dict[int, Connection] = {}
        self.truncated = ""
        self._md5s: dict[int, str] = {}  # by schema id (0: no schema), for channels without md5sum metadata
        self._scanned_schemas: dict[int, Any] = {}
        """Schema records met while reading chunks: a later chunk's channel may use one an earlier chunk held."""
        try:
            self._summary = self._read_summary()
        except BaseException:
            self.file.close()
            raise

    def close(self) -> None:
        """Close the file."""
        self.file.close()

    def _read_profile(self) -> str:
        """The profile string of the header record right after the magic (read within 256 bytes)."""
        head = self.file.read(9 + 4 + 256)
        if len(head) < 13 or head[0] != Opcode.HEADER:
            return ""
        length = _U32.unpack_from(head, 9)[0]
        profile = head[13:13 + length].decode("ascii", "replace") if length <= 256 else ""
        return profile if profile.isprintable() and "\ufffd" not in profile else ""

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

    def _error(self, at: int) -> Callable[[str], MalformedRecord]:
        """What makes the error line of a record at byte ``at``."""
        return lambda what: MalformedRecord(self.path, at, what)

    def _read(self, at: int, length: int) -> bytes:
        """``length`` bytes from byte ``at`` (the caller has checked they lie in the file)."""
        self.file.seek(at)
        data: bytes = self.file.read(length)
        if len(data) < length:
            raise MalformedRecord(self.path, at, "a record is cut short")
        return data

    def _read_summary(self) -> Any:
        """The summary section, or None when the file has none (not closed, or closed without one) or it does
        not read (``truncated`` then says why)."""
        footer_at = self.size - len(MAGIC) - _FOOTER.size
        if footer_at < len(MAGIC):
            return None
        tail = self._read(footer_at, _FOOTER.size + len(MAGIC))
        opcode, length, summary_start, offsets_start, crc = _FOOTER.unpack_from(tail)
        if tail[_FOOTER.size:] != MAGIC or opcode != Opcode.FOOTER or length != _FOOTER.size - 9:
            return None
        if summary_start == 0:
            return None
        try:
            if not len(MAGIC) <= summary_start <= footer_at:
                raise MalformedRecord(self.path, footer_at, f"the footer places the summary at byte {summary_start}")
            return self._summary_records(summary_start, footer_at, crc, tail[:1 + 8 + 16])
        except MalformedRecord as exc:
            self.truncated = f"its summary cannot be read ({exc.where})"
            return None

    def _summary_records(self, start: int, end: int, crc: int, footer_head: bytes) -> Any:
        """The schemas, channels, statistics and chunk indexes of the summary section ``[start, end)``, each
        record read on its own; the section's CRC checked when the footer gives one."""
        from mcap.summary import Summary

        summary = Summary()
        computed = 0
        pos = start
        while pos < end:
            if end - pos < 9:
                raise MalformedRecord(self.path, pos, "a summary record is cut short")
            head = self._read(pos, 9)
            opcode = head[0]
            (length,) = _U64.unpack_from(head, 1)
            if length > end - pos - 9:
                raise MalformedRecord(self.path, pos, f"a summary record of {length} bytes runs past the summary")
            body = self._read(pos + 9, length) if crc or opcode in _SUMMARY_RECORDS else b""
            computed = zlib.crc32(body, zlib.crc32(head, computed)) if crc else 0
            error = self._error(pos)
            if opcode == Opcode.SCHEMA:
                schema = _parsed(Schema, body, error)
                summary.schemas[schema.id] = schema
            elif opcode == Opcode.CHANNEL:
                channel = _parsed(Channel, body, error)
                summary.channels[channel.id] = channel
            elif opcode == Opcode.STATISTICS:
                summary.statistics = _parsed(Statistics, body, error)
            elif opcode == Opcode.CHUNK_INDEX:
                summary.chunk_indexes.append(_parsed(ChunkIndex, body, error))
            pos += 9 + length
        if crc and zlib.crc32(footer_head, computed) != crc:
            raise MalformedRecord(self.path, start, "the summary does not match its CRC")
        return summary

    @property
    def closed_properly(self) -> bool:
        """True when the file ends with a summary section (the writer finished it)."""
        return self._summary is not None

    def _stop(self, exc: MalformedRecord) -> None:
        """A malformed record ends what can be read: an error in a file with a summary; in one without, the
        end of what is readable (``truncated`` says where)."""
        if self.closed_properly:
            raise exc
        self.truncated = exc.where

    def _records(self) -> Iterator[tuple[int, int, int]]:
        """``(position, opcode, body length)`` of each record of the data section, up to its end record; a
        record that does not fit in the file, or of opcode 0, is a MalformedRecord."""
        pos = len(MAGIC)
        while pos < self.size:
            if self.size - pos < 9:
                raise MalformedRecord(self.path, pos, "a record is cut short")
            head = self._read(pos, 9)
            opcode = head[0]
            (length,) = _U64.unpack_from(head, 1)
            if opcode == 0:
                raise MalformedRecord(self.path, pos, "a record of opcode 0 (reserved: never written)")
            if length > self.size - pos - 9:
                raise MalformedRecord(self.path, pos, f"a record of {length} bytes runs past the end of the file")
            yield pos, opcode, length
            if opcode in (Opcode.DATA_END, Opcode.FOOTER):
                return
            pos += 9 + length

    def _chunk_at(self, at: int, length: int | None = None) -> ChunkPlace:
        """Where the chunk record at byte ``at`` keeps its records, and what it declares of them."""
        if length is None:
            if not 0 <= at <= self.size - 9:
                raise MalformedRecord(self.path, at, "the index places a chunk past the end of the file")
            head = self._read(at, 9)
            (length,) = _U64.unpack_from(head, 1)
            if head[0] != OP_CHUNK:
                raise MalformedRecord(self.path, at, "the index places a chunk here")
            if length > self.size - at - 9:
                raise MalformedRecord(self.path, at, f"a record of {length} bytes runs past the end of the file")
        if length < _CHUNK_FIXED.size + 8:
            raise MalformedRecord(self.path, at, f"a chunk record of {length} bytes")
        fixed = self._read(at + 9, _CHUNK_FIXED.size)
        _start, _end, plain_size, crc, name_length = _CHUNK_FIXED.unpack(fixed)
        if name_length > length - _CHUNK_FIXED.size - 8:
            raise MalformedRecord(self.path, at, f"a chunk's compression name of {name_length} bytes runs past "
                                                 "the chunk")
        rest = self._read(at + 9 + _CHUNK_FIXED.size, name_length + 8)
        try:
            compression = rest[:name_length].decode()
        except UnicodeDecodeError:
            raise MalformedRecord(self.path, at, "a chunk's compression name is not UTF-8 text") from None
        (stored,) = _U64.unpack_from(rest, name_length)
        data_at = at + 9 + _CHUNK_FIXED.size + name_length + 8
        if stored > at + 9 + length - data_at:
            raise MalformedRecord(self.path, at, f"a chunk's {stored} bytes of records run past the chunk")
        return ChunkPlace(at, data_at, stored, compression or "none", plain_size, crc)

    def _message(self, body: bytes | memoryview, error: Callable[[str], MalformedRecord]) -> tuple[Connection, int]:
        """The connection and log time of a message record's body."""
        if len(body) < _MESSAGE_BODY:
            raise error(f"a message record of {len(body)} bytes")
        channel_id, _seq, log_time = _MESSAGE_FIELDS.unpack_from(body)
        conn = self.connections.get(channel_id)
        if conn is None:
            raise error(f"a message on channel {channel_id}, which no channel record declares")
        return conn, log_time

    def _take_definition(self, opcode: int, body: bytes | memoryview, schemas: dict[int, Any],
                         error: Callable[[str], MalformedRecord]) -> None:
        """Remember a schema record; turn a channel record into a connection."""
        if opcode == Opcode.SCHEMA:
            schema = _parsed(Schema, body, error)
            schemas[schema.id] = schema
        elif opcode == Opcode.CHANNEL:
            channel = _parsed(Channel, body, error)
            if channel.id not in self.connections:
                self.connections[channel.id] = self._connection(channel, schemas.get(channel.schema_id))

    def _inner_error(self, chunk_at: int, pos: int) -> Callable[[str], MalformedRecord]:
        """What makes the error line of the record ``pos`` bytes into the chunk at ``chunk_at``."""
        return lambda what: MalformedRecord(self.path, chunk_at, f"{what}, {pos} bytes into the chunk")

    def _own_index_parts(self) -> Iterator[ChunkEntries] | None:
        # the summary's chunk indexes and the message indexes after each chunk (a chunk without message
        # indexes is read instead); None without a summary, or with messages outside chunks
        summary = self._summary
        if summary is None:
            return None
        stats = summary.statistics
        if not summary.chunk_indexes and (stats is None or stats.message_count):
            return None
        return self._file_index_parts(summary)

    def _file_index_parts(self, summary: Any) -> Iterator[ChunkEntries]:
        for cid, channel in summary.channels.items():
            self.connections[cid] = self._connection(channel, summary.schemas.get(channel.schema_id))
        self.chunk_table = []
        self._index_spans: list[tuple[int, int] | None] = []
        for number, index in enumerate(sorted(summary.chunk_indexes, key=lambda i: i.chunk_start_offset)):
            self.chunk_table.append(self._chunk_at(index.chunk_start_offset))
            if not index.message_index_offsets:
                self._index_spans.append(None)
                yield self._chunk_part(number)
                continue
            start = index.chunk_start_offset + index.chunk_length
            if not 0 <= start <= self.size or index.message_index_length > self.size - start:
                raise MalformedRecord(self.path, index.chunk_start_offset, "the index places the chunk's message "
                                                                           "indexes past the end of the file")
            self._index_spans.append((start, index.message_index_length))
            yield from self._message_indexes(number, start, index.message_index_length)

    def _message_indexes(self, number: int, start: int, length: int) -> list[ChunkEntries]:
        """The entries of the message index records in the ``length`` bytes at ``start`` (chunk ``number``'s)."""
        import numpy as np

        parts: list[ChunkEntries] = []
        block = self._read(start, length)
        for _at, opcode, body in _walk(block, self.path, start):
            if opcode != Opcode.MESSAGE_INDEX:
                continue
            error = self._error(start)
            if len(body) < 6:
                raise error(f"a message index record of {len(body)} bytes")
            channel_id = struct.unpack_from("<H", body)[0]
            (records_length,) = _U32.unpack_from(body, 2)
            if records_length % 16 or records_length > len(body) - 6:
                raise error(f"a message index record's {records_length} bytes of entries do not fit it")
            if channel_id not in self.connections:
                raise error(f"a message index of channel {channel_id}, which no channel record declares")
            entries = np.frombuffer(body, dtype=_INDEX_ENTRY, count=records_length // 16, offset=6)
            parts.append(ChunkEntries(entries["time"].astype(np.int64),
                                      np.full(len(entries), channel_id, dtype=np.uint32),
                                      entries["offset"], number))
        return parts

    def _chunk_index_parts(self, number: int) -> list[ChunkEntries]:
        span = self._index_spans[number]
        return [self._chunk_part(number)] if span is None else self._message_indexes(number, *span)

    def _scanned_chunk_part(self, number: int) -> ChunkEntries:
        return self._chunk_part(number)

    def _chunk_part(self, number: int) -> ChunkEntries:
        """The entries of chunk ``number`` found by reading its records (schemas and channels taken in)."""
        times, conn_ids, offsets = [], [], []
        schemas = self._scanned_schemas
        chunk_at = self.chunk_table[number].record_at
        for at, opcode, body in _walk(self.cache.get(number), self.path, chunk_at):
            error = self._inner_error(chunk_at, at)
            if opcode == OP_MESSAGE:
                conn, log_time = self._message(body, error)
                times.append(log_time)
                conn_ids.append(conn.id)
                offsets.append(at)
            else:
                self._take_definition(opcode, body, schemas, error)
        return ChunkEntries(times, conn_ids, offsets, number)

    def _scan_parts(self, progress: Callable[[int], None] | None) -> Iterator[ChunkEntries]:
        loose: tuple[list[int], list[int], list[int]] = ([], [], [])
        schemas = self._scanned_schemas
        try:
            for pos, opcode, length in self._records():
                if opcode == OP_CHUNK:
                    self.chunk_table.append(self._chunk_at(pos, length))
                    try:
                        part = self._chunk_part(len(self.chunk_table) - 1)
                    except MalformedRecord:
                        self.chunk_table.pop()
                        raise
                    yield part
                    if progress is not None:
                        progress(pos + 9 + length)
                elif opcode == OP_MESSAGE:
                    conn, log_time = self._message(self._read(pos + 9, min(length, _MESSAGE_BODY)),
                                                   self._error(pos))
                    loose[0].append(log_time)
                    loose[1].append(conn.id)
                    loose[2].append(pos)
                elif opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
                    self._take_definition(opcode, self._read(pos + 9, length), schemas, self._error(pos))
        except MalformedRecord as exc:
            self._stop(exc)
        if loose[0]:
            yield ChunkEntries(*loose, NO_CHUNK)

    def payload(self, chunk: int, offset: int) -> bytes:
        """The serialised message whose record starts at ``offset`` of chunk ``chunk``'s records (or of
        the file, for a message outside any chunk), as an index entry locates it; MalformedRecord when no
        message record fits there."""
        if chunk == NO_CHUNK:
            if not 0 <= offset <= self.size - 9:
                raise MalformedRecord(self.path, offset, "the index places a message past the end of the file")
            head = self._read(offset, 9)
            (length,) = _U64.unpack_from(head, 1)
            if head[0] != OP_MESSAGE or not _MESSAGE_BODY <= length <= self.size - offset - 9:
                raise MalformedRecord(self.path, offset, "the index places a message here")
            return self._read(offset + 9, length)[_MESSAGE_BODY:]
        records = self.cache.get(chunk)
        fits = offset <= len(records) - 9
        length = _U64.unpack_from(records, offset + 1)[0] if fits else 0
        if not fits or records[offset] != OP_MESSAGE or not _MESSAGE_BODY <= length <= len(records) - offset - 9:
            raise MalformedRecord(self.path, self.chunk_table[chunk].record_at,
                                  f"the index places a message {offset} bytes into the chunk")
        return records[offset + 9 + _MESSAGE_BODY:offset + 9 + length]

    def messages(self) -> Iterator[tuple[Connection, int, bytes]]:
        """``(connection, time_ns, data)`` in file order; stops at the first incomplete record."""
        schemas: dict[int, Any] = {}
        try:
            for pos, opcode, length in self._records():
                if opcode == OP_CHUNK:
                    place = self._chunk_at(pos, length)
                    for at, inner, body in _walk(self.read_chunk(place), self.path, pos):
                        error = self._inner_error(pos, at)
                        if inner == OP_MESSAGE:
                            conn, log_time = self._message(body, error)
                            yield conn, log_time, bytes(body[_MESSAGE_BODY:])
                        else:
                            self._take_definition(inner, body, schemas, error)
                elif opcode == OP_MESSAGE:
                    loose = self._read(pos + 9, length)
                    conn, log_time = self._message(loose, self._error(pos))
                    yield conn, log_time, loose[_MESSAGE_BODY:]
                elif opcode in (Opcode.SCHEMA, Opcode.CHANNEL):
                    self._take_definition(opcode, self._read(pos + 9, length), schemas, self._error(pos))
        except MalformedRecord as exc:
            self._stop(exc)

    def summary(self) -> BagSummary:
        """Counts and times from the summary section (no chunk decompressed), or from reading every record
        when there is none."""
        out = BagSummary(self.path, "mcap", f"0 ({self.profile or 'no'} profile)", self.size,
                         closed=self.closed_properly)
        summary = self._summary
        if summary is not None:
            for cid, channel in summary.channels.items():
                self.connections[cid] = self._connection(channel, summary.schemas.get(channel.schema_id))
            for index in summary.chunk_indexes:
                out.add_chunk(index.compression or "none", index.uncompressed_size, index.compressed_size)
            stats = summary.statistics
            if stats is not None:
                out.counts = dict(stats.channel_message_counts)
                out.start_ns, out.end_ns = stats.message_start_time, stats.message_end_time
            else:
                self._count_indexed(out)
        else:
            self._count_messages(out)
        out.problem = self.truncated
        out.connections = [self.connections[c] for c in sorted(self.connections)]
        return out

    def _count_indexed(self, out: BagSummary) -> None:
        """Counts and times from the message indexes (a summary without statistics), chunk by chunk."""
        infos = self.chunk_infos()
        if infos is None:
            self._count_messages(out)
            return
        for conn_id, n in zip(infos.pair_conns.tolist(), infos.pair_counts.tolist()):
            out.counts[conn_id] = out.counts.get(conn_id, 0) + n
        if len(infos):
            out.start_ns, out.end_ns = int(infos.starts.min()), int(infos.ends.max())

    def _count_messages(self, out: BagSummary) -> None:
        """Counts and times from reading every record."""
        first = last = None
        for conn, t, _data in self.messages():
            out.counts[conn.id] = out.counts.get(conn.id, 0) + 1
            first = t if first is None else min(first, t)
            last = t if last is None else max(last, t)
        out.start_ns, out.end_ns = first or 0, last or 0
