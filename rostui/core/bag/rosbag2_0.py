"""rosbag v2.0 ``.bag`` files: a chunked writer that survives a kill, and a sequential reader.

The writer closes a chunk (and writes its index records) whenever it holds
``chunk_bytes`` or is older than ``max_chunk_age`` seconds, so a process killed
mid-recording leaves a file whose complete chunks all read back. The reader
walks records in file order, so it reads indexed and unindexed files alike and
stops cleanly at the first incomplete record.
"""

from __future__ import annotations

import bz2
import os
import struct
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any, BinaryIO

from rostui.core.bag.fileindex import NO_CHUNK, ChunkedFile, ChunkEntries, FileIndex
from rostui.core.bag.iov import Parts
from rostui.core.bag.model import BagError, BagSummary, Connection
from rostui.core.bag.sink import AppendFile, open_append

MAGIC = b"#ROSBAG V2.0\n"
FILE_HEADER_LENGTH = 4096
#: The file header record as rosbag writes it: header length, header, data length, data padding the header
#: to FILE_HEADER_LENGTH.  rosbag rewrites it in place (reindex, append), so it must be exactly this size.
FILE_HEADER_RECORD_SIZE = 4 + FILE_HEADER_LENGTH + 4
OP_MSG_DATA, OP_FILE_HEADER, OP_INDEX_DATA, OP_CHUNK, OP_CHUNK_INFO, OP_CONNECTION = 2, 3, 4, 5, 6, 7
COMPRESSIONS = ("none", "bz2", "lz4")
_U32 = struct.Struct("<I")
PAD_FIELD = "pad"
"""A chunk header field of spaces that puts the chunk's big message on a block boundary, so the recorder's
direct writes take it without a copy (see :mod:`rostui.core.bag.sink`)."""
_TIME = struct.Struct("<II")
_INDEX_ENTRY = [("sec", "<u4"), ("nsec", "<u4"), ("offset", "<u4")]
"""An index-data entry (version 1): time and the message record's offset in its decompressed chunk."""


def _field(name: str, value: bytes) -> bytes:
    item = name.encode() + b"=" + value
    return _U32.pack(len(item)) + item


def _header(fields: dict[str, bytes]) -> bytes:
    body = b"".join(_field(k, v) for k, v in fields.items())
    return _U32.pack(len(body)) + body


def _record(fields: dict[str, bytes], data: bytes) -> bytes:
    return _header(fields) + _U32.pack(len(data)) + data


