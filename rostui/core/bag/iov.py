"""Gathered writes: many small pieces and a few big buffers go to a file descriptor without joining them.

Record headers and small messages are copied into one growing buffer (cheap);
big payloads are kept by reference and handed to ``writev`` as they are, so a
1 MB message is copied once, by the kernel into the page cache.
"""

from __future__ import annotations

import os
from typing import Any

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
