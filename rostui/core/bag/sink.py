"""Where a bag writer's bytes go: the end of one file, through the page cache or around it.

Both writers only ever append whole records at the end of their file, cut the
file back to its last complete record after a failed write, and (for ``.bag``)
rewrite the file header once when closing. :class:`AppendFile` does exactly
that with ``writev`` through the page cache. :class:`DirectAppendFile` does it
with ``O_DIRECT``: appended bytes are copied into aligned staging buffers, and
each full buffer is written straight to the device by a small pool of threads
while the next one fills.

Why a recorder wants ``O_DIRECT``: every megabyte appended through the page
cache needs 256 newly allocated cache pages. On virtual machines, where the
host backs guest memory lazily, allocating them can cost 1-2 ms of kernel time
per megabyte (``dd`` into a new file measured that on our CI-sized VM, against
0.1 ms to overwrite cached pages), and the dirty pages must still be written
back later. Written directly, a megabyte costs one copy into a staging buffer
that stays mapped, plus about 150 µs of kernel time. Small files gain nothing,
so only the recorder asks for it; ``ROSTUI_BAG_DIRECT_IO=0`` turns it off.

What a killed recorder loses stays bounded: full buffers are written at once,
and :meth:`DirectAppendFile.sync_if_old` (called from the writers' chunk timer)
writes the partial last block, zero-padded, then truncates the file to its real
length. Failures never cost an appended byte that the disk has room for: a
failed direct write sends everything staged through the page cache, and the
file stays that way. Staging is not used where a staged byte could be left
with nowhere to go: a file system that refuses ``O_DIRECT`` and a process with
a file size limit (``RLIMIT_FSIZE``) are written through the page cache from
the start, and staging stops as soon as blocks can no longer be reserved ahead
(a full disk).
"""

from __future__ import annotations

import errno
import fcntl
import mmap
import os
import resource
import time
from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any

from rostui.core.bag.iov import Reservation, write_all

__all__ = ["AppendFile", "DirectAppendFile", "open_append", "direct_io_allowed", "BLOCK", "STAGING_BYTES",
           "SYNC_SECONDS", "STAGING_BUFFERS", "WRITE_THREADS"]

BLOCK = 4096
"""Alignment of direct writes: offsets, lengths and buffer addresses (covers 512- and 4096-byte devices)."""
STAGING_BYTES = 4 * 1024 * 1024
"""One staging buffer of a direct file: written out each time it fills."""
STAGING_BUFFERS = 4
"""Staging buffers per file: one fills while the others are being written."""
WRITE_THREADS = 2
"""Direct writes in flight at once (the device works on two while the writer copies into a third)."""
SYNC_SECONDS = 0.25
"""A partial last block waits at most about this long (plus the writer's timer period) before it is written."""

_O_DIRECT = getattr(os, "O_DIRECT", 0)


def direct_io_allowed() -> bool:
    """True unless ``ROSTUI_BAG_DIRECT_IO`` is ``0`` (or the platform has no ``O_DIRECT``)."""
    return bool(_O_DIRECT) and os.environ.get("ROSTUI_BAG_DIRECT_IO", "1").strip() != "0"


class AppendFile:
    """A new file written only at its end through the page cache, with blocks reserved ahead."""

    def __init__(self, path: str, fd: int | None = None) -> None:
        self.path = path
        self.fd = fd if fd is not None else os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        self.reservation = Reservation(self.fd)
        self.end = 0

    @property
    def direct(self) -> bool:
        """True while appends bypass the page cache."""
        return False

    def append(self, buffers: list[Any]) -> int:
        """Write every buffer in order at the end of the file; returns the byte count."""
        self.reservation.ensure(self.end + sum(len(b) for b in buffers))
        written = write_all(self.fd, buffers)
        self.end += written
        return written

    def rewrite(self, data: bytes, offset: int) -> None:
        """Overwrite bytes already in the file (the ``.bag`` file header at close)."""
        os.pwrite(self.fd, data, offset)

    def cut(self, size: int) -> None:
        """End the file at ``size`` (after a failed append), or at what it holds if that is less: later appends
        continue there."""
        size = min(size, self.end)
        try:
            os.ftruncate(self.fd, size)
            os.lseek(self.fd, size, os.SEEK_SET)
        except OSError:
            pass
        self.end = size

    def sync_if_old(self) -> None:
        """Nothing is held back: every append is already in the page cache."""

    def close(self) -> None:
        """Give back blocks reserved past the end and close the file."""
        try:
            self.reservation.release(self.end)
        finally:
            os.close(self.fd)


