"""rosbag v2.0 ``.bag`` files: a chunked writer that survives a kill, and a sequential reader.

The writer closes a chunk (and writes its index records) whenever it holds
``chunk_bytes`` or is older than ``max_chunk_age`` seconds, so a process killed
mid-recording leaves a file whose complete chunks all read back. The reader
walks records in file order, so it reads indexed and unindexed files alike and
stops cleanly at the first incomplete record.
"""

from __future__ import annotations

import os
import struct
import time
from collections.abc import Callable, Iterator
from typing import Any, BinaryIO

from rostui.core.bag.fileindex import NO_CHUNK, ChunkedFile, ChunkEntries, ChunkPlace
from rostui.core.bag.inflate import UNCOMPRESSED, inflate
from rostui.core.bag.model import BagError, BagSummary, Connection, Frame, MalformedRecord
from rostui.core.file_region import FileRegion
from rostui.core.records import FrozenRecord

TYPE_CHECKING = False
if TYPE_CHECKING:
    from rostui.core.bag.sink import AppendFile  # the writer's file: imported when a writer is made

MAGIC = b"#ROSBAG V2.0\n"
FILE_HEADER_LENGTH = 4096
#: The file header record as rosbag writes it: header length, header, data length, data padding the header
#: to FILE_HEADER_LENGTH.  rosbag rewrites it in place (reindex, append), so it must be exactly this size.
FILE_HEADER_RECORD_SIZE = 4 + FILE_HEADER_LENGTH + 4
OP_MSG_DATA, OP_FILE_HEADER, OP_INDEX_DATA, OP_CHUNK, OP_CHUNK_INFO, OP_CONNECTION = 2, 3, 4, 5, 6, 7
COMPRESSIONS = ("none", "bz2", "lz4")
_U32 = struct.Struct("<I")
_RECORD_PEEK = 64
"""Bytes read to find a message record's data: its header length, the header rosbag writes (op, conn and time:
38 bytes) and the data length."""
PAD_FIELD = "pad"
"""A chunk header field of spaces that puts the chunk's big message on a block boundary, so the recorder's
direct writes take it without a copy (see :mod:`rostui.core.bag.sink`)."""
_TIME = struct.Struct("<II")
_INDEX_ENTRY = [("sec", "<u4"), ("nsec", "<u4"), ("offset", "<u4")]
"""An index-data entry (version 1): time and the message record's offset in its decompressed chunk."""
_INDEX_ROW = struct.Struct("<III")
"""The same entry for struct."""


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
        import bz2

        return bz2.compress(data)
    if kind == "lz4":
        return _roslz4_frame(data)
    return data


def _roslz4_frame(data: bytes) -> bytes:
    """``data`` as one lz4 frame in the form roslz4 (rosbag's lz4 library) writes, the only form its reader
    takes: independent 1 MiB blocks, no block checksums, no content size, a content checksum.

    roslz4 refuses linked blocks, python-lz4's default, which a chunk over one block needs, and keeps the
    1 MiB block size id for small chunks too (``lz4.frame.compress`` would lower it).  Written block by block
    (:func:`~rostui.core.bag.lz4frame.compress_frame`): python-lz4's frame compressor spends more on the
    content checksum than on compressing.
    """
    from rostui.core.bag.lz4frame import compress_frame

    return compress_frame(data)


class Resumed(FrozenRecord):
    """An existing ``.bag`` a :class:`BagWriter` goes on writing: the file opened at the end of its last
    complete chunk (the old index cut off), its connections and its chunks' infos
    ``(position, start_ns, end_ns, {conn_id: count})`` (:mod:`rostui.core.bag.bag_append` finds them)."""

    _fields = ("out", "connections", "chunks")
    out: AppendFile
    connections: dict[int, Connection]
    chunks: list[tuple[int, int, int, dict[int, int]]]

    def __init__(self, out: AppendFile, connections: dict[int, Connection],
                 chunks: list[tuple[int, int, int, dict[int, int]]]) -> None:
        self._set(out, connections, chunks)


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
        from rostui.core.bag.iov import Parts  # here: a reader (a player) needs neither
        from rostui.core.bag.sink import open_append

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


