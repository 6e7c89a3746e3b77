"""Messages for the views, read from their bytes without copying their arrays: numeric arrays are numpy views.

A generated message class turns a ``float32[]`` of ten million ranges into
a list of ten million Python floats (400 MB from a 40 MB message) before a
view has looked at one of them.  The views draw a panel's worth of points
or pixels, so they read a message here instead: its scalars and strings
are read at once, every numeric array is a read-only numpy array over the
received bytes (nothing copied, whatever its length), and an array of
messages is a :class:`LazyArray` that reads an element only when it is
asked for.  Views then stride through the arrays to the size they draw.

Only a type rostui knows is read this way, and only when the publisher's
md5sum is that type's: the spec used is rostui's own, never the peer's
definition.  Bad bytes raise :class:`LazyDecodeError` (one line).
"""

from __future__ import annotations

import struct
from array import array
from typing import Any, Iterator, Sequence

import numpy as np

from rostui.core.msg import Duration, Field, MessageError, MsgSpec, Time, get_message_spec, md5sum

__all__ = ["LazyArray", "LazyDecodeError", "LazyMessage", "decode_lazily", "read_message"]

#: numpy dtype of each primitive as ROS 1 serializes it (little endian).
NUMPY_TYPES: dict[str, str] = {
    "bool": "u1", "int8": "i1", "uint8": "u1", "byte": "i1", "char": "u1", "int16": "<i2", "uint16": "<u2",
    "int32": "<i4", "uint32": "<u4", "int64": "<i8", "uint64": "<u8", "float32": "<f4", "float64": "<f8",
}
_STRUCT = {"bool": "?", "int8": "b", "uint8": "B", "byte": "b", "char": "B", "int16": "h", "uint16": "H",
           "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q", "float32": "f", "float64": "d"}
_U32 = struct.Struct("<I")
_TIME = struct.Struct("<II")
_DURATION = struct.Struct("<ii")
#: Elements an array of zero-byte messages may claim (its bytes bound nothing else).
MAX_EMPTY_ELEMENTS = 1 << 20


class LazyDecodeError(ValueError):
    """A message whose bytes do not hold what its type says (too short, an impossible length); one line."""


class LazyMessage:
    """One message's fields as attributes (``_type`` names its type); arrays are numpy views or :class:`LazyArray`."""

    def __init__(self, type_name: str, fields: dict[str, Any]) -> None:
        self._type = type_name
        self.__dict__.update(fields)

    @property
    def _md5sum(self) -> str:
        """rostui's md5sum of its type: it was read with rostui's own spec of that type."""
        return md5sum(self._type)

    def __repr__(self) -> str:
        return f"<{self._type} read lazily>"


def _sizes(spec: MsgSpec, memo: dict[str, int | None]) -> int | None:
    """Bytes every message of ``spec`` takes, or None when strings or variable arrays make it vary."""
    if spec.type_name in memo:
        return memo[spec.type_name]
    total: int | None = 0
    for f in spec.fields:
        if f.is_array and f.array_len is None or f.base_type == "string":
            total = None
            break
        if f.base_type in NUMPY_TYPES:
            one: int | None = np.dtype(NUMPY_TYPES[f.base_type]).itemsize
        elif f.base_type in ("time", "duration"):
            one = 8
        else:
            one = _sizes(get_message_spec(f.base_type), memo)
        if one is None:
            total = None
            break
        assert total is not None
        total += one * (f.array_len if f.is_array and f.array_len is not None else 1)
    memo[spec.type_name] = total
    return total


