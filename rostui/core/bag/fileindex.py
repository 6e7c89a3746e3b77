"""Where each message of one bag file lies, in time order, and a bounded cache of decompressed chunks.

Both formats index their messages per chunk: a rosbag ``.bag`` has an index-data
record per connection after each chunk, an MCAP file a message-index record per
channel. A :class:`FileIndex` gathers those into four columns (time, connection,
chunk, offset), stably sorted by time, so messages with equal times keep their
order in the file. Payloads stay on disk: :class:`ChunkCache` decompresses the
chunks a reader asks for and keeps the most recent ones up to a byte budget.
Memory is 24 bytes a message plus the cache, whatever the file's size.
"""

from __future__ import annotations

import os
import zlib
from collections import OrderedDict
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

from rostui.core.bag.inflate import inflate
from rostui.core.bag.model import MalformedRecord

NO_CHUNK = 0xFFFFFFFF
"""The chunk number of a message stored outside any chunk; its offset is then a position in the file."""

CACHE_BYTES = int(os.environ.get("ROSTUI_BAG_CACHE_BYTES", str(64 * 1024 * 1024)))
"""How many bytes of decompressed chunks a reader keeps (the last chunk read is always kept)."""


class ChunkPlace(NamedTuple):
    """One chunk of a file: where its record starts (the byte its errors name), where its stored bytes start and
    how many there are, their compression, the size its header declares they decompress to, and the CRC32 of
    those plain bytes (0: none given)."""

    record_at: int
    data_at: int
    stored: int
    compression: str
    plain_size: int
    crc: int = 0


@dataclass(frozen=True)
class ChunkEntries:
    """The index entries of one chunk (or of messages outside chunks), in the file's order."""

    times: Any
    conn_ids: Any
    offsets: Any
    chunk: int


@dataclass
class FileIndex:
    """Every message of one file: time, connection id, chunk number and offset, sorted by time.

    ``from_file_index`` is False when the entries were gathered by reading every
    chunk of a file that had no index (unindexed or cut short).
    """

    times: Any
    conn_ids: Any
    chunks: Any
    offsets: Any
    from_file_index: bool = True

    def __len__(self) -> int:
        return int(self.times.shape[0])

    @classmethod
    def build(cls, parts: Sequence[ChunkEntries], *, from_file_index: bool = True) -> FileIndex:
        """Join per-chunk entries (given in file order) and sort them by time; ties keep file order."""
        import numpy as np

        if not parts:
            empty = np.zeros(0, dtype=np.int64)
            return cls(empty, np.zeros(0, dtype=np.uint32), np.zeros(0, dtype=np.uint32),
                       np.zeros(0, dtype=np.uint64), from_file_index)
        times = np.concatenate([np.asarray(p.times, dtype=np.int64) for p in parts])
        conn_ids = np.concatenate([np.asarray(p.conn_ids, dtype=np.uint32) for p in parts])
        chunks = np.concatenate([np.full(len(p.times), p.chunk, dtype=np.uint32) for p in parts])
        offsets = np.concatenate([np.asarray(p.offsets, dtype=np.uint64) for p in parts])
        # np.lexsort sorts by its last key first: time, then the chunk's place in the file, then the offset
        order = np.lexsort((offsets, chunks, times))
        if bool(np.any(order[1:] < order[:-1])):  # one column at a time, so only one is held twice
            times = times[order]
            conn_ids = conn_ids[order]
            chunks = chunks[order]
            offsets = offsets[order]
        return cls(times, conn_ids, chunks, offsets, from_file_index)

    def rows(self, start: int = 0, block: int = 8192) -> Iterator[tuple[int, int, int, int]]:
        """``(time_ns, conn_id, chunk, offset)`` from position ``start`` on, read in blocks."""
        for lo in range(start, len(self), block):
            hi = lo + block
            yield from zip(self.times[lo:hi].tolist(), self.conn_ids[lo:hi].tolist(),
                           self.chunks[lo:hi].tolist(), self.offsets[lo:hi].tolist())


class ChunkCache:
    """Decompressed chunks by number, least recently used dropped first once over ``max_bytes``."""

    def __init__(self, load: Callable[[int], bytes], max_bytes: int = CACHE_BYTES) -> None:
        self._load = load
        self.max_bytes = max_bytes
        self._chunks: OrderedDict[int, bytes] = OrderedDict()
        self._bytes = 0

    @property
    def held_bytes(self) -> int:
        """Bytes of decompressed chunks held now."""
        return self._bytes

    def get(self, chunk: int) -> bytes:
        """Chunk ``chunk``'s decompressed bytes (read and decompressed on a miss)."""
        data = self._chunks.get(chunk)
        if data is not None:
            self._chunks.move_to_end(chunk)
            return data
        data = self._load(chunk)
        self._chunks[chunk] = data
        self._bytes += len(data)
        while self._bytes > self.max_bytes and len(self._chunks) > 1:
            _, dropped = self._chunks.popitem(last=False)
            self._bytes -= len(dropped)
        return data

    def clear(self) -> None:
        """Drop every chunk held."""
        self._chunks.clear()
        self._bytes = 0


class ChunkedFile:
    """What both readers share for reading through an index: the chunk table, the chunk cache, and the
    file's own index read once.

    A reader sets ``path`` and ``file`` and provides ``_read_index`` (the file's own index, or None); its
    ``file_index`` and ``scan_index`` fill ``chunk_table``. A chunk that cannot be read raises the same
    :class:`~rostui.core.bag.model.MalformedRecord` each time it is asked for, without being read again.
    """

    path: str
    file: Any

    def __init__(self) -> None:
        self.chunk_table: list[ChunkPlace] = []
        """Per chunk number: where it lies and what it declares."""
        self.cache = ChunkCache(self._load_chunk)
        self._index: FileIndex | None = None
        self._index_read = False
        self._broken: dict[int, MalformedRecord] = {}

    def file_index(self) -> FileIndex | None:
        """Where every message lies, from the file's own index (read once, no chunk decompressed where the
        format indexes messages); None when the file has no usable index (never closed, or cut short)."""
        if not self._index_read:
            self._index_read = True
            self._index = self._read_index()
        return self._index

    def _read_index(self) -> FileIndex | None:
        raise NotImplementedError

    def read_chunk(self, place: ChunkPlace) -> bytes:
        """The plain bytes of the chunk at ``place``: read, decompressed within the size it declares, checked
        against its CRC; MalformedRecord when any of that fails."""
        self.file.seek(place.data_at)
        data = self.file.read(place.stored)
        if len(data) < place.stored:
            raise MalformedRecord(self.path, place.record_at, "a chunk is cut short")
        plain = inflate(place.compression, data, place.plain_size, path=self.path, offset=place.record_at)
        if place.crc and zlib.crc32(plain) != place.crc:
            raise MalformedRecord(self.path, place.record_at, "a chunk's bytes do not match its CRC")
        return plain

    def _load_chunk(self, number: int) -> bytes:
        broken = self._broken.get(number)
        if broken is not None:
            raise broken
        try:
            return self.read_chunk(self.chunk_table[number])
        except MalformedRecord as exc:
            self._broken[number] = exc
            raise
