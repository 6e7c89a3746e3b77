"""Gathered writes: many small pieces and a few big buffers go to a file descriptor without joining them.

Record headers and small messages are copied into one growing buffer (cheap);
big payloads are kept by reference and handed to ``writev`` as they are, so a
1 MB message is copied once, by the kernel into the page cache.
"""

from __future__ import annotations

import ctypes
import os
import sys
from typing import Any

from rostui.core.libc import libc_function

GATHER_LIMIT = 16 * 1024
"""Pieces shorter than this are copied into the shared buffer; longer ones are written from where they are."""
IOV_MAX = 512


class Parts:
    """The buffers of one record or chunk, in order."""

    __slots__ = ("items", "small", "size")

    def __init__(self) -> None:
        self.items: list[Any] = []
        self.small = bytearray()
        self.size = 0

    def add(self, data: Any) -> None:
        """Append ``data`` (bytes-like)."""
        n = len(data)
        if n < GATHER_LIMIT:
            self.small += data
        else:
            if self.small:
                self.items.append(self.small)
                self.small = bytearray()
            self.items.append(data)
        self.size += n

    def buffers(self) -> list[Any]:
        """Every buffer, in order."""
        return self.items + [self.small] if self.small else list(self.items)

    def clear(self) -> None:
        """Forget everything."""
        self.items = []
        self.small = bytearray()
        self.size = 0


def write_all(fd: int, buffers: list[Any]) -> int:
    """Write every buffer in order with ``writev`` (retrying short writes); returns the byte count."""
    total = 0
    i, n = 0, len(buffers)
    head: Any = None  # the unwritten rest of buffers[i] after a short write
    while i < n:
        batch = [head if head is not None else buffers[i], *buffers[i + 1:i + IOV_MAX]]
        written = os.writev(fd, batch)
        total += written
        for buf in batch:
            size = len(buf)
            if written < size:
                head = memoryview(buf)[written:]
                break
            written -= size
            i += 1
            head = None
    return total


_FALLOC_FL_KEEP_SIZE = 1
RESERVE_STEP = 32 * 1024 * 1024


def _load_fallocate() -> Any:
    fallocate = libc_function("fallocate")
    if fallocate is None:
        return None
    fallocate.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int64, ctypes.c_int64]
    fallocate.restype = ctypes.c_int
    return fallocate


_fallocate = _load_fallocate()


class Reservation:
    """File blocks reserved ahead of the writes, without changing the file's size (Linux ``fallocate``
    with ``FALLOC_FL_KEEP_SIZE``).

    Appending into reserved blocks costs the kernel about a quarter less CPU than
    appending into new ones (no delayed-allocation bookkeeping per page). Where the
    file system cannot reserve, or the disk is full, reserving stops silently and
    the writes report the real error. :meth:`release` frees what was reserved
    beyond the end; a process killed while recording leaves at most
    ``RESERVE_STEP`` bytes reserved past the end of its file (not part of it).
    """

    def __init__(self, fd: int, step: int = RESERVE_STEP) -> None:
        self.fd = fd
        self.step = step
        self.reserved = 0
        self.enabled = _fallocate is not None

    def ensure(self, end: int) -> None:
        """Reserve blocks up to at least ``end`` (a step at a time)."""
        if not self.enabled or end <= self.reserved:
            return
        length = max(self.step, end - self.reserved)
        if _fallocate(self.fd, _FALLOC_FL_KEEP_SIZE, self.reserved, length) != 0:
            self.enabled = False
            return
        self.reserved += length

    def release(self, size: int) -> None:
        """Give back the blocks reserved past ``size`` (the file's final length)."""
        if self.reserved > size:
            try:
                os.ftruncate(self.fd, size)
            except OSError:
                pass
        self.reserved = 0
