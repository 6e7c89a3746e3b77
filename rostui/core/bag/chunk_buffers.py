"""Buffers for decompressed chunks, used again once nothing but the pool refers to them.

A player decompresses every chunk of a compressed bag once and lets it go once
its last message is out. Decompressing each into a new object cost a 1 MiB
allocation and a copy per chunk (python-lz4 copies its output), and spread the
player's working set over fresh memory; with a pool, the chunks of a play take
turns in a few buffers (bench/README.md, "Bag play CPU", sixteenth pass).

A buffer handed back may still be in use: a frame (a memoryview of it) waiting
in a socket's queue, or a caller still holding the chunk. So it is taken again
only when CPython's reference count says the pool holds the only reference
(a memoryview holds one on the buffer it views, however many slices it has):
nothing else can see its bytes change. The count to expect is measured at
import, the same way the pool measures it, so the test does not depend on how
an interpreter counts the references of its own stack.
"""

from __future__ import annotations

import sys

MAX_BUFFERS = 4
"""Buffers the pool keeps: a player holds one or two chunks at a time (the one it plays and the next)."""


def _references(buffers: list[bytearray], i: int) -> int:
    return sys.getrefcount(buffers[i])


_ALONE = _references([bytearray(1)], 0)
"""What :func:`_references` counts for a buffer only its list refers to."""


class BufferPool:
    """Bytearrays to decompress chunks into: :meth:`take` one of a given size, :meth:`give` it back when the chunk
    is let go."""

    def __init__(self, max_buffers: int = MAX_BUFFERS) -> None:
        self.max_buffers = max_buffers
        self._free: list[bytearray] = []

    def take(self, size: int) -> bytearray:
        """A bytearray of ``size`` bytes (its contents are whatever it held): a free buffer nothing else refers to,
        resized, or a new one."""
        free = self._free
        for i in range(len(free)):
            if _references(free, i) == _ALONE:
                buffer = free.pop(i)
                held = len(buffer)
                if size <= held:
                    del buffer[size:]  # within half its allocation: no reallocation
                else:
                    buffer.extend(bytes(size - held))
                return buffer
        return bytearray(size)

    def give(self, buffer: bytearray) -> None:
        """Take ``buffer`` back (it may still be in use: :meth:`take` checks); the oldest goes when the pool is
        full."""
        self._free.append(buffer)
        if len(self._free) > self.max_buffers:
            del self._free[0]
