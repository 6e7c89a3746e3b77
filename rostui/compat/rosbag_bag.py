"""rosbag's ``Bag`` for `rostui python`, over rostui's bag readers and writers (:mod:`rostui.core.bag`).

Reading gives messages in time order through the file's index, a chunk at a
time: what the index says of each chunk (first and last time, counts:
:mod:`rostui.core.bag.chunkinfo`, found by reading the chunks of an unindexed
file when ``allow_unindexed`` is given) and an exact merge of the chunks'
entries, read again as the merge reaches them (:mod:`rostui.core.bag.chunkmerge`),
so the memory a read holds follows the number of chunks, not of messages.
Writing goes through rostui's
writers, so a bag written here is the rosbag v2.0 file rostui's recorder
writes, or an MCAP file when its name ends in ``.mcap``.
Appending to a ``.bag`` continues the file in place
(:mod:`rostui.core.bag.bag_append`); a bag open for writing or appending is
read by flushing its open chunk and reading the file's chunks, as rosbag does.
"""

from __future__ import annotations

import collections
import contextlib
import io
import os
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, NamedTuple

from rostui.core.bag.bag_append import NotIndexed, read_chunk_infos, resume_bag
from rostui.core.bag.chunkmerge import ChunkTable, merged_batches, table_of
from rostui.core.bag.fileindex import ChunkEntries
from rostui.core.bag.files import Reader, Writer, open_reader, open_writer
from rostui.core.bag.mcapfile import MAGIC as MCAP_MAGIC
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.rosbag2_0 import BagWriter
from rostui.core.msg import Message, MessageError, connection_class
from rostui.core.rostime import Time

from .lookup import get_message_class
from .rosbag_files import BagTarget, open_target, stamp_class

__all__ = ["Bag", "BagMessage", "BagMessageWithConnectionHeader", "Compression", "ROSBagException",
           "ROSBagFormatException", "ROSBagUnindexedException", "ROSBagEncryptNotSupportedException",
           "TopicTuple", "TypesAndTopicsTuple", "CompressionTuple"]


class ROSBagException(Exception):
    """A bag cannot be opened, read or written."""

    def __init__(self, value: str = "") -> None:
        super().__init__(value)
        self.value = value

    def __str__(self) -> str:
        return self.value


class ROSBagFormatException(ROSBagException):
    """The file is not a bag, or is damaged."""


class ROSBagUnindexedException(ROSBagException):
    """The bag has no index (it was not closed); ``allow_unindexed=True`` reads it in file order."""

    def __init__(self) -> None:
        super().__init__("Unindexed bag")


class ROSBagEncryptNotSupportedException(ROSBagException):
    """Encrypted bags: rostui reads and writes none."""


class Compression:
    """The chunk compressions a ``.bag`` may use."""

    NONE = "none"
    BZ2 = "bz2"
    LZ4 = "lz4"


BagMessage = collections.namedtuple("BagMessage", "topic message timestamp", module="rosbag.bag")
BagMessageWithConnectionHeader = collections.namedtuple("BagMessageWithConnectionHeader",
                                                        "topic message timestamp connection_header",
                                                        module="rosbag.bag")


class TopicTuple(NamedTuple):
    """One topic in :meth:`Bag.get_type_and_topic_info`: type, count, connection count and median frequency."""

    msg_type: str
    message_count: int
    connections: int
    frequency: float | None


class TypesAndTopicsTuple(NamedTuple):
    """What :meth:`Bag.get_type_and_topic_info` returns: ``{type: md5sum}`` and ``{topic: TopicTuple}``."""

    msg_types: dict[str, str]
    topics: dict[str, TopicTuple]


class CompressionTuple(NamedTuple):
    """What :meth:`Bag.get_compression_info` returns: the main chunk compression and the byte counts."""

    compression: str
    uncompressed: int
    compressed: int


def _ns(stamp: Any) -> int:
    """Nanoseconds of a genpy/rospy ``Time`` (anything with ``secs`` and ``nsecs``) or of a number of seconds."""
    if isinstance(stamp, (int, float)):
        return round(stamp * 1_000_000_000)
    if hasattr(stamp, "to_nsec"):
        return int(stamp.to_nsec())
    return int(stamp.secs) * 1_000_000_000 + int(stamp.nsecs)