_OP_NAMES = {OP_MSG_DATA: "message", OP_FILE_HEADER: "file header", OP_INDEX_DATA: "index data", OP_CHUNK: "chunk",
             OP_CHUNK_INFO: "chunk info", OP_CONNECTION: "connection"}
_IN_CHUNKS = (OP_MSG_DATA, OP_CONNECTION)


class _Place:
    """Where a record lies, for its error line: the file, the record's byte (its chunk's, for a record inside
    one) and, inside a chunk, how far into the chunk's plain bytes."""

    __slots__ = ("path", "at", "inside")

    def __init__(self, path: str, at: int, inside: int = -1) -> None:
        self.path = path
        self.at = at
        self.inside = inside

    def error(self, what: str) -> MalformedRecord:
        """The error line for ``what`` is wrong with the record here."""
        if self.inside >= 0:
            what = f"{what}, {self.inside} bytes into the chunk"
        return MalformedRecord(self.path, self.at, what)


class _Record:
    """One record of the file or of a chunk: where it is (``inside``: its offset in its chunk's plain bytes, -1
    for a record of the file), its op, its header fields, its data (empty when a chunk's data was skipped)
    with where that starts and how long it is."""

    __slots__ = ("path", "at", "inside", "op", "fields", "data", "data_at", "data_length")

    def __init__(self, path: str, at: int, inside: int, op: int, fields: dict[str, bytes], data: bytes | memoryview,
                 data_at: int, data_length: int) -> None:
        self.path = path
        self.at = at
        self.inside = inside
        self.op = op
        self.fields = fields
        self.data = data
        self.data_at = data_at
        self.data_length = data_length

    @property
    def place(self) -> _Place:
        """Where the record lies, for an error line."""
        return _Place(self.path, self.at, self.inside)

    @property
    def kind(self) -> str:
        """The record's kind in words."""
        return _OP_NAMES[self.op]

    def _raw(self, name: str, size: int) -> bytes:
        raw = self.fields.get(name)
        if raw is None:
            raise self.place.error(f"a {self.kind} record has no '{name}' field")
        if len(raw) != size:
            raise self.place.error(f"the '{name}' field of a {self.kind} record is {len(raw)} bytes, not {size}")
        return raw

    def number(self, name: str, size: int = 4) -> int:
        """The little-endian unsigned field ``name`` of ``size`` bytes."""
        return int.from_bytes(self._raw(name, size), "little")

    def time(self, name: str = "time") -> int:
        """The time field ``name`` (seconds and nanoseconds) in nanoseconds."""
        return _time_ns(self._raw(name, 8))

    def text(self, name: str) -> str:
        """The UTF-8 field ``name``."""
        raw = self.fields.get(name)
        if raw is None:
            raise self.place.error(f"a {self.kind} record has no '{name}' field")
        try:
            return raw.decode()
        except UnicodeDecodeError:
            raise self.place.error(f"the '{name}' field of a {self.kind} record is not UTF-8 text") from None


def _fields(raw: bytes | memoryview, place: _Place) -> dict[str, bytes]:
    try:
        return parse_header(raw)
    except BagError as exc:
        raise place.error(str(exc)) from None


def _op(fields: dict[str, bytes], place: _Place) -> int:
    op = fields.get("op")
    if op is None:
        raise place.error("a record has no 'op' field")
    if len(op) != 1 or op[0] not in _OP_NAMES:
        raise place.error(f"a record has an unknown op ({op.hex()})")
    return op[0]


def _data_span(plain: bytes, offset: int) -> tuple[int, int] | None:
    """Where the data of the message record at ``offset`` of a chunk's plain bytes starts and ends; None when no
    record fits there (an index pointing past the chunk or into the middle of a record)."""
    end = len(plain)
    if 0 <= offset <= end - 8:
        data_at = offset + 8 + _U32.unpack_from(plain, offset)[0]
        if data_at <= end:
            (dlen,) = _U32.unpack_from(plain, data_at - 4)
            if dlen <= end - data_at:
                return data_at, data_at + dlen
    return None