def _time_bytes(ns: int) -> bytes:
    return _TIME.pack(ns // 1_000_000_000, ns % 1_000_000_000)


def _time_ns(raw: bytes) -> int:
    sec: int
    nsec: int
    sec, nsec = _TIME.unpack(raw)
    return sec * 1_000_000_000 + nsec


def parse_header(buf: bytes | memoryview) -> dict[str, bytes]:
    """``name=value`` fields of a record header (values stay bytes)."""
    fields: dict[str, bytes] = {}
    pos, end = 0, len(buf)
    while pos + 4 <= end:
        (length,) = _U32.unpack_from(buf, pos)
        pos += 4
        if pos + length > end:
            raise BagError("corrupt record header (field runs past the header)")
        item = bytes(buf[pos:pos + length])
        pos += length
        name, sep, value = item.partition(b"=")
        if not sep:
            raise BagError("corrupt record header (field without '=')")
        fields[name.decode("latin-1")] = value
    return fields


def _compress(kind: str, data: bytes) -> bytes:
    if kind == "bz2":
        return bz2.compress(data)
    if kind == "lz4":
        return _roslz4_frame(data)
    return data


def _roslz4_frame(data: bytes) -> bytes:
    """``data`` as one lz4 frame in the form roslz4 (rosbag's lz4 library) writes, the only form its reader
    takes: independent 1 MiB blocks, no block checksums, no content size, a content checksum.

    roslz4 refuses linked blocks, python-lz4's default, which a chunk over one block needs.  The streaming
    compressor keeps the 1 MiB block size id for small chunks too (``lz4.frame.compress`` would lower it), and
    one ``compress`` call cuts blocks at every 1 MiB of the chunk, as roslz4 does.
    """
    import lz4.frame

    frame = lz4.frame.LZ4FrameCompressor(block_size=lz4.frame.BLOCKSIZE_MAX1MB, block_linked=False,
                                         block_checksum=False, content_checksum=True, auto_flush=True)
    packed: bytes = frame.begin() + frame.compress(data) + frame.flush()
    return packed


def _decompress(kind: str, data: bytes) -> bytes:
    if kind == "none":
        return data
    if kind == "bz2":
        return bz2.decompress(data)
    if kind == "lz4":
        import lz4.frame

        unpacked: bytes = lz4.frame.decompress(data)
        return unpacked
    raise BagError(f"unsupported chunk compression '{kind}'")


@dataclass(frozen=True)
class Resumed:
    """An existing ``.bag`` a :class:`BagWriter` goes on writing: the file opened at the end of its last
    complete chunk (the old index cut off), its connections and its chunks' infos
    ``(position, start_ns, end_ns, {conn_id: count})`` (:mod:`rostui.core.bag.bag_append` finds them)."""

    out: AppendFile
    connections: dict[int, Connection]
    chunks: list[tuple[int, int, int, dict[int, int]]]


class BagWriter:
    """Writes a rosbag v2.0 file; ``close()`` writes the index and the final file header.

    With ``direct`` the file is written around the page cache where it can be (see
    :mod:`rostui.core.bag.sink`); the recorder asks for that.
    """

    def __init__(self, path: str, *, compression: str = "none", chunk_bytes: int = 768 * 1024,
                 max_chunk_age: float = 0.5, direct: bool = False, resume: Resumed | None = None) -> None:
        if compression not in COMPRESSIONS:
            raise BagError(f"a .bag file cannot use {compression} compression (none, bz2 or lz4)")
        self.path = path
        self.compression = compression
        self.chunk_bytes = chunk_bytes
        self.max_chunk_age = max_chunk_age
        self.out = open_append(path, direct) if resume is None else resume.out
        self.connections: dict[int, Connection] = {} if resume is None else dict(resume.connections)
        self.chunk_infos: list[tuple[int, int, int, dict[int, int]]] = [] if resume is None else list(resume.chunks)
        self.closed = False
        self.good_end = 0
        self._chunk = Parts()
        self._chunk_started = 0.0
        self._chunk_index: dict[int, list[tuple[int, int]]] = {}
        self._chunk_new_conns: set[int] = set()
        self._written_conns: set[int] = set()
        if resume is not None:
            # the old chunks hold these connections' records: new chunks do not repeat them, as rosbag appends
            self._written_conns = set(self.connections)
            self.good_end = self.out.end
            return
        self._write_all([MAGIC, self._file_header(0, 0, 0)])
        self.good_end = len(MAGIC) + FILE_HEADER_RECORD_SIZE

    def _file_header(self, index_pos: int, conn_count: int, chunk_count: int) -> bytes:
        fields = {"op": bytes([OP_FILE_HEADER]), "index_pos": struct.pack("<Q", index_pos),
                  "conn_count": _U32.pack(conn_count), "chunk_count": _U32.pack(chunk_count)}
        header = _header(fields)
        pad = FILE_HEADER_LENGTH - (len(header) - 4)
        return header + _U32.pack(pad) + b" " * pad

    def _write_all(self, parts: list[Any]) -> None:
        """Append ``parts`` at ``good_end`` (the end of the file)."""
        self.out.append(parts)

    @property
    def size(self) -> int:
        """Bytes written so far, including the chunk being filled."""
        return self.good_end + self._chunk.size

    @property
    def buffered(self) -> int:
        """Bytes of the open chunk: 0 when no message buffer passed to :meth:`write` is still referenced."""
        return self._chunk.size

    def add_connection(self, conn: Connection) -> None:
        """Declare a connection; its record goes into the next chunk and the index."""
        self.connections[conn.id] = conn

    def _connection_record(self, conn: Connection) -> bytes:
        data = _header({k: v.encode() for k, v in conn.header_fields().items()})[4:]
        return _record({"op": bytes([OP_CONNECTION]), "conn": _U32.pack(conn.id), "topic": conn.topic.encode()},
                       data)

    def write(self, conn_id: int, time_ns: int, data: Any) -> None:
        """Append one message; closes the chunk when it is full or old."""
        if self._chunk.size and self.out.takes_in_place(data):
            self.flush()  # a chunk's padding can line up only its first big message
        chunk = self._chunk
        if not chunk.size:
            self._chunk_started = time.monotonic()
        if conn_id not in self._written_conns:
            chunk.add(self._connection_record(self.connections[conn_id]))
            self._written_conns.add(conn_id)
        self._chunk_index.setdefault(conn_id, []).append((time_ns, chunk.size))
        chunk.add(_header({"op": b"\x02", "conn": _U32.pack(conn_id), "time": _time_bytes(time_ns)})
                  + _U32.pack(len(data)))
        chunk.add(data)
        if chunk.size >= self.chunk_bytes:
            self.flush()

    def flush_if_old(self) -> None:
        """Close the chunk when it is older than ``max_chunk_age`` (called from a timer)."""
        if self._chunk.size and time.monotonic() - self._chunk_started >= self.max_chunk_age:
            self.flush()
        self.out.sync_if_old()

    def flush(self) -> None:
        """Write the open chunk and its index records to the file."""
        if not self._chunk.size:
            return
        times = [t for entries in self._chunk_index.values() for t, _ in entries]
        start, end = min(times), max(times)
        plain_size = self._chunk.size
        if self.compression == "none":
            body = self._chunk.buffers()
            stored = plain_size
        else:
            packed = _compress(self.compression, b"".join(self._chunk.buffers()))
            body = [packed]
            stored = len(packed)
        fields = {"op": bytes([OP_CHUNK]), "compression": self.compression.encode(), "size": _U32.pack(plain_size)}
        parts = [_header(fields), _U32.pack(stored), *body]
        pad = self.out.lend_padding(parts, len(_field(PAD_FIELD, b"")))
        if pad:
            # readers look fields up by name and skip the rest (rosbag's own file header is padded in its data)
            fields[PAD_FIELD] = b" " * (pad - len(_field(PAD_FIELD, b"")))
            parts[0] = _header(fields)
        counts: dict[int, int] = {}
        for conn_id, entries in self._chunk_index.items():
            counts[conn_id] = len(entries)
            data = b"".join(_time_bytes(t) + _U32.pack(off) for t, off in entries)
            parts.append(_record({"op": bytes([OP_INDEX_DATA]), "ver": _U32.pack(1), "conn": _U32.pack(conn_id),
                                  "count": _U32.pack(len(entries))}, data))
        chunk_pos = self.good_end
        try:
            self._write_all(parts)
        except OSError:
            self._rollback()
            raise
        self.good_end += sum(len(p) for p in parts)
        self.chunk_infos.append((chunk_pos, start, end, counts))
        self._chunk.clear()
        self._chunk_index = {}

    def _rollback(self) -> None:
        """Cut a partly written chunk off, so the file ends with complete records."""
        self.out.cut(self.good_end)
        self.good_end = self.out.end
        self._chunk.clear()
        self._chunk_index = {}
        self._written_conns = {c for info in self.chunk_infos for c in info[3]}

    def close(self) -> None:
        """Write the last chunk, the connection and chunk-info index, and the final file header.

        When the disk is full the last chunk is dropped so the index still fits;
        if even the index does not fit, the file is left unindexed but readable.
        """
        if self.closed:
            return
        self.closed = True
        try:
            try:
                self.flush()
            except OSError:
                pass
            index_pos = self.good_end
            used = {c for info in self.chunk_infos for c in info[3]}
            parts = [self._connection_record(self.connections[c]) for c in sorted(used)]
            for pos, start, end, counts in self.chunk_infos:
                data = b"".join(_U32.pack(c) + _U32.pack(n) for c, n in counts.items())
                parts.append(_record({"op": bytes([OP_CHUNK_INFO]), "ver": _U32.pack(1),
                                      "chunk_pos": struct.pack("<Q", pos), "start_time": _time_bytes(start),
                                      "end_time": _time_bytes(end), "count": _U32.pack(len(counts))}, data))
            try:
                self._write_all(parts)
                self.out.rewrite(self._file_header(index_pos, len(used), len(self.chunk_infos)), len(MAGIC))
            except OSError:
                self._rollback()
                raise
        finally:
            self.out.close()


class BagReader(ChunkedFile):
    """Reads a rosbag v2.0 file in file order, or through its index; a file cut short reads up to its last
    complete chunk."""

    def __init__(self, path: str) -> None:
        super().__init__()
        self.path = path
        try:
            self.file: BinaryIO = open(path, "rb")
        except OSError as exc:
            raise BagError(f"cannot open {path}: {exc.strerror}") from None
        self.size = os.fstat(self.file.fileno()).st_size
        magic = self.file.read(len(MAGIC))
        if magic != MAGIC:
            self.file.close()
            if magic.startswith(b"#ROSBAG V"):
                raise BagError(f"{path}: rosbag format {magic[9:].strip().decode(errors='replace')} is not "
                               "supported (only 2.0)")
            raise BagError(f"{path} is not a bag file (no '#ROSBAG V2.0' line)")
        try:
            fields, _ = self._read_record()
        except BagError:
            self.file.close()
            raise BagError(f"{path}: the file header is incomplete") from None
        if fields.get("op") != bytes([OP_FILE_HEADER]):
            self.file.close()
            raise BagError(f"{path}: the file header record is missing")
        self.index_pos: int = struct.unpack("<Q", fields["index_pos"])[0]
        count = fields.get("chunk_count", b"")
        self.chunk_count = _U32.unpack(count)[0] if len(count) == 4 else 0
        self.data_start = self.file.tell()
        self.connections: dict[int, Connection] = {}
        self.truncated = ""
        self.last_data_length = 0
        self.record_at = 0
        """Where the record :meth:`_records` yielded last starts."""

    def close(self) -> None:
        """Close the file."""
        self.file.close()

    @property
    def closed_properly(self) -> bool:
        """True when the writer finished the file (index written)."""
        return self.index_pos != 0 and self.index_pos <= self.size

    def _read_record(self, skip_chunk_data: bool = False) -> tuple[dict[str, bytes], bytes]:
        head = self.file.read(4)
        if len(head) < 4:
            raise EOFError
        (hlen,) = _U32.unpack(head)
        raw = self.file.read(hlen)
        if len(raw) < hlen:
            raise BagError("a record header is cut short")
        fields = parse_header(raw)
        dlen_raw = self.file.read(4)
        if len(dlen_raw) < 4:
            raise BagError("a record is cut short")
        (dlen,) = _U32.unpack(dlen_raw)
        self.last_data_length = dlen
        if not (skip_chunk_data and fields.get("op") == bytes([OP_CHUNK])):
            data = self.file.read(dlen)
            if len(data) < dlen:
                raise BagError("a record's data is cut short")
            return fields, data
        if self.file.tell() + dlen > self.size:
            raise BagError("a record's data is cut short")
        self.file.seek(dlen, os.SEEK_CUR)
        return fields, b""

    def _connection(self, fields: dict[str, bytes], data: bytes) -> Connection:
        conn_id = _U32.unpack(fields["conn"])[0]
        info = {k: v.decode("utf-8", "replace") for k, v in parse_header(data).items()}
        conn = Connection(conn_id, fields["topic"].decode(), info.get("type", ""), info.get("md5sum", ""),
                          info.get("message_definition", ""), info.get("callerid", ""),
                          info.get("latching", "0") == "1")
        self.connections.setdefault(conn_id, conn)
        return conn

    def _records(self, with_chunk_data: bool) -> Iterator[tuple[dict[str, bytes], bytes]]:
        self.file.seek(self.data_start)
        while self.file.tell() < self.size:
            at = self.file.tell()
            try:
                fields, data = self._read_record(skip_chunk_data=not with_chunk_data)
            except EOFError:
                return
            except (BagError, struct.error, KeyError) as exc:
                self.truncated = f"{exc} at byte {at}"
                return
            if fields.get("op") == bytes([OP_INDEX_DATA]) and with_chunk_data:
                continue
            self.record_at = at
            yield fields, data

    def _read_index(self) -> FileIndex | None:
        if not self.closed_properly:
            return None
        try:
            return self._read_file_index()
        except (BagError, EOFError, struct.error, KeyError, ValueError):
            return None

    def _read_file_index(self) -> FileIndex:
        self.file.seek(self.index_pos)
        chunk_positions: list[int] = []
        while self.file.tell() < self.size:
            fields, data = self._read_record()
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, data)
            elif op == bytes([OP_CHUNK_INFO]):
                chunk_positions.append(struct.unpack("<Q", fields["chunk_pos"])[0])
        if len(chunk_positions) != self.chunk_count:
            raise BagError(f"the index lists {len(chunk_positions)} of {self.chunk_count} chunks")
        self.chunk_table = []
        parts: list[ChunkEntries] = []
        for number, pos in enumerate(sorted(chunk_positions)):
            self.file.seek(pos)
            fields, _ = self._read_record(skip_chunk_data=True)
            if fields.get("op") != bytes([OP_CHUNK]):
                raise BagError(f"no chunk at byte {pos}")
            end = self.file.tell()
            self.chunk_table.append((end - self.last_data_length, self.last_data_length,
                                      fields.get("compression", b"none").decode()))
            while self.file.tell() < self.size:
                at = self.file.tell()
                fields, data = self._read_record(skip_chunk_data=True)
                if fields.get("op") != bytes([OP_INDEX_DATA]):
                    self.file.seek(at)
                    break
                import numpy as np

                entries = np.frombuffer(data, dtype=_INDEX_ENTRY, count=_U32.unpack(fields["count"])[0])
                times = entries["sec"].astype(np.int64) * 1_000_000_000 + entries["nsec"]
                conn_id = _U32.unpack(fields["conn"])[0]
                parts.append(ChunkEntries(times, np.full(len(entries), conn_id, dtype=np.uint32),
                                          entries["offset"], number))
        return FileIndex.build(parts)

    def scan_index(self, progress: Callable[[int], None] | None = None) -> FileIndex:
        """Where every readable message lies, by reading every chunk once (payloads are not kept).

        ``progress(bytes_read)`` is called after each chunk.
        """
        self.chunk_table = []
        parts: list[ChunkEntries] = []
        loose: list[tuple[int, int, int]] = []
        for fields, data in self._records(with_chunk_data=True):
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, data)
            elif op == bytes([OP_CHUNK]):
                kind = fields["compression"].decode()
                try:
                    plain = _decompress(kind, data)
                except Exception as exc:
                    self.truncated = f"a chunk does not decompress ({exc})"
                    break
                number = len(self.chunk_table)
                self.chunk_table.append((self.file.tell() - len(data), len(data), kind))
                times, conn_ids, offsets = [], [], []
                for conn_id, t, offset in self._chunk_entries(plain):
                    times.append(t)
                    conn_ids.append(conn_id)
                    offsets.append(offset)
                parts.append(ChunkEntries(times, conn_ids, offsets, number))
                if progress is not None:
                    progress(self.file.tell())
            elif op == bytes([OP_MSG_DATA]):
                conn_id = _U32.unpack(fields["conn"])[0]
                if conn_id in self.connections:
                    loose.append((_time_ns(fields["time"]), conn_id, self.record_at))
        if loose:
            parts.append(ChunkEntries([t for t, _, _ in loose], [c for _, c, _ in loose],
                                      [o for _, _, o in loose], NO_CHUNK))
        return FileIndex.build(parts, from_file_index=False)

    def _chunk_entries(self, plain: bytes) -> Iterator[tuple[int, int, int]]:
        """``(conn_id, time_ns, offset)`` of each message record in a decompressed chunk; connection
        records are taken in on the way."""
        view = memoryview(plain)
        pos, end = 0, len(plain)
        while pos + 4 <= end:
            at = pos
            (hlen,) = _U32.unpack_from(view, pos)
            fields = parse_header(view[pos + 4:pos + 4 + hlen])
            pos += 4 + hlen
            (dlen,) = _U32.unpack_from(view, pos)
            pos += 4 + dlen
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, plain[pos - dlen:pos])
            elif op == bytes([OP_MSG_DATA]):
                yield _U32.unpack(fields["conn"])[0], _time_ns(fields["time"]), at

    def _decompress_chunk(self, kind: str, data: bytes) -> bytes:
        return _decompress(kind, data)

    def payload(self, chunk: int, offset: int) -> bytes:
        """The serialised message whose record starts at ``offset`` of chunk ``chunk`` (or of the file,
        for a message outside any chunk), as a :class:`FileIndex` locates it."""
        if chunk == NO_CHUNK:
            self.file.seek(offset)
            return self._read_record()[1]
        plain = self.cache.get(chunk)
        (hlen,) = _U32.unpack_from(plain, offset)
        pos = offset + 4 + hlen
        (dlen,) = _U32.unpack_from(plain, pos)
        return plain[pos + 4:pos + 4 + dlen]

    def messages(self) -> Iterator[tuple[Connection, int, bytes]]:
        """``(connection, time_ns, data)`` in file order, up to the last complete chunk."""
        for fields, data in self._records(with_chunk_data=True):
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, data)
            elif op == bytes([OP_CHUNK]):
                try:
                    plain = _decompress(fields["compression"].decode(), data)
                except BagError:
                    raise
                except Exception as exc:
                    self.truncated = f"a chunk does not decompress ({exc})"
                    return
                yield from self._chunk_messages(plain)
            elif op == bytes([OP_MSG_DATA]):
                conn = self.connections.get(_U32.unpack(fields["conn"])[0])
                if conn is not None:
                    yield conn, _time_ns(fields["time"]), data

    def _chunk_messages(self, plain: bytes) -> Iterator[tuple[Connection, int, bytes]]:
        view = memoryview(plain)
        pos, end = 0, len(plain)
        while pos + 4 <= end:
            (hlen,) = _U32.unpack_from(view, pos)
            fields = parse_header(view[pos + 4:pos + 4 + hlen])
            pos += 4 + hlen
            (dlen,) = _U32.unpack_from(view, pos)
            pos += 4
            data = plain[pos:pos + dlen]
            pos += dlen
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, data)
            elif op == bytes([OP_MSG_DATA]):
                conn = self.connections[_U32.unpack(fields["conn"])[0]]
                yield conn, _time_ns(fields["time"]), data

    def summary(self) -> BagSummary:
        """Counts and times from the index records, without decompressing any chunk.

        Counts and rosbag info's start and end come from the chunk info records when the file has them (as
        rosbag reads them); a file without (not closed) takes them from the index records after each chunk.
        """
        summary = BagSummary(self.path, "rosbag", "2.0", self.size, closed=self.closed_properly)
        index_counts: dict[int, int] = {}
        chunk_spans: list[list[int]] = []
        chunk_infos: list[tuple[int, int, dict[int, int]]] = []
        for fields, data in self._records(with_chunk_data=False):
            op = fields.get("op")
            if op == bytes([OP_CONNECTION]):
                self._connection(fields, data)
            elif op == bytes([OP_CHUNK]):
                size = fields.get("size", b"")
                summary.add_chunk(fields.get("compression", b"none").decode(),
                                  _U32.unpack(size)[0] if len(size) == 4 else self.last_data_length,
                                  self.last_data_length)
                chunk_spans.append([])
            elif op == bytes([OP_INDEX_DATA]):
                conn_id = _U32.unpack(fields["conn"])[0]
                count = _U32.unpack(fields["count"])[0]
                index_counts[conn_id] = index_counts.get(conn_id, 0) + count
                if count and len(data) >= 12 and chunk_spans:
                    import numpy as np

                    entries = np.frombuffer(data, dtype=_INDEX_ENTRY, count=min(count, len(data) // 12))
                    stamps = entries["sec"].astype(np.int64) * 1_000_000_000 + entries["nsec"]
                    chunk_spans[-1].extend((int(stamps.min()), int(stamps.max())))
            elif op == bytes([OP_CHUNK_INFO]):
                try:
                    chunk_infos.append(_chunk_info(fields, data))
                except (KeyError, struct.error):
                    self.truncated = "a chunk info record is malformed"
        if not self.closed_properly:
            # connection records live inside chunks: read them from the chunks' data
            for conn, _t, _d in self.messages():
                pass
        summary.connections = list(self.connections.values())
        spans = [(min(s), max(s)) for s in chunk_spans if s]
        if chunk_infos:
            for _start, _end, counts in chunk_infos:
                for conn_id, count in counts.items():
                    summary.counts[conn_id] = summary.counts.get(conn_id, 0) + count
            summary.info_span = (chunk_infos[0][0], chunk_infos[-1][1])
            spans += [(start, end) for start, end, _counts in chunk_infos]
        else:
            summary.counts = index_counts
            summary.info_span = (spans[0][0], spans[-1][1]) if spans else None
        summary.start_ns = min((start for start, _ in spans), default=0)
        summary.end_ns = max((end for _, end in spans), default=0)
        summary.problem = self.truncated
        return summary


def _chunk_info(fields: dict[str, bytes], data: bytes) -> tuple[int, int, dict[int, int]]:
    """A chunk info record's start and end time and its message count per connection."""
    count = _U32.unpack(fields["count"])[0]
    counts = {_U32.unpack_from(data, 8 * i)[0]: _U32.unpack_from(data, 8 * i + 4)[0] for i in range(count)}
    return _time_ns(fields["start_time"]), _time_ns(fields["end_time"]), counts
