"""What both bag readers share: their chunk table, a bounded cache of decompressed chunks, and their index
read a chunk at a time.

Both formats index their messages per chunk: a rosbag ``.bag`` has an index-data
record per connection after each chunk, an MCAP file a message-index record per
channel. Readers hand that index out a chunk at a time
(:meth:`ChunkedFile.chunk_infos` for each chunk's times and counts,
:meth:`ChunkedFile.chunk_entries` and :meth:`ChunkedFile.chunk_rows` for one
chunk's entries), so what reads them holds memory by the chunk, not by the
message. Payloads stay on disk: :class:`ChunkCache` decompresses the chunks a
reader asks for and keeps the most recent ones up to a byte budget.
"""

from __future__ import annotations

import os
import zlib
from collections import OrderedDict
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any, NamedTuple

from rostui.core.bag.inflate import UNCOMPRESSED, inflate
from rostui.core.bag.model import Frame, MalformedRecord, frame_of
from rostui.core.records import FrozenRecord

if TYPE_CHECKING:
    from rostui.core.bag.chunk_buffers import BufferPool
    from rostui.core.bag.chunkinfo import ChunkInfos

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


class ChunkEntries(FrozenRecord):
    """The index entries of one chunk (or of messages outside chunks), in the file's order (a record: see
    :mod:`rostui.core.records`)."""

    _fields = ("times", "conn_ids", "offsets", "chunk")
    times: Any
    conn_ids: Any
    offsets: Any
    chunk: int

    def __init__(self, times: Any, conn_ids: Any, offsets: Any, chunk: int) -> None:
        self._set(times, conn_ids, offsets, chunk)


class ChunkCache:
    """Decompressed chunks by number, least recently used dropped first once over ``max_bytes``.

    With a ``pool``, compressed chunks are decompressed into its buffers, and a chunk's buffer goes back to it when
    the chunk is dropped (a player's: :meth:`~rostui.core.bag.fileindex.ChunkedFile.release`)."""

    def __init__(self, load: Callable[[int], bytes], max_bytes: int = CACHE_BYTES) -> None:
        self._load = load
        self.max_bytes = max_bytes
        self._chunks: OrderedDict[int, bytes] = OrderedDict()
        self._bytes = 0
        self.pool: BufferPool | None = None

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
            self._let_go(dropped)
        return data

    def drop(self, chunk: int) -> None:
        """Stop holding chunk ``chunk`` (nothing when it is not held)."""
        data = self._chunks.pop(chunk, None)
        if data is not None:
            self._let_go(data)

    def _let_go(self, data: bytes) -> None:
        self._bytes -= len(data)
        if self.pool is not None and isinstance(data, bytearray):
            self.pool.give(data)

    def clear(self) -> None:
        """Drop every chunk held."""
        self._chunks.clear()
        self._bytes = 0