class _Reader:
    """Reads messages of known specs out of one buffer; bounds-checked at every length."""

    def __init__(self, buf: memoryview) -> None:
        self.buf = buf
        self.sizes: dict[str, int | None] = {}

    def need(self, offset: int, size: int, what: str) -> None:
        if size < 0 or offset + size > len(self.buf):
            raise LazyDecodeError(f"{what} needs {size} bytes at byte {offset}; the message has {len(self.buf)}")

    def u32(self, offset: int, what: str) -> int:
        self.need(offset, 4, what)
        return int(_U32.unpack_from(self.buf, offset)[0])

    def count(self, f: Field, offset: int, spec: MsgSpec) -> tuple[int, int]:
        """The element count of array field ``f`` and where its elements start."""
        if f.array_len is not None:
            return int(f.array_len), offset
        return self.u32(offset, f"the length of {spec.type_name}.{f.name}"), offset + 4

    def message(self, spec: MsgSpec, offset: int) -> tuple[LazyMessage, int]:
        """The message of ``spec`` at ``offset`` and the offset after it."""
        values: dict[str, Any] = {}
        for f in spec.fields:
            values[f.name], offset = self.field(spec, f, offset)
        return LazyMessage(spec.type_name, values), offset

    def field(self, spec: MsgSpec, f: Field, offset: int) -> tuple[Any, int]:
        base, where = f.base_type, f"{spec.type_name}.{f.name}"
        if not f.is_array:
            if base in _STRUCT:
                size = struct.calcsize("<" + _STRUCT[base])
                self.need(offset, size, where)
                return struct.unpack_from("<" + _STRUCT[base], self.buf, offset)[0], offset + size
            if base == "string":
                return self.string(offset, where)
            if base in ("time", "duration"):
                self.need(offset, 8, where)
                if base == "time":
                    return Time(*_TIME.unpack_from(self.buf, offset)), offset + 8
                return Duration(*_DURATION.unpack_from(self.buf, offset)), offset + 8
            return self.message(get_message_spec(base), offset)
        count, offset = self.count(f, offset, spec)
        if base in NUMPY_TYPES:
            dtype = np.dtype(NUMPY_TYPES[base])
            self.need(offset, count * dtype.itemsize, where)
            values = np.frombuffer(self.buf, dtype=dtype, count=count, offset=offset)
            return values, offset + count * dtype.itemsize
        if base in ("string", "time", "duration"):
            self.need(offset, count * 4, where)  # each element takes at least 4 bytes: the count is bounded
            items = []
            for _ in range(count):
                item, offset = self.field(spec, _scalar(f), offset)
                items.append(item)
            return items, offset
        element = get_message_spec(base)
        lazy = LazyArray(self, element, offset, count, where)
        return lazy, lazy.end

    def string(self, offset: int, where: str) -> tuple[str, int]:
        length = self.u32(offset, where)
        self.need(offset + 4, length, where)
        return bytes(self.buf[offset + 4:offset + 4 + length]).decode("utf-8", "replace"), offset + 4 + length

    def skip(self, spec: MsgSpec, offset: int) -> int:
        """The offset after the message of ``spec`` at ``offset``, reading only lengths."""
        size = _sizes(spec, self.sizes)
        if size is not None:
            self.need(offset, size, spec.type_name)
            return offset + size
        for f in spec.fields:
            base, where = f.base_type, f"{spec.type_name}.{f.name}"
            if not f.is_array:
                if base == "string":
                    offset = self.string_end(offset, where)
                elif base in _STRUCT or base in ("time", "duration"):
                    offset += 8 if base in ("time", "duration") else struct.calcsize("<" + _STRUCT[base])
                else:
                    offset = self.skip(get_message_spec(base), offset)
                self.need(offset, 0, where)
                continue
            count, offset = self.count(f, offset, spec)
            if base in NUMPY_TYPES:
                offset += count * np.dtype(NUMPY_TYPES[base]).itemsize
            elif base in ("time", "duration"):
                offset += 8 * count
            elif base == "string":
                self.need(offset, count * 4, where)
                for _ in range(count):
                    offset = self.string_end(offset, where)
            else:
                offset = LazyArray(self, get_message_spec(base), offset, count, where).end
            self.need(offset, 0, where)
        return offset

    def string_end(self, offset: int, where: str) -> int:
        end = offset + 4 + self.u32(offset, where)
        self.need(end, 0, where)
        return end


def _scalar(f: Field) -> Field:
    """Field ``f`` as one element (an array's item)."""
    return Field(f.name, f.base_type, f.base_type, False, None)


class LazyArray(Sequence[LazyMessage]):
    """An array of messages read one element at a time, when asked for.

    Elements of a fixed size are found by arithmetic; others by one walk over their lengths when the
    array is read (8 bytes of offset kept per element, the elements themselves not built).
    """

    def __init__(self, reader: _Reader, spec: MsgSpec, offset: int, count: int, where: str) -> None:
        self._reader = reader
        self._spec = spec
        self._count = count
        self._size = _sizes(spec, reader.sizes)
        self._starts: array[int] | None = None
        if self._size is not None:
            if self._size == 0 and count > MAX_EMPTY_ELEMENTS:
                raise LazyDecodeError(f"{where} claims {count} empty {spec.type_name} elements")
            reader.need(offset, count * self._size, where)
            self._first = offset
            self.end = offset + count * self._size
            return
        reader.need(offset, count * 4, where)  # an element of varying size takes at least 4 bytes
        starts = array("q")
        for _ in range(count):
            starts.append(offset)
            offset = reader.skip(spec, offset)
        self._starts, self._first, self.end = starts, 0, offset

    def __len__(self) -> int:
        return self._count

    def _at(self, i: int) -> LazyMessage:
        start = self._first + i * self._size if self._size is not None else self._starts[i]  # type: ignore[index]
        return self._reader.message(self._spec, start)[0]

    def __getitem__(self, index: Any) -> Any:
        if isinstance(index, slice):
            return [self._at(i) for i in range(*index.indices(self._count))]
        i = int(index)
        if i < 0:
            i += self._count
        if not 0 <= i < self._count:
            raise IndexError(f"index {index} out of {self._count} elements")
        return self._at(i)

    def __iter__(self) -> Iterator[LazyMessage]:
        for i in range(self._count):
            yield self._at(i)


def read_message(type_name: str, data: bytes | bytearray | memoryview) -> LazyMessage:
    """``data`` (one serialized message of ``type_name``, a type rostui knows) read lazily."""
    try:
        spec = get_message_spec(type_name)
    except MessageError as exc:
        raise LazyDecodeError(str(exc).splitlines()[0]) from None
    return _Reader(memoryview(data).cast("B")).message(spec, 0)[0]


def decode_lazily(raw: Any) -> LazyMessage | None:
    """A received ``AnyMsg`` read lazily, or None when its type is not one rostui knows with the publisher's md5sum.

    (None leaves the message to the generated class built from the publisher's definition.)
    """
    header = getattr(raw, "_connection_header", None) or {}
    type_name, sent_md5 = header.get("type", ""), header.get("md5sum", "")
    try:
        known = md5sum(type_name)
    except MessageError:
        return None
    if sent_md5 not in (known, "*"):
        return None
    return read_message(type_name, raw._buff)
