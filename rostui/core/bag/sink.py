"""Where a bag writer's bytes go: the end of one file, through the page cache or around it.

Both writers only ever append whole records at the end of their file, cut the
file back to its last complete record after a failed write, and (for ``.bag``)
rewrite the file header once when closing. :class:`AppendFile` does exactly
that with ``writev`` through the page cache. :class:`DirectAppendFile` does it
with ``O_DIRECT``: appended bytes are copied into aligned staging buffers, and
each full buffer is written straight to the device by a small pool of threads
while the next one fills.

Big messages need not be copied at all. The recorder receives each one into
a page-aligned :class:`LendableBuffer` from its pool; the writers pad before
the chunk that starts with it (a private MCAP record, a ``pad`` field in a
``.bag`` chunk header) so that its bytes fall on a block boundary in the
file, and the direct file then writes it from where it is, together with
the staged bytes before it, in one ``pwritev``. The recorder reuses such a
buffer only once :meth:`DirectAppendFile.lent_in_use` no longer lists it.

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

import ctypes
import errno
import fcntl
import mmap
import os
import resource
import time
from collections import deque
from collections.abc import Collection
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any

from rostui.core.bag.iov import Reservation, write_all

__all__ = ["AppendFile", "DirectAppendFile", "LendableBuffer", "open_append", "direct_io_allowed", "BLOCK",
           "STAGING_BYTES", "SYNC_SECONDS", "STAGING_BUFFERS", "WRITE_THREADS", "LEND_MIN"]

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
LEND_MIN = 256 * 1024
"""Lent buffers at least this big are written from where they are (smaller ones are copied: cheap, and the
padding that lines a buffer up, up to one block, would cost more than the copy saves)."""

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

    def lend_padding(self, buffers: list[Any], min_pad: int) -> int:
        """Padding that would let a lent buffer among ``buffers`` be written without a copy: none here."""
        return 0

    def takes_in_place(self, data: Any) -> bool:
        """Whether ``data``, lined up by padding, would be written from where it is: never here."""
        return False

    def lent_in_use(self) -> Collection[int]:
        """The ids of lent buffers that writes still read: none, appends are copied before they return."""
        return ()

    def close(self) -> None:
        """Give back blocks reserved past the end and close the file."""
        try:
            self.reservation.release(self.end)
        finally:
            os.close(self.fd)


class LendableBuffer(bytearray):
    """A buffer its owner lends to a :class:`DirectAppendFile`: appended, it may be written straight from
    where it is, so the owner must not change it while its id is in :meth:`AppendFile.lent_in_use`."""


class _Write:
    """One direct write: where it goes, the aligned pieces it writes (gathered until it is sent), the staging
    buffers they are in, and the lent buffers it borrows; ``future`` once it is sent."""

    __slots__ = ("future", "start", "stop", "views", "staging", "lent")

    def __init__(self, start: int) -> None:
        self.future: Future[None] | None = None
        self.start = self.stop = start
        self.views: list[memoryview] = []
        self.staging: set[int] = set()
        self.lent: list[Any] = []

    def add(self, view: memoryview, staging: int | None, lent: Any) -> None:
        """Append one piece (from staging buffer ``staging``, or from the lent buffer ``lent``)."""
        self.views.append(view)
        self.stop += len(view)
        if staging is not None:
            self.staging.add(staging)
        if lent is not None:
            self.lent.append(lent)


class DirectAppendFile(AppendFile):
    """An :class:`AppendFile` whose appends go through aligned staging buffers with ``O_DIRECT``.

    Appends are copied into the current staging buffer; a full buffer is
    handed to a writing thread and the next one fills meanwhile, so copying
    and the device's own time overlap. A big :class:`LendableBuffer` whose
    address lines up with its place in the file (see :meth:`lend_padding`)
    is not copied: the staged bytes before it and its aligned middle go out
    in one vectored write, and it stays held until that write is done.

    The file always holds correct bytes up to :attr:`durable` (writes that
    finished, in order, or the padded last block followed by a truncate). A
    failed direct write (found when a staging buffer comes round again, or
    at the next sync) turns the file into a plain :class:`AppendFile`: what
    only the staging buffers and lent buffers hold is written through the
    page cache first.
    """

    def __init__(self, path: str, fd: int, staging_bytes: int = STAGING_BYTES, buffers: int = STAGING_BUFFERS) -> None:
        super().__init__(path, fd)
        self._maps = [mmap.mmap(-1, staging_bytes) for _ in range(buffers)]  # page aligned, as O_DIRECT needs
        self._views = [memoryview(m) for m in self._maps]
        self._current = 0
        self._view = self._views[0]
        self._capacity = staging_bytes
        self._pool = ThreadPoolExecutor(max_workers=WRITE_THREADS, thread_name_prefix="rostui-bag-io")
        self._inflight: deque[_Write] = deque()  # sent, oldest first
        self._gathering: _Write | None = None  # pieces not sent yet (they follow every write in flight)
        self._lent: dict[int, int] = {}  # id of a lent buffer -> writes that read it
        self.base = 0  # the file offset byte 0 of the current staging buffer stands for (always block aligned)
        self._fill = 0  # bytes of the current staging buffer in use
        self._written = 0  # bytes of the current buffer (a multiple of BLOCK) the file already has or is getting
        self._done = 0  # bytes of the buffer being appended that are already taken
        self.durable = 0
        self._direct = True
        self._synced_at = time.monotonic()

    @property
    def direct(self) -> bool:
        """True while appends bypass the page cache."""
        return self._direct

    def lend_padding(self, buffers: list[Any], min_pad: int) -> int:
        """Bytes of padding (0, or at least ``min_pad``) that, put before ``buffers``, line the first big
        :class:`LendableBuffer` among them up with its place in the file, so it is written without a copy."""
        if not self._direct:
            return 0
        at = self.end
        for buf in buffers:
            if _lendable(buf):
                gap = (_address(buf) - at) % BLOCK
                return gap + BLOCK if 0 < gap < min_pad else gap
            at += len(buf)
        return 0

    def takes_in_place(self, data: Any) -> bool:
        """True for a big lent buffer: lined up by :meth:`lend_padding`, it is written from where it is (so
        the writers start a chunk with it: only the first big message of a chunk can be lined up)."""
        return self._direct and _lendable(data)

    def lent_in_use(self) -> Collection[int]:
        """The ids of the lent buffers that writes not finished yet still read (the owner must not change or
        reuse those)."""
        self._reap()
        return self._lent.keys()

    def append(self, buffers: list[Any]) -> int:
        """Stage every buffer (or write a lined-up lent one from where it is), sending each staging buffer
        to be written as it fills.

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
        self._reap()
        index = 0
        self._done = 0
        try:
            while index < len(buffers):
                data = memoryview(buffers[index]).cast("B")
                if not (_lendable(data) and self._lend(data)):
                    self._stage(data)
                index, self._done = index + 1, 0
        except OSError:
            self.end = self.base + self._fill
            problem = self._leave_direct()
            if problem is not None:
                raise problem from None
            rest = [memoryview(buffers[index]).cast("B")[self._done:], *buffers[index + 1:]] \
                if index < len(buffers) else []
            super().append(rest)
            return total
        self.end = self.base + self._fill
        return total

    def _stage(self, data: memoryview) -> None:
        """Copy ``data`` (from ``self._done`` on) into the staging buffers."""
        capacity, size = self._capacity, len(data)
        while self._done < size:
            take = min(size - self._done, capacity - self._fill)
            self._view[self._fill:self._fill + take] = data[self._done:self._done + take]
            self._fill += take
            self._done += take
            if self._fill == capacity:
                self._send_full()

    def _lend(self, data: memoryview) -> bool:
        """Write the aligned middle of a lent buffer straight from it (with what is staged before it); stage
        its ends. False when it does not line up with its place in the file."""
        at = self.base + self._fill
        if (_address(data) - at) % BLOCK:
            return False
        head = -at % BLOCK
        middle = (len(data) - head) // BLOCK * BLOCK
        if middle < LEND_MIN:
            return False
        self._stage(data[:head])
        self._queue(self._view[self._written:self._fill], self.base + self._written)
        self._written = self._fill
        self._queue(data[head:head + middle], self.base + self._fill, data.obj)
        self.base += middle
        self._done = head + middle
        self._stage(data)
        return True

    def _queue(self, view: memoryview, start: int, lent: Any = None) -> None:
        """Gather one aligned piece for the next direct write (a piece of the current staging buffer unless
        ``lent`` is given); send the write once it is as big as a staging buffer."""
        if not len(view):
            return
        write = self._gathering
        if write is None:
            write = self._gathering = _Write(start)
        write.add(view, None if lent is not None else self._current, lent)
        if lent is not None:
            self._lent[id(lent)] = self._lent.get(id(lent), 0) + 1
        if write.stop - write.start >= self._capacity:
            self._send()

    def _send(self) -> None:
        """Hand the gathered pieces to a writing thread."""
        write, self._gathering = self._gathering, None
        if write is not None:
            while len(self._inflight) >= len(self._views):  # as much in flight as the staging buffers hold
                self._finish_oldest()
            write.future = self._pool.submit(_write_direct, self.fd, write.views, write.start)
            self._inflight.append(write)

    def _send_full(self) -> None:
        """Queue the rest of the full current buffer and move on to the next one once nothing reads it."""
        self._queue(self._view[self._written:], self.base + self._written)
        self.base += self._capacity
        self._fill = self._written = 0
        self._current = (self._current + 1) % len(self._views)
        self._view = self._views[self._current]
        if self._gathering is not None and self._current in self._gathering.staging:
            self._send()
        while any(self._current in write.staging for write in self._inflight):
            self._finish_oldest()

    def _finish_oldest(self) -> None:
        """Wait for the oldest write sent; its bytes are then durable (or its error is raised)."""
        write = self._inflight[0]
        assert write.future is not None
        write.future.result()
        self._inflight.popleft()
        self._give_back(write)
        self.durable = max(self.durable, write.stop)

    def _give_back(self, write: _Write) -> None:
        """The write no longer reads its lent buffers."""
        for buf in write.lent:
            key = id(buf)
            left = self._lent.pop(key) - 1
            if left:
                self._lent[key] = left
        write.lent = []

    def _reap(self) -> None:
        """Take the writes that already finished well off the front of the queue (a failed one stays, for
        the next append or sync to find and go on through the page cache)."""
        inflight = self._inflight
        while inflight and inflight[0].future.done() and inflight[0].future.exception() is None:  # type: ignore
            self._finish_oldest()

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
            self._send()
            while self._inflight:
                self._finish_oldest()
            if padded > self._written:
                _write_direct(self.fd, [self._view[self._written:padded]], self.base + self._written)
            os.ftruncate(self.fd, self.end)
        except OSError:
            problem = self._leave_direct()
            if problem is not None:
                raise problem from None
            return
        self._written = fill // BLOCK * BLOCK  # the partial block is written again when it grows
        self.durable = self.end

    def _leave_direct(self) -> OSError | None:
        """Go on through the page cache: clear O_DIRECT and write what only the staging and lent buffers hold.

        Returns the error that stopped that write (the file then ends at what it durably holds), or None.
        """
        if not self._direct:
            return None
        self._direct = False
        problem: OSError | None = None
        pending: list[tuple[int, list[memoryview]]] = []  # from the first failed write on, all written again
        writes = list(self._inflight)
        for write in writes:
            try:
                write.future.result()  # type: ignore[union-attr]
            except OSError:
                pending.append((write.start, write.views))
            else:
                if pending:
                    pending.append((write.start, write.views))
                else:
                    self.durable = max(self.durable, write.stop)
        if self._gathering is not None:
            writes.append(self._gathering)
            pending.append((self._gathering.start, self._gathering.views))
        pending.append((self.base + self._written, [self._view[self._written:self._fill]]))
        try:
            flags = fcntl.fcntl(self.fd, fcntl.F_GETFL)
            fcntl.fcntl(self.fd, fcntl.F_SETFL, flags & ~_O_DIRECT)
            for start, views in pending:
                at = start
                for view in views:
                    if not len(view):
                        continue
                    if at > self.durable:
                        raise OSError(errno.EIO, "a staged piece of the file could not be written")
                    stop = at + len(view)
                    while at < stop:
                        at += os.pwrite(self.fd, view[len(view) - (stop - at):], at)
                        self.durable = max(self.durable, at)
        except OSError as exc:
            problem = exc  # the disk may be full: the file keeps what it durably has
        finally:
            for write in writes:
                self._give_back(write)
            self._inflight.clear()
            self._gathering = None
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


def _write_direct(fd: int, views: list[memoryview], offset: int) -> None:
    """Write aligned pieces in one go at ``offset`` (O_DIRECT may write less than asked; then go on)."""
    done, size = 0, sum(len(v) for v in views)
    while done < size:
        written = os.pwritev(fd, views, offset + done) if len(views) > 1 else os.pwrite(fd, views[0], offset + done)
        if written <= 0 or written % BLOCK:
            raise OSError(errno.EIO, f"short direct write of {written} bytes")
        done += written
        views = _after(views, written)


def _after(views: list[memoryview], count: int) -> list[memoryview]:
    """``views`` without their first ``count`` bytes."""
    while views and count >= len(views[0]):
        count -= len(views[0])
        views = views[1:]
    if views and count:
        views = [views[0][count:], *views[1:]]
    return views


def _lendable(buf: Any) -> bool:
    """A buffer big enough to be worth writing from where it is, whose owner lends it (see LendableBuffer)."""
    return len(buf) >= LEND_MIN and isinstance(buf, memoryview) and type(buf.obj) is LendableBuffer


def _address(view: memoryview) -> int:
    """Where a writable buffer's first byte is in memory."""
    return ctypes.addressof(ctypes.c_char.from_buffer(view))


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