class ChunkedFile:
    """What both readers share for reading through an index: the chunk table, the chunk cache, and the
    file's own index read once.

    A reader sets ``path``, ``file`` and ``truncated`` and provides ``_index_parts`` (the entries of the file's
    own index, chunk by chunk, or None when it has none), ``_scan_parts`` (the same found by reading every
    chunk), and ``_chunk_index_parts``/``_scanned_chunk_part`` (one chunk's entries, each way); they fill
    ``chunk_table``. A chunk that cannot be read raises the same
    :class:`~rostui.core.bag.model.MalformedRecord` each time it is asked for, without being read again.
    """

    path: str
    file: Any
    truncated: str

    def __init__(self) -> None:
        self.chunk_table: list[ChunkPlace] = []
        """Per chunk number: where it lies and what it declares."""
        self.cache = ChunkCache(self._load_chunk)
        self._infos: ChunkInfos | None = None
        self._infos_read = False
        self._entries_scanned = False
        self._broken: dict[int, MalformedRecord] = {}

    def framer(self, chunk: int) -> Callable[[int], Frame]:
        """The frames of chunk ``chunk``'s messages by offset: each message :meth:`payload` finds, with
        TCPROS's 4-byte length before it."""
        return lambda offset: frame_of(self.payload(chunk, offset))

    def release(self, chunk: int) -> None:
        """Chunk ``chunk`` is not needed again soon (a player is past it): its decompressed bytes leave the cache."""
        self.cache.drop(chunk)

    def payload(self, chunk: int, offset: int) -> bytes:
        """The serialised message whose record lies at ``offset`` of chunk ``chunk`` (each format's own)."""
        raise NotImplementedError

    def chunk_infos(self) -> ChunkInfos | None:
        """Each chunk's times and counts per connection from the file's own index (read once, each chunk's
        entries dropped once counted); None when the file has no usable index."""
        from rostui.core.bag.chunkinfo import ChunkInfos

        if not self._infos_read:
            self._infos_read = True
            parts = self._own_index_parts()
            if parts is not None:
                try:
                    self._infos = ChunkInfos.gather(parts)
                except (MalformedRecord, EOFError) as exc:
                    self._index_unreadable(exc)
                else:
                    self._entries_scanned = False
        return self._infos

    def chunk_spans(self) -> list[tuple[int, int, int]] | None:
        """``(first time, last time, chunk number)`` of every chunk holding messages, from the file's own index
        (messages outside chunks as chunk NO_CHUNK); None when the file has no usable index."""
        infos = self.chunk_infos()
        if infos is None:
            return None
        return list(zip(infos.starts.tolist(), infos.ends.tolist(), infos.numbers.tolist()))

    def chunk_rows(self, number: int) -> list[tuple[int, int, int]]:
        """``(time, offset, connection id)`` of chunk ``number``'s messages (NO_CHUNK: those outside chunks),
        sorted by time, then offset."""
        entries = self._infos.loose if number == NO_CHUNK and self._infos is not None else None
        if entries is None:
            entries = self.chunk_entries(number)
        return list(zip(entries.times.tolist(), entries.offsets.tolist(), entries.conn_ids.tolist()))

    def scan_chunk_infos(self, progress: Callable[[int], None] | None = None) -> ChunkInfos:
        """Each readable chunk's times and counts, by reading every chunk once (a file without an index);
        ``progress(bytes_read)`` after each chunk."""
        from rostui.core.bag.chunkinfo import ChunkInfos

        infos = ChunkInfos.gather(self._fresh_scan(progress), from_file_index=False)
        self._entries_scanned = True
        return infos

    def chunk_entries(self, number: int) -> ChunkEntries:
        """Chunk ``number``'s entries sorted by time, then offset: from the file's index records of that chunk,
        or by reading the chunk when the file was scanned (after :meth:`chunk_infos` or
        :meth:`scan_chunk_infos`); MalformedRecord when they cannot be read."""
        from rostui.core.bag.chunkinfo import sorted_entries

        if not 0 <= number < len(self.chunk_table):
            raise MalformedRecord(self.path, 0, f"no chunk {number} in the file")
        try:
            parts = [self._scanned_chunk_part(number)] if self._entries_scanned else self._chunk_index_parts(number)
        except EOFError:
            raise MalformedRecord(self.path, self.chunk_table[number].record_at,
                                  "the chunk's index runs past the end of the file") from None
        return sorted_entries(parts, number)

    def _fresh_scan(self, progress: Callable[[int], None] | None) -> Iterator[ChunkEntries]:
        self.chunk_table = []
        self._broken = {}
        self.cache.clear()
        return self._scan_parts(progress)

    def _index_unreadable(self, exc: MalformedRecord | EOFError) -> None:
        where = exc.where if isinstance(exc, MalformedRecord) else "it ends early"
        self.truncated = self.truncated or f"its index cannot be read ({where})"

    def _own_index_parts(self) -> Iterator[ChunkEntries] | None:
        """The entries of the file's own index, chunk by chunk in file order (several parts may share a chunk),
        filling ``chunk_table`` as they go; None when the file has none."""
        raise NotImplementedError

    def _scan_parts(self, progress: Callable[[int], None] | None) -> Iterator[ChunkEntries]:
        """The entries found by reading every chunk (messages outside chunks last, as chunk NO_CHUNK)."""
        raise NotImplementedError

    def _chunk_index_parts(self, number: int) -> list[ChunkEntries]:
        """Chunk ``number``'s entries from the file's own index."""
        raise NotImplementedError

    def _scanned_chunk_part(self, number: int) -> ChunkEntries:
        """Chunk ``number``'s entries found by reading the chunk."""
        raise NotImplementedError

    def read_chunk(self, place: ChunkPlace) -> bytes:
        """The plain bytes of the chunk at ``place``: read, decompressed within the size it declares, checked
        against its CRC; MalformedRecord when any of that fails."""
        pool = self.cache.pool
        data: bytes | memoryview
        if pool is not None and place.compression not in UNCOMPRESSED:  # decompressed into a new buffer at once
            data = pool.read_stored(self.file.fileno(), place.data_at, place.stored)
        else:
            self.file.seek(place.data_at)
            data = self.file.read(place.stored)
        if len(data) < place.stored:
            raise MalformedRecord(self.path, place.record_at, "a chunk is cut short")
        plain = inflate(place.compression, data, place.plain_size, path=self.path, offset=place.record_at,
                        buffer=None if pool is None else pool.take)
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