def _record_in(view: memoryview, pos: int, path: str, chunk_at: int) -> tuple[_Record, int]:
    """The record at ``pos`` of the plain bytes of the chunk at ``chunk_at`` and where the next one starts."""
    end = len(view)
    if end - pos < 8:
        raise _Place(path, chunk_at, pos).error("a record is cut short")
    (hlen,) = _U32.unpack_from(view, pos)
    if hlen > end - pos - 8:
        raise _Place(path, chunk_at, pos).error(f"a record header of {hlen} bytes runs past the end of the chunk")
    try:
        fields = parse_header(view[pos + 4:pos + 4 + hlen])
        op = fields["op"][0] if len(fields.get("op", b"")) == 1 else -1
    except BagError as exc:
        raise _Place(path, chunk_at, pos).error(str(exc)) from None
    if op not in _OP_NAMES:
        _op(fields, _Place(path, chunk_at, pos))
    data_at = pos + 8 + hlen
    (dlen,) = _U32.unpack_from(view, data_at - 4)
    if dlen > end - data_at:
        raise _Place(path, chunk_at, pos).error(f"a record's {dlen} bytes of data run past the end of the chunk")
    return _Record(path, chunk_at, pos, op, fields, view[data_at:data_at + dlen], data_at, dlen), data_at + dlen


class _ChunkRegion(FileRegion):
    """A message's frame in an uncompressed chunk: a file cut short while played is a malformed chunk."""

    __slots__ = ("chunk_at",)

    def __init__(self, fd: int, offset: int, length: int, chunk_at: tuple[str, int]) -> None:
        # FileRegion's three fields set here too: one call less for each message a player sends
        self.fd, self.offset, self.length = fd, offset, length
        self.chunk_at = chunk_at  # the file's path and where its chunk record starts

    def cut_short(self) -> Exception:
        """The chunk's error, as reading it whole would give."""
        return MalformedRecord(*self.chunk_at, "a chunk is cut short")


