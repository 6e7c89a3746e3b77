"""lz4 frames read and written block by block, their checksums by xxhash.

python-lz4's frame decoder checks a frame's content checksum (which roslz4, the
compressor of ``rosbag record --lz4``, always writes) at 0.75 GB/s on the
benchmark machine; xxhash's one-shot hash does it at 10 GB/s (its streaming
one, which lz4 uses, at 2), and lz4's own block decoder
copies a stored block at memory speed (bench/README.md, "Bag play CPU", third
pass). So this reads the frame format (lz4's ``lz4_Frame_format.md``) itself:
the header, each block (stored or compressed, linked to the previous 64 KiB or
independent, with or without its own checksum), the end mark and the content
checksum, and hands each compressed block to ``lz4.block``, or, with
:func:`decompress_frame_into`, to cramjam's block decoder, which writes it in
place in a buffer the caller gives (python-lz4's copies its output into a new
bytes object).

What it does not read (a dictionary id, reserved bits set, a version other
than 1, a skippable frame) it leaves to python-lz4: :func:`decompress_frame`
returns None for those. :func:`compress_frame` writes roslz4's form the same
way, at 2.2 times the speed of python-lz4's frame compressor.
"""

from __future__ import annotations

import struct

_U32 = struct.Struct("<I")
_U64 = struct.Struct("<Q")
FRAME_MAGIC = 0x184D2204
END_MARK = 0
STORED_BIT = 0x80000000
MAX_RATIO = 255
"""The most bytes one byte of an lz4 block decompresses to (each byte of a match's length adds at most 255)."""
LINK_WINDOW = 64 * 1024
"""How far back a linked block may copy from (lz4's window)."""
_BLOCK_MAX = {4: 64 * 1024, 5: 256 * 1024, 6: 1024 * 1024, 7: 4 * 1024 * 1024}

_FLG_VERSION_SHIFT = 6
_FLG_INDEPENDENT = 0x20
_FLG_BLOCK_CHECKSUM = 0x10
_FLG_CONTENT_SIZE = 0x08
_FLG_CONTENT_CHECKSUM = 0x04
_FLG_RESERVED = 0x02
_FLG_DICT_ID = 0x01
_BD_RESERVED = 0x8F


class FrameError(ValueError):
    """An lz4 frame that breaks the format or fails a checksum."""


class _NotRead(Exception):
    """A frame this module leaves to python-lz4, found out after its header."""


def _header(view: memoryview) -> tuple[int, int, int, int | None] | None:
    """The header of the lz4 frame at the start of ``view``, checked; None for a frame this module leaves to
    python-lz4 (or one cut short in its header: ``(0, 0, -1, None)``)."""
    if len(view) < 7 or _U32.unpack_from(view, 0)[0] != FRAME_MAGIC:
        return None
    flg, bd = view[4], view[5]
    if flg >> _FLG_VERSION_SHIFT != 1 or flg & (_FLG_RESERVED | _FLG_DICT_ID) or bd & _BD_RESERVED:
        return None
    block_max = _BLOCK_MAX.get(bd >> 4)
    if block_max is None:
        return None
    import xxhash  # here: only chunks read from lz4 files need it

    pos = 6 + (8 if flg & _FLG_CONTENT_SIZE else 0)
    if len(view) <= pos:
        return 0, 0, -1, None
    if view[pos] != (xxhash.xxh32_intdigest(view[4:pos]) >> 8) & 0xFF:
        raise FrameError("the frame's header checksum does not match")
    content_size = _U64.unpack_from(view, 6)[0] if flg & _FLG_CONTENT_SIZE else None
    return flg, block_max, pos + 1, content_size


def decompress_frame(data: bytes | memoryview, limit: int) -> tuple[list[bytes], bool] | None:
    """The blocks of the lz4 frame at the start of ``data``, decompressed until they pass ``limit`` bytes or the
    frame ends; and whether it ended (its end mark read and its content checksum, when it has one, matched).

    None for a frame this does not read (see the module); :class:`FrameError` for a broken one (``lz4.block``
    raises its own error for a block that does not decompress).
    """
    view = memoryview(data)
    header = _header(view)
    if header is None:
        return None
    flg, block_max, pos, content_size = header
    if pos < 0:
        return [], False  # cut short in its header
    try:
        parts, end = _blocks(view, pos, flg, block_max, limit)
    except _NotRead:
        return None
    if end is None:
        return parts, False
    if flg & _FLG_CONTENT_CHECKSUM:
        if len(view) < end + 4:
            return parts, False
        parts = [parts[0] if len(parts) == 1 else b"".join(parts)]  # xxhash's one-shot hash is 5x its streaming one
        if not _checksum_matches(parts[0], view, end):
            raise FrameError("the frame's content checksum does not match")
    got = sum(len(p) for p in parts)
    if content_size is not None and content_size != got:
        raise FrameError(f"the frame holds {got} bytes and declares {content_size}")
    return parts, True


def _checksum_matches(content: bytes | bytearray | memoryview, view: memoryview, at: int) -> bool:
    """Whether the content checksum stored at ``at`` of ``view`` is ``content``'s."""
    import xxhash

    return bool(xxhash.xxh32_intdigest(content) == _U32.unpack_from(view, at)[0])


