"""Opening bags by what they hold (MCAP or rosbag v2.0), writing by name, merging, converting, reindexing."""

from __future__ import annotations

import heapq
import os
from collections.abc import Callable, Iterable, Iterator
from typing import Any, Protocol

from rostui.core.bag.chunkinfo import ChunkInfos
from rostui.core.bag.chunkorder import chunk_order
from rostui.core.bag.fileindex import ChunkCache, ChunkEntries
from rostui.core.bag.model import MCAP_COMPRESSIONS, MCAP_MAGIC, BagError, BagSummary, Connection, Frame
from rostui.core.bag.progress import Progress, counted
from rostui.core.bag.rosbag2_0 import COMPRESSIONS as BAG_COMPRESSIONS
from rostui.core.bag.rosbag2_0 import MAGIC as BAG_MAGIC
from rostui.core.bag.rosbag2_0 import BagReader, BagWriter

TYPE_CHECKING = False
if TYPE_CHECKING:
    from rostui.core.bag.sink import AppendFile  # imported by the writers that use it: a reader needs none

COMPRESSIONS = ("none", "lz4", "zstd", "bz2")


class Reader(Protocol):
    """What both readers offer."""

    path: str
    truncated: str
    connections: dict[int, Connection]
    cache: ChunkCache

    def messages(self) -> Iterator[tuple[Connection, int, bytes]]: ...
    def summary(self) -> BagSummary: ...
    def close(self) -> None: ...
    def payload(self, chunk: int, offset: int) -> bytes: ...
    def framer(self, chunk: int) -> Callable[[int], Frame]: ...
    def release(self, chunk: int) -> None: ...
    def chunk_spans(self) -> list[tuple[int, int, int]] | None: ...
    def chunk_rows(self, number: int) -> list[tuple[int, int, int]]: ...
    def chunk_infos(self) -> ChunkInfos | None: ...
    def scan_chunk_infos(self, progress: Callable[[int], None] | None = None) -> ChunkInfos: ...
    def chunk_entries(self, number: int) -> ChunkEntries: ...

    @property
    def closed_properly(self) -> bool: ...


class Writer(Protocol):
    """What both writers offer."""

    path: str
    connections: dict[int, Connection]
    out: AppendFile

    @property
    def size(self) -> int: ...
    @property
    def buffered(self) -> int: ...

    def add_connection(self, conn: Connection) -> None: ...
    def write(self, conn_id: int, time_ns: int, data: Any) -> None: ...
    def flush_if_old(self) -> None: ...
    def flush(self) -> None: ...
    def close(self) -> None: ...


def is_rosbag_name(path: str) -> bool:
    """True when the name asks for a rosbag v2.0 file (``.bag``), else MCAP."""
    return path.endswith(".bag") or path.endswith(".bag.active")


def open_reader(path: str) -> Reader:
    """A reader for ``path``, chosen by its first bytes; BagError for anything else."""
    try:
        with open(path, "rb") as f:
            head = f.read(len(MCAP_MAGIC) + len(BAG_MAGIC))
    except FileNotFoundError:
        raise BagError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise BagError(f"{path} is a directory, not a bag file") from None
    except OSError as exc:
        raise BagError(f"cannot open {path}: {exc.strerror}") from None
    if head.startswith(MCAP_MAGIC):
        from rostui.core.bag.mcapfile import McapBagReader  # the mcap library loads for MCAP files only

        return McapBagReader(path)
    if head.startswith(b"#ROSBAG"):
        return BagReader(path)
    if not head:
        raise BagError(f"{path} is empty, not a bag file")
    raise BagError(f"{path} is neither an MCAP file nor a rosbag file (unknown first bytes)")


def open_writer(path: str, compression: str = "none", *, max_chunk_age: float = 0.5, chunk_crcs: bool = True,
                direct: bool = False) -> Writer:
    """A writer for ``path``: rosbag v2.0 when the name ends in ``.bag``, otherwise MCAP (with chunk CRCs
    unless ``chunk_crcs`` is False; rosbag files have none); ``direct`` bypasses the page cache where the file
    system allows it (:mod:`rostui.core.bag.sink`)."""
    if compression not in COMPRESSIONS:
        raise BagError(f"unknown compression '{compression}' (none, lz4, zstd or bz2)")
    try:
        if is_rosbag_name(path):
            return BagWriter(path, compression=compression, max_chunk_age=max_chunk_age, direct=direct)
        from rostui.core.bag.mcapfile import McapBagWriter

        return McapBagWriter(path, compression=compression, max_chunk_age=max_chunk_age, chunk_crcs=chunk_crcs,
                             direct=direct)
    except OSError as exc:
        raise BagError(f"cannot create {path}: {exc.strerror}") from None


