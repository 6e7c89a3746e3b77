"""Going on writing an existing rosbag v2.0 file in place, as rosbag's append mode does.

The file's index (connection and chunk-info records after the last chunk) is
read and cut off, the file header is cleared (so a process killed while
appending leaves an unindexed file, not a wrong index), and a
:class:`~rostui.core.bag.rosbag2_0.BagWriter` continues after the last chunk;
closing it writes an index covering the old chunks and the new ones. A file
without an index (a recorder killed mid-way) is read chunk by chunk instead,
up to its last complete chunk, when the caller allows it: that rebuilds the
index the way ``rosbag reindex`` does.
"""

from __future__ import annotations

import os

from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.rosbag2_0 import (
    MAGIC,
    OP_CHUNK,
    OP_CHUNK_INFO,
    OP_CONNECTION,
    OP_INDEX_DATA,
    BagReader,
    BagWriter,
    Resumed,
    _chunk_info,
)
from rostui.core.bag.sink import AppendFile

__all__ = ["NotIndexed", "ChunkInfo", "read_chunk_infos", "resume_bag"]

ChunkInfo = tuple[int, int, int, dict[int, int]]
"""A chunk's position in the file, its first and last time stamp and its message count per connection."""


class NotIndexed(BagError):
    """The file has no index (it was not closed); appending to it needs its chunks read first."""


def _indexed_chunks(reader: BagReader) -> list[ChunkInfo] | None:
    """The chunk infos of the file's index, or None when it has no complete one."""
    if not reader.closed_properly:
        return None
    chunks: list[ChunkInfo] = []
    try:
        reader.file.seek(reader.index_pos)
        while reader.file.tell() < reader.size:
            record = reader._read_record()
            if record.op == OP_CONNECTION:
                reader._connection(record)
            elif record.op == OP_CHUNK_INFO:
                start, end, counts = _chunk_info(record)
                chunks.append((record.number("chunk_pos", 8), start, end, counts))
    except (BagError, EOFError):
        return None
    if len(chunks) != reader.chunk_count:
        return None
    return sorted(chunks)


def _scanned_chunks(reader: BagReader) -> tuple[list[ChunkInfo], int]:
    """Every complete chunk (with all its index-data records) read from the file, and where the last one ends."""
    chunks: list[ChunkInfo] = []
    good_end = reader.data_start
    pending: tuple[ChunkInfo, int] | None = None  # a chunk and how many index-data records it still needs
    reader.file.seek(reader.data_start)
    while reader.file.tell() < reader.size:
        at = reader.file.tell()
        try:
            record = reader._read_record()
        except (EOFError, BagError):
            break
        op = record.op
        if op == OP_CHUNK:
            if pending is not None:
                break  # the previous chunk's index records are missing: the file stays valid only up to it
            try:
                counts: dict[int, int] = {}
                times: list[int] = []
                for conn_id, t, _offset in reader._chunk_entries(reader._plain(record), at):
                    counts[conn_id] = counts.get(conn_id, 0) + 1
                    times.append(t)
            except BagError:  # a damaged chunk: keep what comes before it
                break
            if not counts:
                break
            pending = ((at, min(times), max(times), counts), len(counts))
        elif op == OP_INDEX_DATA and pending is not None:
            info, needed = pending
            pending = (info, needed - 1)
            if needed == 1:
                chunks.append(info)
                good_end = reader.file.tell()
                pending = None
        elif op == OP_CONNECTION:
            try:
                reader._connection(record)
            except BagError:
                break
            if pending is None:
                good_end = reader.file.tell()
        else:
            break
    return chunks, good_end


def read_chunk_infos(path: str, *, scan: bool) -> tuple[dict[int, Connection], list[ChunkInfo], int]:
    """The connections and chunk infos of a ``.bag`` and where its chunks end (where its index starts).

    A file without an index raises :class:`NotIndexed` unless ``scan`` is given; then its chunks are read.
    """
    reader = BagReader(path)
    try:
        chunks = _indexed_chunks(reader)
        if chunks is not None:
            return dict(reader.connections), chunks, reader.index_pos
        if not scan:
            raise NotIndexed(f"{path} has no index (it was not closed)")
        reader.connections.clear()
        chunks, end = _scanned_chunks(reader)
        used = {c for info in chunks for c in info[3]}
        return {c: conn for c, conn in reader.connections.items() if c in used}, chunks, end
    finally:
        reader.close()


def resume_bag(path: str, *, compression: str = "none", chunk_bytes: int = 768 * 1024,
               scan_unindexed: bool = False) -> BagWriter:
    """A writer that appends to the ``.bag`` at ``path`` in place (see the module's docstring)."""
    connections, chunks, end = read_chunk_infos(path, scan=scan_unindexed)
    fd = os.open(path, os.O_WRONLY)
    try:
        os.ftruncate(fd, end)
        os.lseek(fd, end, os.SEEK_SET)
        out = AppendFile(path, fd)
    except OSError:
        os.close(fd)
        raise
    out.end = end
    writer = BagWriter(path, compression=compression, chunk_bytes=chunk_bytes,
                       resume=Resumed(out, connections, chunks))
    out.rewrite(writer._file_header(0, 0, 0), len(MAGIC))
    return writer
