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

import os
import sys

MAX_BUFFERS = 4
"""Buffers the pool keeps: a player holds one or two chunks at a time (the one it plays and the next)."""


def _references(buffers: list[bytearray], i: int) -> int:
    return sys.getrefcount(buffers[i])


_ALONE = _references([bytearray(1)], 0)
"""What :func:`_references` counts for a buffer only its list refers to."""


class BufferPool:
    """Bytearrays to decompress chunks into: :meth:`take` one of a given size, :meth:`give` it back when the chunk
    is let go; and one to read each compressed chunk's stored bytes into (:meth:`read_stored`)."""

    def __init__(self, max_buffers: int = MAX_BUFFERS) -> None:
        self.max_buffers = max_buffers
        self._free: list[bytearray] = []
        self._stored = bytearray()

    def read_stored(self, fd: int, at: int, size: int) -> memoryview:
        """Up to ``size`` bytes of the file ``fd`` from ``at`` (fewer at its end), read into the pool's one read
        buffer: valid until the next call, for a chunk decompressed out of them at once and never looked at again.
        Reading each chunk into a new bytes object took twice the time (fresh pages each time: 19.5 against
        10 ms for the 81 MB of the benchmark's lz4 bag, bench/README.md, "Bag play CPU", eighteenth pass)."""
        if len(self._stored) < size:
            self._stored = bytearray(size)  # a new one, not a resize: a view of the old may still be alive
        view = memoryview(self._stored)[:size]
        got = 0
        while got < size:
            n = os.preadv(fd, [view[got:]], at + got)
            if n <= 0:
                break
            got += n
        return view[:got]

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