def unordered_notice(reader: Reader) -> str:
    """Why ``reader`` plays in file order (it has no index to play it in time order), or ''."""
    if reader.chunk_spans() is not None:
        return ""
    return (f"{reader.path} has no index ({'cut short' if reader.truncated else 'not closed'}): its messages "
            "play in file order; `rostui bag reindex` writes one")


def time_ordered(reader: Reader) -> Iterator[tuple[Connection, int, bytes]]:
    """One file's messages in time order, chunk by chunk (ties in file order, as rosbag plays them; memory
    follows the chunks open, not the messages); in file order when it has no index (:func:`unordered_notice`
    says so)."""
    spans = reader.chunk_spans()
    if spans is None:
        return reader.messages()
    return _by_chunks(reader, spans)


def _by_chunks(reader: Reader, spans: list[tuple[int, int, int]]) -> Iterator[tuple[Connection, int, bytes]]:
    conns = reader.connections
    payload = reader.payload
    for t, chunk, offset, conn_id in chunk_order(spans, reader.chunk_rows):
        yield conns[conn_id], t, payload(chunk, offset)


def merged_messages(readers: Iterable[Reader]) -> Iterator[tuple[Connection, int, bytes, int]]:
    """Messages of several files in time order: ``(connection, time_ns, data, file_index)``."""

    def tagged(reader: Reader, i: int) -> Iterator[tuple[int, int, Connection, bytes]]:
        return ((t, i, conn, data) for conn, t, data in time_ordered(reader))

    streams = [tagged(r, i) for i, r in enumerate(readers)]  # (each stream its own i, not the loop's last)
    for t, i, conn, data in heapq.merge(*streams, key=lambda item: (item[0], item[1])):
        yield conn, t, data, i


class ConnectionMap:
    """Gives each source connection an id in the new file the first time one of its messages is written."""

    def __init__(self, writer: Writer) -> None:
        self.writer = writer
        self.ids: dict[tuple[int, int], int] = {}

    def write(self, conn: Connection, time_ns: int, data: bytes, source: int = 0) -> None:
        """Write one message of ``conn`` (of source file ``source``), adding the connection when it is new."""
        key = (source, conn.id)
        new_id = self.ids.get(key)
        if new_id is None:
            new_id = self.ids[key] = len(self.ids)
            self.writer.add_connection(Connection(new_id, conn.topic, conn.type, conn.md5sum, conn.definition,
                                                  conn.callerid, conn.latching))
        self.writer.write(new_id, time_ns, data)


def copy_messages(reader: Reader, writer: Writer, progress: Progress | None = None) -> int:
    """Write every readable message of ``reader`` into ``writer``, in time order where the file has an index
    (as rosbag's tools rewrite bags); returns how many (``progress`` follows)."""
    conns = ConnectionMap(writer)
    count = 0
    total = reader.summary().message_count if progress is not None else 0
    for conn, t, data in counted(time_ordered(reader), total, progress):
        conns.write(conn, t, data)
        count += 1
    return count


def convert(src: str, dst: str, compression: str = "none", progress: Progress | None = None) -> int:
    """Copy a bag into a new file whose format follows its name; returns the message count."""
    if os.path.abspath(src) == os.path.abspath(dst):
        raise BagError("convert needs a different output file")
    reader = open_reader(src)
    try:
        writer = open_writer(dst, compression)
        try:
            return copy_messages(reader, writer, progress)
        finally:
            writer.close()
    finally:
        reader.close()


def reindex(path: str, progress: Progress | None = None) -> tuple[int, str]:
    """Rewrite a file cut short (or any file) in place with a full index.

    The original is kept as ``<name>.orig.<ext>`` like rosbag reindex does.
    Returns the message count and what was wrong ('' when the file was fine).
    """
    reader = open_reader(path)
    root, ext = os.path.splitext(path)
    backup = f"{root}.orig{ext}"
    reader.close()
    os.replace(path, backup)
    reader = open_reader(backup)
    try:
        kinds = reader.summary().chunk_compression
        rosbag = isinstance(reader, BagReader)  # the format stays what it was, whatever the name says
        compression = max(kinds, key=lambda k: kinds[k]) if kinds else "none"
        if compression not in (BAG_COMPRESSIONS if rosbag else MCAP_COMPRESSIONS):
            compression = "none"
        from rostui.core.bag.mcapfile import McapBagWriter

        writer: Writer = (BagWriter(path, compression=compression) if rosbag
                          else McapBagWriter(path, compression=compression))
        try:
            count = copy_messages(reader, writer, progress)
        finally:
            writer.close()
        return count, reader.truncated
    finally:
        reader.close()