def decompress_frame_into(data: bytes | memoryview, out: bytearray) -> bool:
    """Decompress the lz4 frame at the start of ``data`` straight into ``out``, which it must fill exactly: True
    when it did (a frame of independent blocks, as roslz4 writes, ended by its end mark, every checksum it has
    matching); False for anything else, with ``out`` holding whatever was written, so that the caller reads the
    frame again by :func:`decompress_frame` for its verdict or python-lz4's reading.

    Each block goes into its place in ``out`` (cramjam's block decoder), where :func:`decompress_frame` has
    python-lz4 decompress it into a buffer of its own and copy it into a new bytes object: a player reusing its
    buffers skips that copy of every chunk (bench/README.md, "Bag play CPU", sixteenth pass).
    """
    view = memoryview(data)
    try:
        header = _header(view)
    except FrameError:
        return False
    if header is None or header[2] < 0 or not header[0] & _FLG_INDEPENDENT:
        return False
    flg, block_max, pos, content_size = header
    import cramjam

    decompress_into = cramjam.lz4.decompress_block_into
    checked = bool(flg & _FLG_BLOCK_CHECKSUM)
    target = memoryview(out)
    room = len(out)
    got = 0
    while True:
        try:
            block, stored, pos = _next_block(view, pos, block_max, checked)
        except (_CutShort, FrameError):
            return False
        if block is None:
            break
        size = len(block)
        if stored:
            if size > room - got:
                return False
            target[got:got + size] = block
            written = size
        else:
            space = min(block_max, room - got)
            try:
                written = decompress_into(block, target[got:got + space], output_len=space)
            except Exception:  # noqa: BLE001 - whatever fails here, the general way gives its verdict
                return False
        got += written
    if got != room or (content_size is not None and content_size != got):
        return False
    if flg & _FLG_CONTENT_CHECKSUM:
        if len(view) < pos + 4 or not _checksum_matches(out, view, pos):
            return False
    return True


class _CutShort(Exception):
    """The data ends before the frame does."""


def _next_block(view: memoryview, pos: int, block_max: int, checked: bool) -> tuple[memoryview | None, bool, int]:
    """The block at ``pos``: its bytes as stored, whether it is stored uncompressed, and where the next starts
    (its own checksum, when the frame has them, checked); ``(None, False, where the end mark ends)`` at the end
    mark. :class:`_CutShort` when the data ends first; :class:`FrameError` for a block over the frame's size or
    one whose checksum does not match."""
    if len(view) < pos + 4:
        raise _CutShort
    (size,) = _U32.unpack_from(view, pos)
    pos += 4
    if size == END_MARK:
        return None, False, pos
    stored = bool(size & STORED_BIT)
    size &= ~STORED_BIT
    if size > block_max:
        raise FrameError(f"a block of {size} bytes is over the frame's {block_max}-byte blocks")
    if len(view) < pos + size + (4 if checked else 0):
        raise _CutShort
    block = view[pos:pos + size]
    pos += size
    if checked:
        if not _checksum_matches(block, view, pos):
            raise FrameError("a block's checksum does not match")
        pos += 4
    return block, stored, pos


def _blocks(view: memoryview, pos: int, flg: int, block_max: int, limit: int) -> tuple[list[bytes], int | None]:
    """The frame's blocks from ``pos``: their bytes, and where the end mark ends (None when it was not reached
    within the data or within ``limit`` bytes)."""
    import lz4.block

    linked = not flg & _FLG_INDEPENDENT
    checked = bool(flg & _FLG_BLOCK_CHECKSUM)
    parts: list[bytes] = []
    got = 0
    while got < limit:
        try:
            block, stored, pos = _next_block(view, pos, block_max, checked)
        except _CutShort:
            return parts, None
        if block is None:
            return parts, pos
        if stored:
            out = bytes(block)
        elif linked and parts:
            if len(parts[-1]) < LINK_WINDOW:
                raise _NotRead  # a short block before a linked one: its window spans blocks; python-lz4 keeps it
            out = lz4.block.decompress(block, uncompressed_size=_room(len(block), block_max),
                                       dict=memoryview(parts[-1])[-LINK_WINDOW:])
        else:
            out = lz4.block.decompress(block, uncompressed_size=_room(len(block), block_max))
        parts.append(out)
        got += len(out)
    return parts, None


def _room(size: int, block_max: int) -> int:
    """The buffer a compressed block of ``size`` bytes needs: a frame of many tiny blocks costs no large one each."""
    return min(block_max, MAX_RATIO * size)


ROSLZ4_BLOCK = 1024 * 1024
ROSLZ4_HEADER = bytes.fromhex("04224d18646085")
"""The header roslz4 writes: the magic, FLG 0x64 (version 1, independent blocks, a content checksum, no content
size, no block checksums), BD 0x60 (1 MiB blocks) and the header checksum."""


def compress_frame(data: bytes) -> bytes:
    """``data`` as one lz4 frame in roslz4's form (see :data:`ROSLZ4_HEADER`): a block every 1 MiB, compressed
    by ``lz4.block`` or stored as it is where that is not smaller (as lz4's own frame compressor does), the end
    mark, the content checksum."""
    import lz4.block
    import xxhash

    view = memoryview(data)
    parts = [ROSLZ4_HEADER]
    for start in range(0, len(view), ROSLZ4_BLOCK):
        block = view[start:start + ROSLZ4_BLOCK]
        packed = lz4.block.compress(block, store_size=False)
        if len(packed) < len(block):
            parts += (_U32.pack(len(packed)), packed)
        else:
            parts += (_U32.pack(len(block) | STORED_BIT), block)
    parts += (_U32.pack(END_MARK), _U32.pack(xxhash.xxh32_intdigest(view)))
    return b"".join(parts)