def _time(ns: int) -> Time:
    return stamp_class()(ns // 1_000_000_000, ns % 1_000_000_000)


def _canonical(name: str) -> str:
    """A topic name without repeated or trailing slashes, as rosbag compares the topics asked for."""
    if not name or name == "/":
        return name
    while "//" in name:
        name = name.replace("//", "/")
    return name.rstrip("/") or "/"


def _topics(topics: str | Iterable[str] | None) -> set[str] | None:
    if not topics:
        return None
    return {_canonical(topics)} if isinstance(topics, str) else {_canonical(t) for t in topics}


def _header_bytes(conn: Connection) -> dict[str, bytes]:
    """The connection header as rosbag gives it to filters and with ``return_connection_header``: bytes values."""
    return {k: v.encode() for k, v in conn.header_fields().items()}


_COMPRESSIONS = (Compression.NONE, Compression.BZ2, Compression.LZ4)

READ_CACHE_BYTES = 4 * 1024 * 1024
"""Decompressed chunks a bag keeps while it reads messages (the chunk in use is always kept): a read goes
through the chunks in time order, needing more than one only where chunks overlap."""


class Bag:
    """A bag file opened for reading (``'r'``), writing (``'w'``) or appending (``'a'``).

    ``f`` is a file name or a binary file object. The format follows the file:
    a ``.bag`` (rosbag v2.0) or an MCAP file when reading; when writing, a name
    ending in ``.mcap`` makes an MCAP file and any other name (or a file
    object) a rosbag v2.0 file, as rosbag writes. A bag open for writing or appending can be read too. Use
    it as a context manager or ``close()`` it.
    """

    def __init__(self, f: Any, mode: str = "r", compression: str = Compression.NONE,
                 chunk_threshold: int = 768 * 1024, allow_unindexed: bool = False, options: Any = None,
                 skip_index: bool = False) -> None:
        if options is not None:
            if type(options) is not dict:
                raise ValueError("options must be of type dict")
            compression = options.get("compression", compression)
            chunk_threshold = options.get("chunk_threshold", chunk_threshold)
        if compression not in _COMPRESSIONS:
            raise ValueError(f"compression must be one of: {', '.join(_COMPRESSIONS)}")
        if chunk_threshold < 0:
            raise ValueError("chunk_threshold must be greater than or equal to zero")
        if not f:
            raise ValueError("filename (or stream) is invalid")
        if mode not in ("r", "w", "a"):
            raise ValueError(f'mode "{mode}" is invalid')
        self._mode = mode
        self._compression = compression
        self._chunk_threshold = chunk_threshold
        self._allow_unindexed = allow_unindexed
        self._skip_index = skip_index
        self._reader: Reader | None = None
        self._writer: Writer | None = None
        self._stale = False  # the writer wrote since self._reader was opened on its file
        self._topic_ids: dict[str, int] = {}
        self._classes: dict[tuple[str, str, str], type[Message]] = {}
        self._table: tuple[Reader, ChunkTable] | None = None  # the chunks of the reader last read through
        self._open = False
        try:
            self._target: BagTarget = open_target(f, mode)
        except TypeError as exc:
            if mode == "w":
                raise
            raise ROSBagException(str(exc)) from None
        try:
            if mode == "r":
                self._open_read()
            elif mode == "w":
                self._open_write()
            else:
                self._open_append()
        except BaseException:
            self._target.finish(wrote=False)
            raise
        self._open = True

    # --- opening -----------------------------------------------------------------------------------------

    @staticmethod
    def _check_bag_file(path: str) -> bytes:
        """The file's first bytes; OSError as ``open`` raises it, ROSBagException for no bag (rosbag's words)."""
        with open(path, "rb") as f:
            head = f.readline(64)
        if not head:
            raise ROSBagException("empty file")
        if head.startswith(MCAP_MAGIC[:5]):
            return head
        if not head.startswith(b"#ROS") or b" V" not in head:
            raise ROSBagException("This does not appear to be a bag file")
        if not head.startswith(b"#ROSBAG V2.0"):
            raise ROSBagFormatException(f"unsupported bag version: {head.strip().decode(errors='replace')} "
                                        "(rostui reads rosbag v2.0 and MCAP)")
        return head

    def _open_read(self) -> None:
        path = self._target.path
        self._check_bag_file(path)
        try:
            reader = open_reader(path)
        except BagError as exc:
            raise ROSBagFormatException(str(exc)) from None
        if reader.chunk_infos() is None and not self._allow_unindexed:
            reader.close()
            raise ROSBagUnindexedException()
        self._reader = reader

    def _new_writer(self, path: str) -> Writer:
        """An MCAP writer for a name ending in ``.mcap``, else a rosbag v2.0 one (whatever the name, as rosbag)."""
        try:
            if path.endswith(".mcap"):
                writer = open_writer(path, self._compression)
            else:
                writer = BagWriter(path, compression=self._compression)
        except OSError as exc:
            raise ROSBagException(f"cannot create {path}: {exc.strerror}") from None
        except BagError as exc:
            raise ROSBagException(str(exc)) from None
        self._tune(writer)
        return writer

    def _tune(self, writer: Writer) -> None:
        if hasattr(writer, "chunk_bytes"):
            writer.chunk_bytes = max(1, self._chunk_threshold)
        if hasattr(writer, "max_chunk_age"):
            writer.max_chunk_age = float("inf")  # chunks close by size, as rosbag's do

    def _open_write(self) -> None:
        with open(self._target.path, "wb"):  # create or truncate it as rosbag does; errors are open()'s
            pass
        self._writer = self._new_writer(self._target.path)

    def _open_append(self) -> None:
        path = self._target.path
        if not os.path.exists(path):
            open(path, "ab").close()  # rosbag creates the file, then finds it empty
        head = self._check_bag_file(path)
        if head.startswith(MCAP_MAGIC[:5]):
            self._append_by_copy()
            return
        try:
            writer = resume_bag(path, compression=self._compression, chunk_bytes=max(1, self._chunk_threshold),
                                scan_unindexed=self._allow_unindexed)
        except NotIndexed:
            raise ROSBagUnindexedException() from None
        except BagError as exc:
            raise ROSBagFormatException(str(exc)) from None
        self._tune(writer)
        self._writer = writer  # new messages get new connections, even on old topics, as rosbag appends

    def _append_by_copy(self) -> None:
        """MCAP files are appended to by writing their messages into a new file first (rostui's MCAP writer
        only creates files)."""
        path = self._target.path
        backup = f"{path}.rostui-append"
        os.replace(path, backup)
        try:
            reader = open_reader(backup)
            try:
                if reader.chunk_infos() is None and not self._allow_unindexed:
                    raise ROSBagUnindexedException()
                self._writer = self._new_writer(path)
                table = self._chunk_table(reader)
                conns, payload = reader.connections, reader.payload
                for part in merged_batches(table):
                    for conn_id, t, chunk, offset in zip(part.conn_ids.tolist(), part.times.tolist(),
                                                         part.chunks.tolist(), part.offsets.tolist()):
                        conn = conns[conn_id]
                        self._writer.write(self._connection_id(conn.topic, conn.header_fields()), t,
                                           payload(chunk, offset))
                self._table = None
                self._topic_ids = {}  # new messages get new connections, as in a .bag appended to
            finally:
                reader.close()
        except BaseException:
            if self._writer is not None:
                self._writer.close()
                self._writer = None
            os.replace(backup, path)
            raise
        os.remove(backup)

    # --- properties --------------------------------------------------------------------------------------

    @property
    def filename(self) -> str | None:
        """The file's name as given; None for a bag opened on a file object (as rosbag)."""
        return self._target.filename

    @property
    def mode(self) -> str:
        """``'r'``, ``'w'`` or ``'a'``."""
        return self._mode

    @property
    def options(self) -> dict[str, Any]:
        """``{'compression': ..., 'chunk_threshold': ...}``."""
        return {"compression": self._compression, "chunk_threshold": self._chunk_threshold}

    @property
    def compression(self) -> str:
        """The compression of chunks written (``none``, ``bz2`` or ``lz4``); setting it closes the open chunk."""
        return self._compression

    @compression.setter
    def compression(self, value: str) -> None:
        if value not in _COMPRESSIONS:
            raise ValueError(f"compression must be one of: {', '.join(_COMPRESSIONS)}")
        self.flush()
        self._compression = value
        if self._writer is not None and hasattr(self._writer, "compression"):
            self._writer.compression = value

    @property
    def chunk_threshold(self) -> int:
        """Uncompressed bytes after which a chunk is written out; setting it closes the open chunk."""
        return self._chunk_threshold

    @chunk_threshold.setter
    def chunk_threshold(self, value: int) -> None:
        if value < 0:
            raise ValueError("chunk_threshold must be greater than or equal to zero")
        self.flush()
        self._chunk_threshold = value
        if self._writer is not None:
            self._tune(self._writer)

    @property
    def size(self) -> int:
        """The file's size in bytes (what has been written so far, when writing); ValueError when closed."""
        if not self._open:
            raise ValueError("I/O operation on closed bag")
        if self._writer is not None:
            return self._writer.size
        return os.path.getsize(self._target.path)

    @property
    def version(self) -> int:
        """200: rosbag v2.0 (MCAP files too, as rostui reads them through the same API)."""
        return 200

    # --- context manager ---------------------------------------------------------------------------------

    def __enter__(self) -> Bag:
        return self

    def __exit__(self, exc_type: object, exc_value: object, traceback: object) -> None:
        self.close()

    def __iter__(self) -> Iterator[BagMessage]:
        return self.read_messages()

    def close(self) -> None:
        """Finish the file (writing its index) and release it; closing twice does nothing."""
        if not self._open:
            return
        self._open = False
        wrote = self._writer is not None
        try:
            if self._reader is not None:
                reader, self._reader = self._reader, None
                reader.close()
            if self._writer is not None:
                writer, self._writer = self._writer, None
                try:
                    writer.close()
                except BagError as exc:
                    raise ROSBagException(str(exc)) from None
        finally:
            self._target.finish(wrote)

    def flush(self) -> None:
        """Write the open chunk to disk; ValueError on a closed bag."""
        if not self._open:
            raise ValueError("I/O operation on closed bag")
        if self._writer is not None and self._writer.buffered:
            self._writer.flush()
            self._stale = True

    def __str__(self) -> str:
        """What ``rosbag info`` prints for the bag (without rosbag's per-topic frequencies)."""
        from rostui.tools.bag.info import format_info

        with self._peek() as reader:
            summary = reader.summary()
        summary.path = str(self._target.filename)
        return format_info(summary)

    # --- reading -----------------------------------------------------------------------------------------

    def _live_reader(self, flush: bool = True) -> Reader:
        """The reader of an open bag: for one being written, a reader of the chunks written so far (the open
        chunk written out first, unless ``flush`` is False)."""
        if not self._open:
            raise ValueError("I/O operation on closed bag")
        if self._writer is not None:
            if flush:
                self.flush()
            if self._reader is None or self._stale:
                if self._reader is not None:
                    self._reader.close()
                self._reader = open_reader(self._target.path)
                self._stale = False
        assert self._reader is not None
        return self._reader

    @contextlib.contextmanager
    def _peek(self) -> Iterator[Reader]:
        """A reader for the bag's counts and times; a closed bag's file is read again (rosbag answers these
        from the index it keeps after closing)."""
        if self._open:
            # rosbag counts a bag being written from its closed chunks once it has any, else from every message
            closed_chunks = getattr(self._writer, "chunk_infos", None) or getattr(self._writer, "chunk_indexes", None)
            yield self._live_reader(flush=not closed_chunks)
            return
        if self._target.stream is not None:
            raise ValueError("I/O operation on closed bag")
        try:
            reader = open_reader(self._target.path)
        except BagError as exc:
            raise ROSBagException(str(exc)) from None
        try:
            yield reader
        finally:
            reader.close()

    def _chunk_table(self, reader: Reader) -> ChunkTable:
        """The chunks of ``reader``'s file, from its index (or found by reading its chunks, for a file without
        one), kept while the bag reads through the same reader; equal times in connection order, as rosbag's
        merge of its per-connection indexes gives them, then in file order."""
        if self._table is not None and self._table[0] is reader:
            return self._table[1]
        infos = reader.chunk_infos()
        if infos is None:
            infos = reader.scan_chunk_infos()
        reader.cache.max_bytes = min(reader.cache.max_bytes, READ_CACHE_BYTES)

        def load(_file: int, chunk: int) -> ChunkEntries:
            return reader.chunk_entries(chunk)

        table = table_of([infos], load, by_connection=True)
        self._table = (reader, table)
        return table

    def _median_periods(self, reader: Reader, topic_conns: dict[str, list[int]]) -> dict[str, float]:
        """The median period of each topic's messages in time order (seconds), for topics with two or more;
        exact, each pass over the index holding at most the entry budget of periods
        (:mod:`rostui.compat.rosbag_periods`)."""
        from rostui.core.bag import chunkmerge

        from .rosbag_periods import median_periods

        table = self._chunk_table(reader)

        def passes() -> Iterator[tuple[Any, Any]]:
            try:
                for part in merged_batches(table):
                    yield part.times, part.conn_ids
            except BagError as exc:
                raise ROSBagFormatException(str(exc)) from None

        return median_periods(passes, topic_conns, chunkmerge.ENTRY_BUDGET)

    def _index_rows(self, reader: Reader, start: int | None = None, end: int | None = None
                    ) -> Iterator[tuple[list[int], list[int], list[int], list[int]]]:
        """``(connection ids, times, chunks, offsets)`` of the messages from ``start`` to ``end`` (None:
        unbounded; both included) in time order, a block at a time."""
        try:
            for part in merged_batches(self._chunk_table(reader), start, end):
                yield part.conn_ids.tolist(), part.times.tolist(), part.chunks.tolist(), part.offsets.tolist()
        except BagError as exc:
            raise ROSBagFormatException(str(exc)) from None

    def _message_class(self, conn: Connection) -> type[Message]:
        """The class of ``conn``'s messages: the script's own when its md5sum is the bag's, else the class the
        bag's type, md5sum and definition describe, once checked (another version of a type is built from the
        bag's definition, as rosbag does)."""
        key = (conn.type, conn.md5sum, conn.definition)
        cls = self._classes.get(key)
        if cls is None:
            found = get_message_class(conn.type)
            if found is not None and found._md5sum == conn.md5sum:
                cls = found
            else:
                try:
                    cls = connection_class(conn.type, conn.md5sum, conn.definition,
                                           sender=f"the connection of {conn.topic}", stored=True)
                except MessageError as exc:  # refused: a definition that does not hash to its md5sum, or none
                    raise ROSBagException(f"Error generating datatype {conn.type}: {exc}") from None
            self._classes[key] = cls
        return cls

    def _wanted(self, topics: set[str] | None,
                connection_filter: Callable[..., bool] | None) -> Callable[[Connection], bool]:
        decided: dict[int, bool] = {}

        def wanted(conn: Connection) -> bool:
            ok = decided.get(conn.id)
            if ok is None:
                ok = topics is None or conn.topic in topics or _canonical(conn.topic) in topics
                if ok and connection_filter is not None:
                    ok = bool(connection_filter(conn.topic, conn.type, conn.md5sum, conn.definition,
                                                _header_bytes(conn)))
                decided[conn.id] = ok
            return ok

        return wanted

    def read_messages(self, topics: str | Iterable[str] | None = None, start_time: Any = None,
                      end_time: Any = None, connection_filter: Callable[..., bool] | None = None,
                      raw: bool = False, return_connection_header: bool = False) -> Iterator[Any]:
        """``BagMessage(topic, message, timestamp)`` for each message, in time order.

        ``topics`` is one topic or a list (empty or None: all); ``start_time`` and
        ``end_time`` bound the time stamps (both included); ``connection_filter``
        is called as ``f(topic, datatype, md5sum, msg_def, header)``. With ``raw``
        the message is ``(datatype, data, md5sum, position, pytype)``; with
        ``return_connection_header`` a fourth field holds the connection header
        (values as bytes). A bag open for writing shows what was written so far.
        """
        reader = self._live_reader()
        # a zero time bounds nothing, as in rosbag (whose test is the time's truth value)
        start = None if start_time is None else _ns(start_time) or None
        end = None if end_time is None else _ns(end_time) or None
        wanted = self._wanted(_topics(topics), connection_filter)
        return self._generate(reader, start, end, wanted, raw, return_connection_header)

    def _generate(self, reader: Reader, start: int | None, end: int | None, wanted: Callable[[Connection], bool],
                  raw: bool, with_header: bool) -> Iterator[Any]:
        stamp = stamp_class()
        new = object.__new__
        conns = reader.connections
        payload = reader.payload
        chunk_positions = self._chunk_positions(reader) if raw else []
        # MCAP's raw position: the message's place in time order among all the bag's messages
        position = self._chunk_table(reader).count_before(start) if raw and start is not None else 0
        chosen: dict[int, tuple[Connection, type[Message]] | None] = {}  # per connection: None when filtered out
        for conn_ids, times, chunks, offsets in self._index_rows(reader, start, end):
            for conn_id, t, chunk, offset in zip(conn_ids, times, chunks, offsets):
                position += 1
                try:
                    pick = chosen[conn_id]
                except KeyError:
                    conn = conns[conn_id]
                    pick = chosen[conn_id] = (conn, self._message_class(conn)) if wanted(conn) else None
                if pick is None:
                    continue
                conn, cls = pick
                data = payload(chunk, offset)
                if raw:
                    where: Any = (chunk_positions[chunk], offset) if chunk < len(chunk_positions) else position - 1
                    message: Any = (conn.type, bytes(data), conn.md5sum, where, cls)
                else:
                    try:
                        message = cls().deserialize(data)
                    except Exception as exc:  # the generated deserialiser's errors on damaged data
                        raise ROSBagFormatException(f"cannot decode a {conn.type} message on {conn.topic}: "
                                                    f"{exc}") from None
                # a bag's times are unsigned and whole: the stamp needs none of the constructor's checks
                when = new(stamp)
                when.secs, when.nsecs = divmod(t, 1_000_000_000)
                if with_header:
                    yield BagMessageWithConnectionHeader(conn.topic, message, when, _header_bytes(conn))
                else:
                    yield BagMessage(conn.topic, message, when)

    def _chunk_positions(self, reader: Reader) -> list[int]:
        """Where each chunk of a ``.bag`` starts, by chunk number (rosbag's raw position is ``(chunk position,
        offset in the chunk)``); empty for MCAP, whose raw position is the message's place in time order."""
        chunks = getattr(self._writer, "chunk_infos", None)
        if chunks is None:
            if reader.summary().format != "rosbag":
                return []
            try:
                _conns, chunks, _end = read_chunk_infos(self._target.path, scan=True)
            except BagError:
                return []
        return sorted(pos for pos, _start, _end, _counts in chunks)

    def get_message_count(self, topic_filters: str | list[str] | None = None) -> int:
        """How many messages the bag holds, on the given topics only when ``topic_filters`` is given."""
        if topic_filters is not None:
            return sum(t.message_count for t in self.get_type_and_topic_info(topic_filters).topics.values())
        with self._peek() as reader:
            return sum(reader.summary().counts.values())

    def _span(self) -> tuple[int, int]:
        with self._peek() as reader:
            summary = reader.summary()
        if not summary.message_count:
            raise ROSBagException("Bag contains no message")
        return summary.info_span or (summary.start_ns, summary.end_ns)

    def get_start_time(self) -> float:
        """The bag's start, in seconds (its first chunk's start time, as rosbag gives it); ROSBagException
        ``Bag contains no message`` for an empty bag."""
        return _time(self._span()[0]).to_sec()

    def get_end_time(self) -> float:
        """The bag's end, in seconds (its last chunk's end time, as rosbag gives it); ROSBagException
        ``Bag contains no message`` for an empty bag."""
        return _time(self._span()[1]).to_sec()

    def get_type_and_topic_info(self, topic_filters: str | list[str] | None = None) -> TypesAndTopicsTuple:
        """``TypesAndTopicsTuple(msg_types={type: md5sum}, topics={topic: TopicTuple})`` (``frequency`` is
        1 / the median period between the topic's messages, None with fewer than two)."""
        with self._peek() as reader:
            counts = reader.summary().counts
            conns = list(reader.connections.values())
            types: dict[str, str] = {}
            for conn in sorted(conns, key=lambda c: (c.type, c.md5sum, c.definition)):
                types.setdefault(conn.type, conn.md5sum)
            if topic_filters is not None:
                names = sorted(set([topic_filters] if not isinstance(topic_filters, list) else topic_filters))
            else:
                names = sorted({c.topic for c in conns})
            wanted = set(names)
            topic_conns: dict[str, list[int]] = {}
            for conn in conns:
                if conn.topic in wanted:
                    topic_conns.setdefault(conn.topic, []).append(conn.id)
            periods = self._median_periods(reader, topic_conns) if topic_conns else {}
        topics: dict[str, TopicTuple] = {}
        for name in names:
            of_topic = [c for c in conns if c.topic == name]
            if not of_topic:
                continue
            frequency = None
            period = periods.get(name)
            if period is not None and period > 0.0:
                frequency = 1.0 / period
            topics[name] = TopicTuple(of_topic[0].type, sum(counts.get(c.id, 0) for c in of_topic), len(of_topic),
                                      frequency)
        return TypesAndTopicsTuple(types, topics)

    def get_compression_info(self) -> CompressionTuple:
        """``CompressionTuple(compression, uncompressed, compressed)``: the compression most chunks use and the
        byte counts of all chunks (the compression set for writing, and zeros, before any chunk)."""
        with self._peek() as reader:
            summary = reader.summary()
        kinds = summary.chunk_compression
        if not kinds:
            return CompressionTuple(self._compression, 0, 0)
        kind = max(kinds, key=lambda k: (kinds[k], k))
        plain = sum(u for u, _ in summary.chunk_bytes.values())
        packed = sum(p for _, p in summary.chunk_bytes.values())
        return CompressionTuple(kind, plain, packed)

    def reindex(self) -> Iterator[int]:
        """Yields the position of each chunk as the bag's chunks are read to index them (rosbag's progress).

        Opened with ``'a'`` and ``allow_unindexed=True``, an unindexed ``.bag`` was read at opening up to its
        last complete chunk; closing the bag writes its index, as ``rosbag reindex`` does. Read-only bags
        (``'r'``) are indexed in memory only. MCAP files: ROSBagException (use ``rostui bag reindex``).
        """
        if not self._open:
            raise ValueError("I/O operation on closed bag")
        chunks = getattr(self._writer, "chunk_infos", None)
        if chunks is None:
            with open(self._target.path, "rb") as f:
                if f.read(len(MCAP_MAGIC)) == MCAP_MAGIC:
                    raise ROSBagException("rostui's rosbag reindexes .bag files only: use `rostui bag reindex`")
            try:
                _conns, chunks, _end = read_chunk_infos(self._target.path, scan=True)
            except BagError as exc:
                raise ROSBagFormatException(str(exc)) from None
        return iter([pos for pos, _start, _end, _counts in chunks])

    # --- writing -----------------------------------------------------------------------------------------

    def _connection_id(self, topic: str, header: dict[str, str]) -> int:
        """The connection of ``topic``: one per topic, from its first message's header, as rosbag writes."""
        assert self._writer is not None
        conn_id = self._topic_ids.get(topic)
        if conn_id is None:
            conn_id = max(self._writer.connections, default=-1) + 1
            self._topic_ids[topic] = conn_id
            self._writer.add_connection(Connection(conn_id, topic, header.get("type", ""), header.get("md5sum", ""),
                                                   header.get("message_definition", ""), header.get("callerid", ""),
                                                   header.get("latching", "0") == "1"))
        return conn_id

    def write(self, topic: str, msg: Any, t: Any = None, raw: bool = False,
              connection_header: dict[str, str] | None = None) -> None:
        """Append ``msg`` on ``topic`` stamped ``t`` (now when None).

        With ``raw``, ``msg`` is ``(datatype, data, md5sum, position, pytype)`` (or
        rosbag's older ``(datatype, data, md5sum, pytype)``) as ``read_messages(raw=True)``
        gives it. A topic's first ``connection_header`` (or its first message's type)
        makes its connection, as rosbag writes one connection per topic.
        """
        if not self._open:
            raise ValueError("I/O operation on closed bag")
        if self._writer is None:
            raise io.UnsupportedOperation("write")
        if not topic:
            raise ValueError("topic is invalid")
        if not msg:
            raise ValueError("msg is invalid")
        stamp = time.time_ns() if t is None else _ns(t)
        if raw:
            if len(msg) == 5:
                type_name, data, md5sum, _position, pytype = msg
            elif len(msg) == 4:
                type_name, data, md5sum, pytype = msg
            else:
                raise ValueError("msg must be of length 4 or 5")
            if pytype is None:
                pytype = get_message_class(type_name)
                if pytype is None:
                    raise ROSBagException(f"cannot locate message class and no message class provided for "
                                          f"[{type_name}]")
            definition = pytype._full_text
            payload = bytes(data)
        else:
            type_name, md5sum, definition = msg._type, msg._md5sum, msg._full_text
            buff = io.BytesIO()
            msg.serialize(buff)
            payload = buff.getvalue()
        header = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in (connection_header or {}).items()}
        if connection_header is None:
            header = {"topic": topic, "type": type_name, "md5sum": md5sum, "message_definition": definition}
        conn_id = self._connection_id(topic, header)
        try:
            self._writer.write(conn_id, stamp, payload)
        except BagError as exc:
            raise ROSBagException(str(exc)) from None
        self._stale = True