class BagReader(ChunkedFile):
    """Reads a rosbag v2.0 file in file order, or through its index; a file cut short reads up to its last
    complete chunk.

    Every length is checked against what holds it (the file, or the chunk) before anything is read, every
    chunk is decompressed within its declared size (:mod:`rostui.core.bag.inflate`), and every field is checked
    before use: a record that breaks any of that is a :class:`~rostui.core.bag.model.MalformedRecord`. In a
    file its writer closed that is an error; in one cut short it ends what can be read, as ``rosbag reindex``
    stops at the first record that is not what it should be (a run of zeros stops it at its first byte).
    """

    def __init__(self, path: str) -> None:
        super().__init__()
        self.path = path
        try:
            self.file: BinaryIO = open(path, "rb")
        except OSError as exc:
            raise BagError(f"cannot open {path}: {exc.strerror}") from None
        self.size = os.fstat(self.file.fileno()).st_size
        self.connections: dict[int, Connection] = {}
        self.truncated = ""
        self.index_pos = 0
        self.chunk_count = 0
        self._spans: list[tuple[int, int, int]] | None = None
        self._spans_unreadable = False
        try:
            self._read_file_header()
        except BaseException:
            self.file.close()
            raise
        self.data_start = self.file.tell()

    def _read_file_header(self) -> None:
        magic = self.file.read(len(MAGIC))
        if magic != MAGIC:
            if magic.startswith(b"#ROSBAG V"):
                raise BagError(f"{self.path}: rosbag format {magic[9:].strip().decode(errors='replace')} is not "
                               "supported (only 2.0)")
            raise BagError(f"{self.path} is not a bag file (no '#ROSBAG V2.0' line)")
        try:
            record = self._read_record()
        except EOFError:
            raise BagError(f"{self.path}: the file header is incomplete") from None
        if record.op != OP_FILE_HEADER:
            raise BagError(f"{self.path}: the file header record is missing")
        self.index_pos = record.number("index_pos", 8)
        if "chunk_count" in record.fields:
            self.chunk_count = record.number("chunk_count")

    def close(self) -> None:
        """Close the file."""
        self.file.close()

    @property
    def closed_properly(self) -> bool:
        """True when the writer finished the file (index written)."""
        return self.index_pos != 0 and self.index_pos <= self.size

    def _read_record(self, skip_chunk_data: bool = False, at: int | None = None) -> _Record:
        """The record at byte ``at`` (the file's position when None; a chunk's data skipped with
        ``skip_chunk_data``), the file left at its end; EOFError at the end of the file.  A reader that knows
        where it stands says ``at``: the buffered file's ``tell`` asks the kernel each time."""
        if at is None:
            at = self.file.tell()
        else:
            self.file.seek(at)
        place = _Place(self.path, at)
        left = self.size - at
        head = self.file.read(4)
        if not head:
            raise EOFError
        if len(head) < 4 or left < 8:
            raise place.error("a record is cut short")
        (hlen,) = _U32.unpack(head)
        if hlen > left - 8:
            raise place.error(f"a record header of {hlen} bytes runs past the end of the file")
        raw = self.file.read(hlen)
        fields = _fields(raw, place)
        op = _op(fields, place)
        tail = self.file.read(4)
        if len(raw) < hlen or len(tail) < 4:
            raise place.error("a record is cut short")
        (dlen,) = _U32.unpack(tail)
        if dlen > left - 8 - hlen:
            raise place.error(f"a record's {dlen} bytes of data run past the end of the file")
        data_at = at + 8 + hlen
        if skip_chunk_data and op == OP_CHUNK:
            self.file.seek(dlen, os.SEEK_CUR)
            return _Record(self.path, at, -1, op, fields, b"", data_at, dlen)
        data = self.file.read(dlen)
        if len(data) < dlen:
            raise place.error("a record is cut short")
        return _Record(self.path, at, -1, op, fields, data, data_at, dlen)

    def _stop(self, exc: MalformedRecord) -> None:
        """A malformed record ends what can be read: an error in a file its writer closed; in a file cut short,
        the end of what is readable (``truncated`` says where)."""
        if self.closed_properly:
            raise exc
        self.truncated = exc.where

    def _connection(self, record: _Record) -> Connection:
        conn_id = record.number("conn")
        topic = record.text("topic")
        info = {k: v.decode("utf-8", "replace") for k, v in _fields(record.data, record.place).items()}
        conn = Connection(conn_id, topic, info.get("type", ""), info.get("md5sum", ""),
                          info.get("message_definition", ""), info.get("callerid", ""),
                          info.get("latching", "0") == "1")
        self.connections.setdefault(conn_id, conn)
        return conn

    def _message(self, record: _Record) -> tuple[Connection, int]:
        """The connection and time of a message record."""
        raw, stamp = record.fields.get("conn"), record.fields.get("time")
        conn = self.connections.get(_U32.unpack(raw)[0]) if raw is not None and len(raw) == 4 else None
        if conn is None or stamp is None or len(stamp) != 8:  # say what is wrong
            conn_id = record.number("conn")
            record.time()
            raise record.place.error(f"a message on connection {conn_id}, which no connection record declares")
        return conn, _time_ns(stamp)

    def _records(self, with_chunk_data: bool) -> Iterator[_Record]:
        """The file's records in order, from the first after the file header (index data records left out
        when chunks are read); a malformed one ends them (see :meth:`_stop`)."""
        at = self.data_start
        while at < self.size:
            try:
                record = self._read_record(skip_chunk_data=not with_chunk_data, at=at)
            except EOFError:
                return
            except MalformedRecord as exc:
                self._stop(exc)
                return
            at = record.data_at + record.data_length
            if record.op == OP_INDEX_DATA and with_chunk_data:
                continue
            yield record

    def _chunk_place(self, record: _Record) -> ChunkPlace:
        return ChunkPlace(record.at, record.data_at, record.data_length, record.text("compression"),
                          record.number("size"))

    def _plain(self, record: _Record) -> bytes:
        """A chunk record's plain bytes (decompressed within the size it declares)."""
        place = self._chunk_place(record)
        return inflate(place.compression, bytes(record.data), place.plain_size, path=self.path,
                       offset=place.record_at)

    def _chunk_records(self, plain: bytes, chunk_at: int) -> Iterator[_Record]:
        """The records of a chunk's plain bytes (connections taken in on the way)."""
        view = memoryview(plain)
        pos = 0
        while pos < len(view):
            record, pos = _record_in(view, pos, self.path, chunk_at)
            if record.op not in _IN_CHUNKS:
                raise record.place.error(f"a {record.kind} record inside a chunk")
            if record.op == OP_CONNECTION:
                self._connection(record)
            yield record

    def _chunk_entries(self, plain: bytes, chunk_at: int) -> Iterator[tuple[int, int, int]]:
        """``(conn_id, time_ns, offset)`` of each message record in a decompressed chunk; connection
        records are taken in on the way."""
        for record in self._chunk_records(plain, chunk_at):
            if record.op == OP_MSG_DATA:
                conn, t = self._message(record)
                yield conn.id, t, record.inside

    def _own_index_parts(self) -> Iterator[ChunkEntries] | None:
        return self._file_index_parts() if self.closed_properly else None

    def _chunk_info_records(self) -> list[tuple[int, _Record]]:
        """The index section's chunk info records by the position of their chunk, in file order (its connection
        records taken in on the way); MalformedRecord when they are not one for each chunk the header counts."""
        infos: list[tuple[int, _Record]] = []
        at = self.index_pos
        while at < self.size:
            record = self._read_record(at=at)
            at = record.data_at + record.data_length
            if record.op == OP_CONNECTION:
                self._connection(record)
            elif record.op == OP_CHUNK_INFO:
                infos.append((record.number("chunk_pos", 8), record))
        if len(infos) != self.chunk_count:
            raise MalformedRecord(self.path, self.index_pos, f"the index lists {len(infos)} of the "
                                                             f"{self.chunk_count} chunks the file header counts")
        infos.sort(key=lambda info: info[0])
        return infos

    def _indexed_chunk(self, pos: int) -> ChunkPlace:
        """The chunk record the index places at ``pos`` (its data skipped: the file stands at its end)."""
        if not self.data_start <= pos < self.index_pos:
            raise MalformedRecord(self.path, self.index_pos, f"the index places a chunk at byte {pos}, "
                                                             "outside the chunks")
        self.file.seek(pos)
        record = self._read_record(skip_chunk_data=True)
        if record.op != OP_CHUNK:
            raise record.place.error("the index places a chunk here")
        return self._chunk_place(record)

    def _file_index_parts(self) -> Iterator[ChunkEntries]:
        infos = self._chunk_info_records()
        self.chunk_table = []
        self._index_spans: list[tuple[int, int]] = []
        for number, (pos, _info) in enumerate(infos):
            self.chunk_table.append(self._indexed_chunk(pos))
            first = self.file.tell()
            parts = list(self._index_data(number))
            self._index_spans.append((first, self.file.tell()))
            yield from parts

    def _index_data(self, number: int, end: int | None = None) -> Iterator[ChunkEntries]:
        """The index data records from the file's position on (up to ``end``, else up to the first other record
        or the index), as entries of chunk ``number``."""
        while self.file.tell() < (self.index_pos if end is None else end):
            at = self.file.tell()
            record = self._read_record(skip_chunk_data=True)
            if record.op != OP_INDEX_DATA:
                if end is not None:
                    raise record.place.error("the index places a chunk's index data here")
                self.file.seek(at)
                break
            yield self._index_entries(record, number)

    def chunk_spans(self) -> list[tuple[int, int, int]] | None:
        """``(first time, last time, chunk number)`` of every chunk as its chunk info record gives them (as
        rosbag plays by them), without reading any chunk's index entries; None when the file was not closed or
        its index cannot be read."""
        if self._spans is None and self.closed_properly and not self._spans_unreadable:
            try:
                self._spans = self._chunk_info_spans()
            except (MalformedRecord, EOFError) as exc:
                self._spans_unreadable = True
                self._index_unreadable(exc)
        return self._spans

    def _adopt_chunk_spans(self, places: dict[int, ChunkPlace], infos: list[tuple[int, int, int]]) -> None:
        """Keep what :meth:`chunk_spans` would read again, from a summary's walk of a closed file: its chunk infos
        ``(chunk position, start, end)`` and the chunk records by position. Only when they are what that reading
        accepts (one info for each chunk the header counts, each at a chunk before the index); otherwise
        :meth:`chunk_spans` reads them itself, and says what is wrong."""
        if self._spans is not None or not self.closed_properly or len(infos) != self.chunk_count:
            return
        infos = sorted(infos, key=lambda info: info[0])
        if not all(pos < self.index_pos and pos in places for pos, _start, _end in infos):
            return
        self.chunk_table = [places[pos] for pos, _start, _end in infos]
        self._spans = [(start, end, number) for number, (_pos, start, end) in enumerate(infos)]

    def _chunk_info_spans(self) -> list[tuple[int, int, int]]:
        infos = self._chunk_info_records()
        spans = [(info.time("start_time"), info.time("end_time"), number) for number, (_pos, info) in enumerate(infos)]
        self.chunk_table = [self._indexed_chunk(pos) for pos, _info in infos]
        return spans

    def chunk_rows(self, number: int) -> list[tuple[int, int, int]]:
        """``(time, offset, connection id)`` of chunk ``number``'s messages from the index data records after it,
        sorted by time, then offset (the file's order); read without numpy, a chunk at a time."""
        place = self.chunk_table[number]
        self.file.seek(place.data_at + place.stored)
        rows: list[tuple[int, int, int]] = []
        try:
            while self.file.tell() < self.index_pos:
                record = self._read_record(skip_chunk_data=True)
                if record.op != OP_INDEX_DATA:
                    break
                conn_id, _count = self._index_record(record)
                rows.extend((sec * 1_000_000_000 + nsec, offset, conn_id)
                            for sec, nsec, offset in _INDEX_ROW.iter_unpack(record.data))
        except EOFError:
            raise MalformedRecord(self.path, place.record_at, "the chunk's index runs past the end of the file") \
                from None
        rows.sort()
        return rows

    def _chunk_index_parts(self, number: int) -> list[ChunkEntries]:
        first, end = self._index_spans[number]
        self.file.seek(first)
        return list(self._index_data(number, end))

    def _index_record(self, record: _Record) -> tuple[int, int]:
        """An index data record's connection id and entry count, each checked against the file."""
        version = record.number("ver")
        if version != 1:
            raise record.place.error(f"an index data record of version {version} (only 1 is known)")
        conn_id = record.number("conn")
        if conn_id not in self.connections:
            raise record.place.error(f"an index data record of connection {conn_id}, which no connection "
                                     "record declares")
        count = record.number("count")
        if count * 12 != len(record.data):
            raise record.place.error(f"an index data record of {count} entries holds {len(record.data)} bytes")
        return conn_id, count

    def _index_entries(self, record: _Record, number: int) -> ChunkEntries:
        """The entries of an index data record of chunk ``number``."""
        import numpy as np

        conn_id, count = self._index_record(record)
        entries = np.frombuffer(record.data, dtype=_INDEX_ENTRY, count=count)
        times = entries["sec"].astype(np.int64) * 1_000_000_000 + entries["nsec"]
        return ChunkEntries(times, np.full(count, conn_id, dtype=np.uint32), entries["offset"], number)

    def _scan_parts(self, progress: Callable[[int], None] | None) -> Iterator[ChunkEntries]:
        loose: list[tuple[int, int, int]] = []
        for record in self._records(with_chunk_data=True):
            try:
                if record.op == OP_CONNECTION:
                    self._connection(record)
                elif record.op == OP_CHUNK:
                    entries = list(self._chunk_entries(self._plain(record), record.at))
                    part = ChunkEntries([t for _, t, _ in entries], [c for c, _, _ in entries],
                                        [o for _, _, o in entries], len(self.chunk_table))
                    self.chunk_table.append(self._chunk_place(record))
                    yield part
                    if progress is not None:
                        progress(self.file.tell())
                elif record.op == OP_MSG_DATA:
                    conn, t = self._message(record)
                    loose.append((t, conn.id, record.at))
            except MalformedRecord as exc:
                self._stop(exc)
                break
        if loose:
            yield ChunkEntries([t for t, _, _ in loose], [c for _, c, _ in loose], [o for _, _, o in loose], NO_CHUNK)

    def _scanned_chunk_part(self, number: int) -> ChunkEntries:
        place = self.chunk_table[number]
        entries = list(self._chunk_entries(self.cache.get(number), place.record_at))
        return ChunkEntries([t for _, t, _ in entries], [c for c, _, _ in entries], [o for _, _, o in entries],
                            number)

    def payload(self, chunk: int, offset: int) -> bytes:
        """The serialised message whose record starts at ``offset`` of chunk ``chunk`` (or of the file,
        for a message outside any chunk), as an index entry locates it; MalformedRecord when no record
        fits there."""
        if chunk == NO_CHUNK:
            self.file.seek(offset)
            try:
                record = self._read_record()
            except EOFError:
                raise MalformedRecord(self.path, offset, "the index places a message past the end of the file") \
                    from None
            if record.op != OP_MSG_DATA:
                raise record.place.error("the index places a message here")
            return bytes(record.data)
        plain, data_at, end = self._data_in_chunk(chunk, offset)
        data = plain[data_at:end]
        return data if type(data) is bytes else bytes(data)  # a chunk in a pool's buffer gives bytearray slices

    def framer(self, chunk: int) -> Callable[[int], Frame]:
        """The frames of chunk ``chunk``'s messages by offset: each message as :meth:`payload` finds it, with its
        4-byte length before it, as TCPROS sends it.  In a chunk the record's own data-length field is that
        prefix, so a frame is a view of the chunk, not a copy; in an uncompressed chunk (whole in the file, of
        the size it declares), the region of the file that holds it: the chunk is not read (rosbag's chunks
        carry no CRC that reading would check).  What each frame needs of the chunk (its plain bytes, read and
        decompressed here when the cache does not hold them) is looked up here, once."""
        if chunk == NO_CHUNK:
            return super().framer(chunk)
        place = self.chunk_table[chunk]
        if place.compression in UNCOMPRESSED and place.plain_size == place.stored \
                and place.data_at + place.stored <= self.size:
            return self._regions_in_chunk(place)

        plain = self.cache.get(chunk)
        view = memoryview(plain)

        def view_at(offset: int) -> Frame:
            span = _data_span(plain, offset)
            if span is None:
                raise self._no_record_at(place, offset)
            return view[span[0] - 4:span[1]]
        return view_at

    def _regions_in_chunk(self, place: ChunkPlace) -> Callable[[int], FileRegion]:
        """The frame of the message record at an offset of the uncompressed chunk at ``place``, as a region of
        the file: only the record's header length and its data length are read (a syscall, 64 bytes)."""
        fd, start, end, chunk_at = self.file.fileno(), place.data_at, place.stored, (self.path, place.record_at)
        pread, peek, unpack_from = os.pread, _RECORD_PEEK, _U32.unpack_from

        def region_at(offset: int) -> FileRegion:
            if 0 <= offset <= end - 8:
                head = pread(fd, peek, start + offset)
                if len(head) >= 4:
                    data_at = offset + 8 + unpack_from(head)[0]
                    if data_at <= end:
                        length_field = head[data_at - 4 - offset:data_at - offset]
                        if len(length_field) < 4:
                            length_field = pread(fd, 4, start + data_at - 4)
                        (dlen,) = unpack_from(length_field)
                        if dlen <= end - data_at:
                            return _ChunkRegion(fd, start + data_at - 4, dlen + 4, chunk_at)
            raise self._no_record_at(place, offset)
        return region_at

    def _data_in_chunk(self, chunk: int, offset: int) -> tuple[bytes, int, int]:
        """Chunk ``chunk``'s plain bytes and where the data of the message record at ``offset`` starts and ends."""
        plain = self.cache.get(chunk)
        span = _data_span(plain, offset)
        if span is None:
            raise self._no_record_at(self.chunk_table[chunk], offset)
        return plain, span[0], span[1]

    def _no_record_at(self, place: ChunkPlace, offset: int) -> MalformedRecord:
        """The error for an index entry whose offset holds no whole message record of its chunk."""
        return MalformedRecord(self.path, place.record_at,
                               f"the index places a message {offset} bytes into the chunk, where none fits")

    def messages(self) -> Iterator[tuple[Connection, int, bytes]]:
        """``(connection, time_ns, data)`` in file order, up to the last complete chunk."""
        for record in self._records(with_chunk_data=True):
            try:
                if record.op == OP_CONNECTION:
                    self._connection(record)
                elif record.op == OP_CHUNK:
                    for inner in self._chunk_records(self._plain(record), record.at):
                        if inner.op == OP_MSG_DATA:
                            conn, t = self._message(inner)
                            yield conn, t, bytes(inner.data)
                elif record.op == OP_MSG_DATA:
                    conn, t = self._message(record)
                    yield conn, t, bytes(record.data)
            except MalformedRecord as exc:
                self._stop(exc)
                return

    def _index_data_spans(self, index_data: list[tuple[int, int, int]], chunk_spans: list[list[int]]) -> None:
        """Widen each chunk's span to the times of its index entries (``(chunk, where, count)`` records)."""
        if not index_data:
            return
        import numpy as np

        for chunk, data_at, count in index_data:
            self.file.seek(data_at)
            raw = self.file.read(count * 12)
            entries = np.frombuffer(raw, dtype=_INDEX_ENTRY, count=len(raw) // 12)
            if entries.shape[0]:
                stamps = entries["sec"].astype(np.int64) * 1_000_000_000 + entries["nsec"]
                chunk_spans[chunk].extend((int(stamps.min()), int(stamps.max())))

    def summary(self) -> BagSummary:
        """Counts and times from the index records, without decompressing any chunk.

        Counts and rosbag info's start and end come from the chunk info records when the file has them (as
        rosbag reads them); a file without (not closed) takes them from the index records after each chunk.
        """
        summary = BagSummary(self.path, "rosbag", "2.0", self.size, closed=self.closed_properly)
        index_counts: dict[int, int] = {}
        chunk_spans: list[list[int]] = []
        chunk_infos: list[tuple[int, int, dict[int, int]]] = []
        index_data: list[tuple[int, int, int]] = []  # (chunk, where its entries are, how many)
        places: dict[int, ChunkPlace] = {}
        info_places: list[tuple[int, int, int]] = []  # (chunk position, start, end) of each chunk info
        for record in self._records(with_chunk_data=False):
            try:
                if record.op == OP_CONNECTION:
                    self._connection(record)
                elif record.op == OP_CHUNK:
                    place = self._chunk_place(record)
                    places[record.at] = place
                    summary.add_chunk(place.compression, place.plain_size, place.stored)
                    chunk_spans.append([])
                elif record.op == OP_INDEX_DATA:
                    conn_id, count = record.number("conn"), record.number("count")
                    index_counts[conn_id] = index_counts.get(conn_id, 0) + count
                    if count and len(record.data) >= 12 and chunk_spans:
                        index_data.append((len(chunk_spans) - 1, record.data_at, min(count, len(record.data) // 12)))
                elif record.op == OP_CHUNK_INFO:
                    start, end, counts = _chunk_info(record)
                    chunk_infos.append((start, end, counts))
                    if record.at >= self.index_pos:  # where chunk_spans reads them
                        info_places.append((record.number("chunk_pos", 8), start, end))
            except MalformedRecord as exc:
                self._stop(exc)
                break
        self._adopt_chunk_spans(places, info_places)
        if not self.closed_properly:
            # connection records live inside chunks: read them from the chunks' data
            for _conn, _t, _d in self.messages():
                pass
        summary.connections = list(self.connections.values())
        if not chunk_infos:  # only then are the chunks' spans read from their index entries
            self._index_data_spans(index_data, chunk_spans)
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


def _chunk_info(record: _Record) -> tuple[int, int, dict[int, int]]:
    """A chunk info record's start and end time and its message count per connection."""
    count = record.number("count")
    if count * 8 != len(record.data):
        raise record.place.error(f"a chunk info record of {count} connections holds {len(record.data)} bytes")
    data = record.data
    counts = {_U32.unpack_from(data, 8 * i)[0]: _U32.unpack_from(data, 8 * i + 4)[0] for i in range(count)}
    return record.time("start_time"), record.time("end_time"), counts
