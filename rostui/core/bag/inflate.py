"""Chunk decompression bounded by the size each chunk declares and by a cap: no file can make a reader hold more.

Every chunk of both formats states what its data decompresses to (a ``.bag`` chunk's ``size`` field, an MCAP
chunk's ``uncompressed_size``). A chunk declaring more than ``ROSTUI_BAG_MAX_CHUNK`` bytes (1 GiB, ROS's own
limit on one message) is refused before anything is decompressed; the others are decompressed with streaming
decompressors asked for at most one byte more than declared, so a chunk that decompresses to anything but
what it declares is a malformed record, whatever its data holds.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Protocol

from rostui.core.bag.lz4frame import decompress_frame, decompress_frame_into
from rostui.core.bag.model import MalformedRecord

#: What ``ROSTUI_BAG_MAX_CHUNK`` is when unset: a chunk holds at least one message, and ROS refuses messages over
#: a gigabyte (rostui's TCPROS limit, ``ROSTUI_TCPROS_MAX_FRAME``, is the same).
DEFAULT_MAX_CHUNK = 1 << 30

UNCOMPRESSED = ("", "none")
"""The compression names of a chunk stored as it is (a chunk header may leave the name empty)."""

_MIN_ZSTD_WINDOW = 1 << 23
"""zstd frames written without their size known use a window set by the level (8 MiB covers up to level 19)."""


def max_chunk_bytes() -> int:
    """The most bytes one chunk may decompress to (``ROSTUI_BAG_MAX_CHUNK``, 1 GiB when unset)."""
    try:
        return max(0, int(os.environ.get("ROSTUI_BAG_MAX_CHUNK", DEFAULT_MAX_CHUNK)))
    except ValueError:
        return DEFAULT_MAX_CHUNK


class _Streaming(Protocol):
    """What bz2's and lz4.frame's decompressors share."""

    @property
    def eof(self) -> bool: ...
    @property
    def needs_input(self) -> bool: ...
    @property
    def unused_data(self) -> bytes: ...

    def decompress(self, data: bytes | memoryview, max_length: int = -1) -> bytes: ...


def _drain(decompressor: _Streaming, data: bytes | memoryview, limit: int, parts: list[bytes]) -> int:
    """Decompress ``data`` into ``parts`` until ``limit`` bytes, the stream's end or the input's; returns how
    many bytes were added."""
    got = 0
    out = decompressor.decompress(data, max_length=limit)
    while out:
        parts.append(out)
        got += len(out)
        if got >= limit or decompressor.eof or decompressor.needs_input:
            break
        out = decompressor.decompress(b"", max_length=limit - got)
    return got


def _bz2(data: bytes | memoryview, limit: int) -> tuple[list[bytes], bool]:
    """bz2 streams one after the other (as ``bz2.decompress`` reads them), up to ``limit`` bytes; and whether
    the last stream ended."""
    import bz2

    parts: list[bytes] = []
    got = 0
    ended = False
    while data and got < limit:
        stream = bz2.BZ2Decompressor()
        got += _drain(stream, data, limit - got, parts)
        ended = stream.eof
        if not ended:
            break
        data = stream.unused_data
    return parts, ended


def _lz4(data: bytes | memoryview, limit: int) -> tuple[list[bytes], bool]:
    """One lz4 frame, up to ``limit`` bytes; and whether it ended (python-lz4's frame decoder only for frames
    :mod:`~rostui.core.bag.lz4frame` leaves to it)."""
    read = decompress_frame(data, limit)
    if read is not None:
        return read
    import lz4.frame

    frame = lz4.frame.LZ4FrameDecompressor()
    parts: list[bytes] = []
    _drain(frame, data, limit, parts)
    return parts, frame.eof


def _zstd(data: bytes | memoryview, limit: int, declared: int) -> tuple[list[bytes], bool]:
    """zstd frames, up to ``limit`` bytes, with a window no larger than the chunk needs; the frames' end is where
    the reader runs dry (a frame cut short gives fewer bytes)."""
    import zstandard

    window = max(_MIN_ZSTD_WINDOW, 1 << max(declared - 1, 1).bit_length())
    reader = zstandard.ZstdDecompressor(max_window_size=window).stream_reader(data, read_across_frames=True)
    parts: list[bytes] = []
    got = 0
    while got < limit:
        out = reader.read(limit - got)
        if not out:
            break
        parts.append(out)
        got += len(out)
    return parts, True


def _errors() -> tuple[type[Exception], ...]:
    """What the decompressors raise on data that is not theirs (bz2: OSError, lz4: RuntimeError or LZ4BlockError,
    a broken lz4 frame: FrameError, a ValueError; zstd: ZstdError)."""
    import lz4.block
    import zstandard

    return OSError, EOFError, RuntimeError, ValueError, lz4.block.LZ4BlockError, zstandard.ZstdError


def inflate(compression: str, data: bytes | memoryview, declared: int, *, path: str, offset: int,
            buffer: Callable[[int], bytearray] | None = None) -> bytes:
    """The plain bytes of the chunk record at ``offset`` of ``path`` whose ``compression`` data is ``data`` and
    whose header says it holds ``declared`` bytes. ``data`` may be a view of a buffer that is read into again once
    this returns: nothing returned for compressed data refers to it.

    ``buffer(size)`` (a :class:`~rostui.core.bag.chunk_buffers.BufferPool`'s ``take``) gives a bytearray to
    decompress an lz4 chunk into, returned filled when its frame reads straight into it
    (:func:`~rostui.core.bag.lz4frame.decompress_frame_into`); any other chunk, and an lz4 frame that does not,
    take the general way, which also gives a broken one its exact error.

    :class:`~rostui.core.bag.model.MalformedRecord` when the declared size is over the cap, the compression is
    unknown, the data does not decompress, or it decompresses to more or fewer bytes than declared.
    """
    cap = max_chunk_bytes()
    if declared > cap:
        raise MalformedRecord(path, offset, f"a chunk declares {declared} bytes, more than ROSTUI_BAG_MAX_CHUNK "
                                            f"allows ({cap})")
    if compression in UNCOMPRESSED:
        if len(data) != declared:
            raise MalformedRecord(path, offset, f"an uncompressed chunk of {len(data)} bytes declares {declared}")
        return data if isinstance(data, bytes) else bytes(data)
    if buffer is not None and compression == "lz4":
        out = buffer(declared)
        if decompress_frame_into(data, out):
            return out  # a bytearray: it offers all a chunk is read for (struct, memoryview, slices)
    limit = declared + 1
    try:
        if compression == "bz2":
            parts, ended = _bz2(data, limit)
        elif compression == "lz4":
            parts, ended = _lz4(data, limit)
        elif compression == "zstd":
            parts, ended = _zstd(data, limit, declared)
        else:
            raise MalformedRecord(path, offset, f"a chunk has unknown compression {compression!r}")
    except _errors() as exc:
        raise MalformedRecord(path, offset, f"a {compression} chunk does not decompress ({exc})") from None
    got = sum(len(p) for p in parts)
    if got > declared:
        raise MalformedRecord(path, offset, f"a {compression} chunk decompresses past the {declared} bytes it "
                                            "declares")
    if got < declared or not ended:
        raise MalformedRecord(path, offset, f"a {compression} chunk decompresses to {got} of the {declared} bytes "
                                            "it declares")
    return parts[0] if len(parts) == 1 else b"".join(parts)