class DirectAppendFile(AppendFile):
    """An :class:`AppendFile` whose appends go through aligned staging buffers with ``O_DIRECT``.

    Appends are copied into the current staging buffer; a full buffer is
    handed to a writing thread and the next one fills meanwhile, so copying
    and the device's own time overlap. The file always holds correct bytes
    up to :attr:`durable` (buffers whose write finished, in order, or the
    padded last block followed by a truncate). A failed direct write (found
    when its buffer comes round again, or at the next sync) turns the file
    into a plain :class:`AppendFile`: what only the staging buffers hold is
    written through the page cache first.
    """

    def __init__(self, path: str, fd: int, staging_bytes: int = STAGING_BYTES, buffers: int = STAGING_BUFFERS) -> None:
        super().__init__(path, fd)
        self._maps = [mmap.mmap(-1, staging_bytes) for _ in range(buffers)]  # page aligned, as O_DIRECT needs
        self._views = [memoryview(m) for m in self._maps]
        self._current = 0
        self._view = self._views[0]
        self._capacity = staging_bytes
        self._pool = ThreadPoolExecutor(max_workers=WRITE_THREADS, thread_name_prefix="rostui-bag-io")
        self._inflight: deque[tuple[Future[None], int, int, int]] = deque()  # future, buffer, file start, end
        self.base = 0
        self._fill = 0  # bytes of the current staging buffer in use
        self._written = 0  # bytes of the current buffer (a multiple of BLOCK) the file already has
        self.durable = 0
        self._direct = True
        self._synced_at = time.monotonic()

    @property
    def direct(self) -> bool:
        """True while appends bypass the page cache."""
        return self._direct

    def append(self, buffers: list[Any]) -> int:
        """Copy every buffer into the staging buffers, sending each one to be written as it fills.

        When a direct write fails (now, or one sent earlier), everything staged is written through the page
        cache and the append goes on that way; only an error of that write too is raised.
        """
        if not self._direct:
            return super().append(buffers)
        total = sum(len(b) for b in buffers)
        self.reservation.ensure(self.end + total)
        if not self.reservation.enabled:
            # No blocks could be reserved (a full disk, or a file system without fallocate): from here on, a
            # staged byte might have nowhere to go after its append was reported done, so stage no more.
            problem = self._leave_direct()
            if problem is not None:
                raise problem
            return super().append(buffers)
        capacity = self._capacity
        index, offset = 0, 0
        try:
            while index < len(buffers):
                data = memoryview(buffers[index]).cast("B")
                size = len(data)
                while offset < size:
                    take = min(size - offset, capacity - self._fill)
                    self._view[self._fill:self._fill + take] = data[offset:offset + take]
                    self._fill += take
                    offset += take
                    if self._fill == capacity:
                        self._send_full()
                index, offset = index + 1, 0
        except OSError:
            self.end = self.base + self._fill
            problem = self._leave_direct()
            if problem is not None:
                raise problem from None
            rest = [memoryview(buffers[index]).cast("B")[offset:], *buffers[index + 1:]] if index < len(buffers) \
                else []
            super().append(rest)
            return total
        self.end = self.base + self._fill
        return total

    def _send_full(self) -> None:
        """Queue the full current buffer for writing and move on to the next free one."""
        start, stop = self.base + self._written, self.base + self._capacity
        view = self._views[self._current][self._written:]
        future = self._pool.submit(_write_direct, self.fd, view, start)
        self._inflight.append((future, self._current, start, stop))
        self.base += self._capacity
        self._fill = self._written = 0
        self._current = (self._current + 1) % len(self._views)
        self._view = self._views[self._current]
        while self._inflight and self._inflight[0][1] == self._current:
            self._finish_oldest()

    def _finish_oldest(self) -> None:
        """Wait for the oldest queued write; its bytes are then durable (or its error is raised)."""
        future, _buffer, _start, stop = self._inflight[0]
        future.result()
        self._inflight.popleft()
        self.durable = max(self.durable, stop)

    def sync_if_old(self) -> None:
        """Write the partial last block (zero padded) and trim the file to its length, at most every
        ``SYNC_SECONDS``."""
        if self._direct and self.durable < self.end and time.monotonic() - self._synced_at >= SYNC_SECONDS:
            self.sync()

    def sync(self) -> None:
        """Put everything appended so far into the file."""
        self._synced_at = time.monotonic()
        if not self._direct or self.durable >= self.end:
            return
        fill = self._fill
        padded = -(-fill // BLOCK) * BLOCK
        self._view[fill:padded] = bytes(padded - fill)
        try:
            while self._inflight:
                self._finish_oldest()
            if padded > self._written:
                _write_direct(self.fd, self._view[self._written:padded], self.base + self._written)
            os.ftruncate(self.fd, self.end)
        except OSError:
            problem = self._leave_direct()
            if problem is not None:
                raise problem from None
            return
        self._written = fill // BLOCK * BLOCK  # the partial block is written again when it grows
        self.durable = self.end

    def _leave_direct(self) -> OSError | None:
        """Go on through the page cache: clear O_DIRECT and write what only the staging buffers hold.

        Returns the error that stopped that write (the file then ends at what it durably holds), or None.
        """
        if not self._direct:
            return None
        self._direct = False
        problem: OSError | None = None
        pending = []  # from the first failed write on, every staged piece is written again, in order
        for future, buffer, start, stop in self._inflight:
            try:
                future.result()
            except OSError:
                pending.append((buffer, start, stop))
            else:
                if pending:
                    pending.append((buffer, start, stop))
                else:
                    self.durable = max(self.durable, stop)
        self._inflight.clear()
        pending.append((self._current, self.base + self._written, self.end))
        try:
            flags = fcntl.fcntl(self.fd, fcntl.F_GETFL)
            fcntl.fcntl(self.fd, fcntl.F_SETFL, flags & ~_O_DIRECT)
            for buffer, start, stop in pending:
                if stop <= start:
                    continue
                if start > self.durable:
                    raise OSError(errno.EIO, "a staged piece of the file could not be written")
                first = start - (start // self._capacity * self._capacity)
                view = self._views[buffer]
                at = start
                while at < stop:
                    at += os.pwrite(self.fd, view[first + at - start:first + stop - start], at)
                    self.durable = max(self.durable, at)
        except OSError as exc:
            problem = exc  # the disk may be full: the file keeps what it durably has
        try:
            os.ftruncate(self.fd, self.durable)
            os.lseek(self.fd, self.durable, os.SEEK_SET)
        except OSError as exc:
            problem = problem or exc
        self.end = self.durable
        return problem

    def rewrite(self, data: bytes, offset: int) -> None:
        """Overwrite bytes already in the file, through the page cache (appends continue that way)."""
        problem = self._leave_direct()
        if problem is not None:
            raise problem
        super().rewrite(data, offset)

    def cut(self, size: int) -> None:
        """End the file at ``size``, or at what it could keep if that is less (the disk may be full)."""
        self._leave_direct()
        super().cut(size)

    def close(self) -> None:
        """Write what is staged, trim the padding, and close; raises if the staged bytes could not be written."""
        problem = None
        try:
            problem = self._leave_direct()
        finally:
            self._pool.shutdown(wait=True)
            try:
                super().close()
            finally:
                self._views.clear()
                for staging in self._maps:
                    try:
                        staging.close()
                    except BufferError:  # a view of it is still referenced somewhere: the collector frees it
                        pass
        if problem is not None:
            raise problem


def _write_direct(fd: int, view: memoryview, offset: int) -> None:
    """Write a whole aligned piece at ``offset`` (O_DIRECT may write less than asked; then go on)."""
    done, size = 0, len(view)
    while done < size:
        written = os.pwrite(fd, view[done:], offset + done)
        if written <= 0 or written % BLOCK:
            raise OSError(errno.EIO, f"short direct write of {written} bytes")
        done += written


def open_append(path: str, direct: bool = False) -> AppendFile:
    """A new (truncated) file at ``path`` to append to; with ``direct``, written with ``O_DIRECT`` where the
    file system allows it and :func:`direct_io_allowed` says so."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC
    if direct and direct_io_allowed() and _no_file_size_limit():
        try:
            fd = os.open(path, flags | _O_DIRECT, 0o644)
        except OSError as exc:
            if exc.errno != errno.EINVAL:
                raise
        else:
            if _direct_write_works(fd):
                return DirectAppendFile(path, fd)
            os.close(fd)
    return AppendFile(path, os.open(path, flags, 0o644))


def _no_file_size_limit() -> bool:
    """True without RLIMIT_FSIZE: a direct write crossing such a limit fails as a whole (it cannot be shortened
    to an unaligned length), where a buffered one keeps the bytes below the limit."""
    try:
        return resource.getrlimit(resource.RLIMIT_FSIZE)[0] == resource.RLIM_INFINITY
    except (OSError, ValueError):
        return False


def _direct_write_works(fd: int) -> bool:
    """Write one aligned block and take it back: some file systems open with O_DIRECT but refuse the write."""
    block = mmap.mmap(-1, BLOCK)
    try:
        return os.pwrite(fd, block, 0) == BLOCK
    except OSError:
        return False
    finally:
        block.close()
        try:
            os.ftruncate(fd, 0)
        except OSError:
            pass
