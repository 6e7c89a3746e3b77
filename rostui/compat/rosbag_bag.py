"""rosbag's ``Bag`` for `rostui python`, over rostui's bag readers and writers (:mod:`rostui.core.bag`).

Reading gives messages in time order through the file's index
(:class:`rostui.core.bag.fileindex.FileIndex`, built by scanning an unindexed
file when ``allow_unindexed`` is given); writing goes through
:func:`rostui.core.bag.files.open_writer`, so a ``.bag`` written here is the
rosbag v2.0 file rostui's recorder writes, and any other name an MCAP file.
"""

from __future__ import annotations

import collections
import os
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any, NamedTuple

from rostui.core.bag.files import Reader, Writer, open_reader, open_writer
from rostui.core.bag.model import BagError, Connection
from rostui.core.msg import Message, register_types_from_definition
from rostui.core.rostime import Time

from .lookup import get_message_class

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


BagMessage = collections.namedtuple("BagMessage", "topic message timestamp")
BagMessageWithConnectionHeader = collections.namedtuple("BagMessageWithConnectionHeader",
                                                        "topic message timestamp connection_header")


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


def _median(values: list[float]) -> float:
    ordered = sorted(values)
    half = len(ordered) // 2
    if len(ordered) % 2:
        return ordered[half]
    return float(ordered[half - 1] + ordered[half]) / 2


def _ns(stamp: Any) -> int:
    """Nanoseconds of a genpy/rospy ``Time`` (anything with ``secs`` and ``nsecs``) or of a number of seconds."""
    if isinstance(stamp, (int, float)):
        return round(stamp * 1_000_000_000)
    if hasattr(stamp, "to_nsec"):
        return int(stamp.to_nsec())
    return int(stamp.secs) * 1_000_000_000 + int(stamp.nsecs)


def _time(ns: int) -> Time:
    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


def _topics(topics: str | Iterable[str] | None) -> set[str] | None:
    if not topics:
        return None
    return {topics} if isinstance(topics, str) else set(topics)


