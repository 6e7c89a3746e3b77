"""MCAP files in the ROS 1 profile (schema encoding ``ros1msg``, message encoding ``ros1``), via ``mcap``.

Each bag connection is one MCAP channel; its schema is the message type with
its full definition; the channel metadata keeps md5sum, callerid and latching.
The writer closes a chunk at least every ``max_chunk_age`` seconds so a killed
recording keeps all but its last moments. The reader uses the summary when the
file was closed and otherwise streams records up to the first incomplete one.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from typing import Any

from rostui.core.bag.model import BagError, BagSummary, Connection

MAGIC = b"\x89MCAP0\r\n"
COMPRESSIONS = ("none", "lz4", "zstd")
PROFILE = "ros1"


class _GuardedFile:
    """The writer's output file: remembers where the last complete flush ended."""

    def __init__(self, path: str) -> None:
        self.raw = open(path, "wb", buffering=0)
        self.pos = 0

    def write(self, data: Any) -> int:
        view = memoryview(data)
        total = len(view)
        while view:
            n = self.raw.write(view)
            self.pos += n
            view = view[n:]
        return total

    def tell(self) -> int:
        return self.pos

    def flush(self) -> None:
        """Nothing is buffered here."""

    def cut(self, offset: int) -> None:
        """Drop everything after ``offset``."""
        try:
            os.ftruncate(self.raw.fileno(), offset)
            self.raw.seek(offset)
        except OSError:
            pass
        self.pos = offset

    def close(self) -> None:
        self.raw.close()


class McapBagWriter:
    """Writes an MCAP (ros1 profile) file; ``close()`` writes the summary (indexes, statistics)."""

    def __init__(self, path: str, *, compression: str = "none", chunk_bytes: int = 768 * 1024,
                 max_chunk_age: float = 0.5) -> None:
        from mcap.writer import CompressionType, Writer

        if compression not in COMPRESSIONS:
            raise BagError(f"an MCAP file cannot use {compression} compression (none, lz4 or zstd)")
        kind = {"none": CompressionType.NONE, "lz4": CompressionType.LZ4, "zstd": CompressionType.ZSTD}[compression]
        self.path = path
        self.compression = compression
        self.max_chunk_age = max_chunk_age
        self.out = _GuardedFile(path)
        self.writer = Writer(self.out, chunk_size=chunk_bytes, compression=kind)  # type: ignore[arg-type]
        self.writer.start(profile=PROFILE, library="rostui")
        self.good_end = self.out.pos
        self.connections: dict[int, Connection] = {}
        self._channel: dict[int, int] = {}
        self._schema: dict[tuple[str, str], int] = {}
        self._pending = 0
        self._chunk_started = 0.0
        self._open_counts: dict[int, int] = {}
        self._open_times: list[int] = []
        self.committed_counts: dict[int, int] = {}
        self.committed_times: list[int] = []
        self.failed = False
        self.closed = False

    @property
    def size(self) -> int:
        """Bytes written so far (plus what the open chunk holds)."""
        return self.out.pos + self._pending

    def add_connection(self, conn: Connection) -> None:
        """Register a schema (once per type) and a channel for this connection."""
        key = (conn.type, conn.definition)
        schema_id = self._schema.get(key)
        if schema_id is None:
            schema_id = self.writer.register_schema(conn.type, "ros1msg", conn.definition.encode())
            self._schema[key] = schema_id
        metadata = {"md5sum": conn.md5sum, "callerid": conn.callerid, "latching": "1" if conn.latching else "0"}
        self._channel[conn.id] = self.writer.register_channel(conn.topic, "ros1", schema_id, metadata)
        self.connections[conn.id] = conn

    def write(self, conn_id: int, time_ns: int, data: bytes) -> None:
        """Append one message (log and publish time are the receive time)."""
        if not self._pending:
            self._chunk_started = time.monotonic()
        try:
            self.writer.add_message(self._channel[conn_id], time_ns, data, time_ns)
        except OSError:
            self._rollback()
            raise
        self._pending += len(data) + 64
        channel = self._channel[conn_id]
        self._open_counts[channel] = self._open_counts.get(channel, 0) + 1
        self._open_times.append(time_ns)
        if self.out.pos != self.good_end:  # the library closed the chunk, this message included
            self._commit()

    def _commit(self) -> None:
        """The open chunk reached the file: its messages count."""
        self.good_end = self.out.pos
        self._pending = 0
        for channel, n in self._open_counts.items():
            self.committed_counts[channel] = self.committed_counts.get(channel, 0) + n
        if self._open_times:
            self.committed_times = [min(self._open_times + self.committed_times),
                                    max(self._open_times + self.committed_times)]
        self._open_counts, self._open_times = {}, []

    def flush_if_old(self) -> None:
        """Close the open chunk when it is older than ``max_chunk_age``."""
        if self._pending and time.monotonic() - self._chunk_started >= self.max_chunk_age:
            self.flush()

    def flush(self) -> None:
        """Write the open chunk and its message indexes."""
        try:
            self.writer.flush()
        except OSError:
            self._rollback()
            raise
        self._commit()

    def _rollback(self) -> None:
        """Cut the chunk that did not fit and make the writer forget it, so its summary stays true."""
        self.out.cut(self.good_end)
        self._pending = 0
        self._open_counts, self._open_times = {}, []
        self.failed = True
        builder = getattr(self.writer, "_Writer__chunk_builder", None)
        stats = getattr(self.writer, "_Writer__statistics", None)
        if builder is None or stats is None:
            return
        builder.reset()
        stats.channel_message_counts.clear()
        stats.channel_message_counts.update(self.committed_counts)
        stats.message_count = sum(self.committed_counts.values())
        stats.message_start_time, stats.message_end_time = (self.committed_times or [0, 0])[:2]

    def close(self) -> None:
        """Write the summary section and footer; on a full disk end the file without a summary instead."""
        if self.closed:
            return
        self.closed = True
        try:
            try:
                if self.failed:
                    self.writer.flush()  # nothing is open after a rollback; keeps the stream position true
                self.writer.finish()
            except OSError:
                self._rollback()
                self._end_without_summary()
                raise
        finally:
            self.out.close()

    def _end_without_summary(self) -> None:
        """DataEnd, a Footer pointing at no summary, and the closing magic: a valid file without indexes."""
        from mcap.data_stream import RecordBuilder
        from mcap.records import DataEnd, Footer

        builder = RecordBuilder()
        DataEnd(0).write(builder)
        Footer(0, 0, 0).write(builder)
        try:
            self.out.write(builder.end() + MAGIC)
        except OSError:
            self.out.cut(self.good_end)


