"""Bytes of an open file that the kernel hands to a socket itself (``sendfile``), never read into Python.

A bag player sends each message of an uncompressed ``.bag`` chunk as it lies in
the file (a record's data follows its 4-byte length, which is TCPROS's frame).
Reading each chunk and writing each message copied every byte twice;
``os.sendfile`` copies none on the sender's side, and the player holds no
chunk: 29 MB resident against 46 (bench/README.md, "Bag play CPU", third
pass, where the CPU is measured: the same as reading and writing under a rospy
subscriber, less under a bare one).
"""

from __future__ import annotations

import os


class FileRegion:
    """``length`` bytes at ``offset`` of the open file ``fd``: what a subscriber's link hands to ``os.sendfile``,
    and what :meth:`read` reads."""

    __slots__ = ("fd", "offset", "length")

    def __init__(self, fd: int, offset: int, length: int) -> None:
        self.fd = fd
        self.offset = offset
        self.length = length

    def __len__(self) -> int:
        return self.length

    def __bytes__(self) -> bytes:
        return self.read()

    def read(self, start: int = 0) -> bytes:
        """The bytes from ``start`` on; :meth:`cut_short` when the file no longer holds them all."""
        want = self.length - start
        data = os.pread(self.fd, want, self.offset + start)
        if len(data) < want:
            raise self.cut_short()
        return data

    def cut_short(self) -> Exception:
        """The error for a file that lost the region's bytes (cut short while open)."""
        return EOFError(f"{self.length} bytes at byte {self.offset} of a file are no longer there")