class Bag:
    """A bag file opened for reading (``'r'``), writing (``'w'``) or appending (``'a'``).

    The format follows the file: a ``.bag`` (rosbag v2.0) or an MCAP file when
    reading; when writing, a name ending in ``.bag`` makes a rosbag v2.0 file
    and any other name an MCAP file. Use it as a context manager or ``close()`` it.
    """

    def __init__(self, f: str | os.PathLike[str], mode: str = "r", compression: str = Compression.NONE,
                 chunk_threshold: int = 768 * 1024, allow_unindexed: bool = False, options: Any = None,
                 skip_index: bool = False) -> None:
        if not isinstance(f, (str, os.PathLike)):
            raise ValueError("rostui's rosbag opens bags by file name only, not file objects")
        if mode not in ("r", "w", "a"):
            raise ValueError(f"mode {mode!r} is invalid: use 'r', 'w' or 'a'")
        if options is not None and isinstance(options, dict):
            compression = options.get("compression", compression)
            chunk_threshold = options.get("chunk_threshold", chunk_threshold)
        if compression not in (Compression.NONE, Compression.BZ2, Compression.LZ4):
            raise ValueError(f"compression {compression!r} is invalid: use none, bz2 or lz4")
        if chunk_threshold < 0:
            raise ValueError("chunk_threshold must be greater than or equal to zero")
        self._filename = os.fspath(f)
        self._mode = mode
        self._compression = compression
        self._chunk_threshold = chunk_threshold
        self._allow_unindexed = allow_unindexed
        self._skip_index = skip_index
        self._reader: Reader | None = None
        self._writer: Writer | None = None
        self._conn_ids: dict[tuple[str, str, str, str, bool], int] = {}
        self._classes: dict[tuple[str, str], type[Message]] = {}
        try:
            if mode == "r":
                self._open_read()
            else:
                self._open_write(append=mode == "a" and os.path.exists(self._filename))
        except BagError as exc:
            raise ROSBagException(str(exc)) from None

    # --- opening -----------------------------------------------------------------------------------------

    def _open_read(self) -> None:
        with open(self._filename, "rb"):  # a missing or unreadable file raises OSError, as rosbag's open does
            pass
        try:
            reader = open_reader(self._filename)
        except BagError as exc:
            raise ROSBagException(str(exc)) from None
        if reader.file_index() is None and not self._allow_unindexed:
            reader.close()
            raise ROSBagUnindexedException()
        self._reader = reader

    def _open_write(self, append: bool) -> None:
        if not append:
            self._writer = open_writer(self._filename, self._compression)
            self._tune_writer()
            return
        # rostui's writers only create files: appending rewrites the bag's messages into a new file first
        backup = f"{self._filename}.rostui-append"
        os.replace(self._filename, backup)
        try:
            reader = open_reader(backup)
            try:
                self._writer = open_writer(self._filename, self._compression)
                self._tune_writer()
                rows = (reader.messages() if reader.file_index() is None
                        else self._indexed(reader))
                for conn, t, data in rows:
                    self._writer.write(self._connection_id(conn.topic, conn.type, conn.md5sum, conn.definition,
                                                           conn.callerid, conn.latching), t, data)
            finally:
                reader.close()
        except BaseException:
            if self._writer is not None:
                self._writer.close()
            os.replace(backup, self._filename)
            raise
        os.remove(backup)

    def _tune_writer(self) -> None:
        if self._writer is not None and hasattr(self._writer, "chunk_bytes"):
            self._writer.chunk_bytes = max(1, self._chunk_threshold)

    @staticmethod
    def _indexed(reader: Reader) -> Iterator[tuple[Connection, int, bytes]]:
        from rostui.core.bag.files import time_ordered

        return time_ordered(reader)

    # --- properties --------------------------------------------------------------------------------------

    @property
    def filename(self) -> str:
        """The file's name, as given."""
        return self._filename

    @property
    def mode(self) -> str:
        """``'r'``, ``'w'`` or ``'a'``."""
        return self._mode

    @property
    def compression(self) -> str:
        """The compression of chunks written (``none``, ``bz2`` or ``lz4``)."""
        return self._compression

    @property
    def chunk_threshold(self) -> int:
        """Uncompressed bytes after which a chunk is written out."""
        return self._chunk_threshold

    @property
    def size(self) -> int:
        """The file's size in bytes (what has been written so far, when writing)."""
        if self._writer is not None:
            return self._writer.size
        return os.path.getsize(self._filename)

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
        if self._writer is not None:
            writer, self._writer = self._writer, None
            try:
                writer.close()
            except BagError as exc:
                raise ROSBagException(str(exc)) from None
        if self._reader is not None:
            reader, self._reader = self._reader, None
            reader.close()

    def flush(self) -> None:
        """Write the open chunk to disk; ValueError on a closed bag."""
        if self._writer is None and self._reader is None:
            raise ValueError("I/O operation on closed bag")
        if self._writer is not None:
            self._writer.flush()

    def __str__(self) -> str:
        return f"path: {self._filename}\nmode: {self._mode}"

    # --- reading -----------------------------------------------------------------------------------------

    def _open_reader(self) -> Reader:
        if self._reader is not None:
            return self._reader
        if self._writer is None:
            raise ValueError("I/O operation on closed bag")
        raise ROSBagException("rostui's rosbag reads a bag opened for reading ('r') only")

    def _index_rows(self) -> Iterator[tuple[Connection, int, int, int]]:
        """``(connection, time_ns, chunk, offset)`` of every message in time order, equal times in connection
        order as rosbag's merge of its per-connection indexes gives them (file order for an unindexed file)."""
        import numpy as np

        reader = self._open_reader()
        index = reader.file_index()
        if index is None:
            index = reader.scan_index()
        conns = reader.connections
        # the index is sorted by time, ties in file order: a stable sort by (time, connection) keeps that order
        order = np.lexsort((np.arange(len(index)), index.conn_ids, index.times))
        block = 8192
        for lo in range(0, len(order), block):
            rows = order[lo:lo + block]
            yield from zip((conns[c] for c in index.conn_ids[rows].tolist()), index.times[rows].tolist(),
                           index.chunks[rows].tolist(), index.offsets[rows].tolist())

    def _message_class(self, conn: Connection) -> type[Message]:
        key = (conn.type, conn.definition)
        cls = self._classes.get(key)
        if cls is None:
            found = get_message_class(conn.type)
            if found is not None and found._md5sum == conn.md5sum:
                cls = found
            elif conn.definition:
                cls = register_types_from_definition(conn.type, conn.definition)
            elif found is not None:
                cls = found
            else:
                raise ROSBagFormatException(f"no definition of {conn.type} for {conn.topic}")
            self._classes[key] = cls
        return cls

    def _wanted(self, topics: set[str] | None,
                connection_filter: Callable[..., bool] | None) -> Callable[[Connection], bool]:
        decided: dict[int, bool] = {}

        def wanted(conn: Connection) -> bool:
            ok = decided.get(conn.id)
            if ok is None:
                ok = topics is None or conn.topic in topics
                if ok and connection_filter is not None:
                    ok = bool(connection_filter(conn.topic, conn.type, conn.md5sum, conn.definition,
                                                conn.header_fields()))
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
        the message is ``(datatype, data, md5sum, position, pytype)``.
        """
        reader = self._open_reader()
        # a zero time bounds nothing, as in rosbag (whose test is the time's truth value)
        start = None if start_time is None else _ns(start_time) or None
        end = None if end_time is None else _ns(end_time) or None
        wanted = self._wanted(_topics(topics), connection_filter)
        return self._generate(reader, start, end, wanted, raw, return_connection_header)

    def _generate(self, reader: Reader, start: int | None, end: int | None, wanted: Callable[[Connection], bool],
                  raw: bool, with_header: bool) -> Iterator[Any]:
        for position, (conn, t, chunk, offset) in enumerate(self._index_rows()):
            if (start is not None and t < start) or not wanted(conn):
                continue
            if end is not None and t > end:
                break
            data = reader.payload(chunk, offset)
            cls = self._message_class(conn)
            if raw:
                message: Any = (conn.type, bytes(data), conn.md5sum, position, cls)
            else:
                try:
                    message = cls().deserialize(bytes(data))
                except Exception as exc:  # the generated deserialiser's errors on damaged data
                    raise ROSBagFormatException(f"cannot decode a {conn.type} message on {conn.topic}: "
                                                f"{exc}") from None
            if with_header:
                yield BagMessageWithConnectionHeader(conn.topic, message, _time(t), conn.header_fields())
            else:
                yield BagMessage(conn.topic, message, _time(t))

    def _connections(self) -> list[Connection]:
        return list(self._open_reader().connections.values())

    def _counts(self) -> dict[int, int]:
        return self._open_reader().summary().counts

    def get_message_count(self, topic_filters: str | list[str] | None = None) -> int:
        """How many messages the bag holds, on the given topics only when ``topic_filters`` is given."""
        if topic_filters is not None:
            return sum(t.message_count for t in self.get_type_and_topic_info(topic_filters).topics.values())
        return sum(self._counts().values())

    def _span(self) -> tuple[int, int]:
        summary = self._open_reader().summary()
        if not summary.message_count:
            raise ROSBagException("Bag contains no message")
        return summary.info_span or (summary.start_ns, summary.end_ns)

    def get_start_time(self) -> float:
        """The bag's start, in seconds (its first chunk's start time, as rosbag gives it)."""
        return _time(self._span()[0]).to_sec()

    def get_end_time(self) -> float:
        """The bag's end, in seconds (its last chunk's end time, as rosbag gives it)."""
        return _time(self._span()[1]).to_sec()

    def get_type_and_topic_info(self, topic_filters: str | list[str] | None = None) -> TypesAndTopicsTuple:
        """``TypesAndTopicsTuple(msg_types={type: md5sum}, topics={topic: TopicTuple})`` (``frequency`` is
        1 / the median period between the topic's messages, None with fewer than two)."""
        conns = self._connections()
        types: dict[str, str] = {}
        for conn in sorted(conns, key=lambda c: (c.type, c.md5sum, c.definition)):
            types.setdefault(conn.type, conn.md5sum)
        if topic_filters is not None:
            names = sorted(set([topic_filters] if not isinstance(topic_filters, list) else topic_filters))
        else:
            names = sorted({c.topic for c in conns})
        counts = self._counts()
        stamps: dict[str, list[float]] = {}
        if names:
            wanted = set(names)
            for conn, t, _chunk, _offset in self._index_rows():
                if conn.topic in wanted:
                    stamps.setdefault(conn.topic, []).append(_time(t).to_sec())
        topics: dict[str, TopicTuple] = {}
        for name in names:
            of_topic = [c for c in conns if c.topic == name]
            if not of_topic:
                continue
            frequency = None
            seen = stamps.get(name, [])
            if len(seen) > 1:
                period = _median([b - a for a, b in zip(seen, seen[1:])])
                if period > 0.0:
                    frequency = 1.0 / period
            topics[name] = TopicTuple(of_topic[0].type, sum(counts.get(c.id, 0) for c in of_topic), len(of_topic),
                                      frequency)
        return TypesAndTopicsTuple(types, topics)

    def get_compression_info(self) -> CompressionTuple:
        """``CompressionTuple(compression, uncompressed, compressed)``: the main chunk compression and sizes."""
        summary = self._open_reader().summary()
        kinds = summary.chunk_compression
        kind = max(kinds, key=lambda k: kinds[k]) if kinds else "none"
        plain = sum(u for u, _ in summary.chunk_bytes.values())
        packed = sum(p for _, p in summary.chunk_bytes.values())
        return CompressionTuple(kind, plain, packed)

    # --- writing -----------------------------------------------------------------------------------------

    def _connection_id(self, topic: str, type_name: str, md5sum: str, definition: str, callerid: str = "",
                       latching: bool = False) -> int:
        assert self._writer is not None
        key = (topic, type_name, md5sum, callerid, latching)
        conn_id = self._conn_ids.get(key)
        if conn_id is None:
            conn_id = self._conn_ids[key] = len(self._conn_ids)
            self._writer.add_connection(Connection(conn_id, topic, type_name, md5sum, definition, callerid,
                                                   latching))
        return conn_id

    def write(self, topic: str, msg: Any, t: Any = None, raw: bool = False,
              connection_header: dict[str, str] | None = None) -> None:
        """Append ``msg`` on ``topic`` stamped ``t`` (now when None).

        With ``raw``, ``msg`` is ``(datatype, data, md5sum, position, pytype)`` (or
        rosbag's older ``(datatype, data, md5sum, pytype)``) as ``read_messages(raw=True)``
        gives it. ``connection_header`` may carry ``callerid`` and ``latching``.
        """
        if self._writer is None:
            if self._reader is not None:
                raise ROSBagException("the bag is open for reading, not writing")
            raise ValueError("I/O operation on closed bag")
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
                raise ValueError("raw messages are (datatype, data, md5sum, position, pytype)")
            definition = pytype._full_text
            payload = bytes(data)
        else:
            type_name, md5sum, definition = msg._type, msg._md5sum, msg._full_text
            from io import BytesIO

            buff = BytesIO()
            msg.serialize(buff)
            payload = buff.getvalue()
        header = connection_header or {}
        topic = header.get("topic", topic)
        conn_id = self._connection_id(topic, header.get("type", type_name), header.get("md5sum", md5sum),
                                      header.get("message_definition", definition), header.get("callerid", ""),
                                      header.get("latching", "0") == "1")
        try:
            self._writer.write(conn_id, stamp, payload)
        except BagError as exc:
            raise ROSBagException(str(exc)) from None