def _connection_of(channel: Any, schema: Any) -> Connection:
    meta = dict(channel.metadata or {})
    definition = schema.data.decode("utf-8", "replace") if schema is not None else ""
    return Connection(channel.id, channel.topic, schema.name if schema is not None else "",
                      meta.get("md5sum", ""), definition, meta.get("callerid", ""), meta.get("latching", "0") == "1")


class McapBagReader:
    """Reads an MCAP (ros1 profile) file; one cut short reads up to its last complete record."""

    def __init__(self, path: str) -> None:
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
        self._summary = self._read_summary()

    def close(self) -> None:
        """Close the file."""
        self.file.close()

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
                    self.connections[record.id] = _connection_of(record, schemas.get(record.schema_id))

    def summary(self) -> BagSummary:
        """Counts and times from the summary section, or from reading every record when there is none."""
        out = BagSummary(self.path, "mcap", "0 (ros1 profile)", self.size, closed=self.closed_properly)
        summary = self._summary
        if summary is not None and summary.statistics is not None:
            for cid, channel in summary.channels.items():
                self.connections[cid] = _connection_of(channel, summary.schemas.get(channel.schema_id))
            stats = summary.statistics
            out.counts = {cid: n for cid, n in stats.channel_message_counts.items()}
            out.start_ns, out.end_ns = stats.message_start_time, stats.message_end_time
            for index in summary.chunk_indexes:
                kind = index.compression or "none"
                out.chunk_compression[kind] = out.chunk_compression.get(kind, 0) + 1
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
