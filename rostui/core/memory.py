"""Allocator tuning for large messages.

glibc serves blocks over 128 KiB with mmap and unmaps them on free, so every
new 1 MB message buffer page-faults from scratch; on virtual machines that
costs more than the copy itself.  Raising the mmap and trim thresholds keeps
freed buffers in the heap for reuse.  Only glibc is touched, once per process;
``ROSTUI_NO_MALLOC_TUNING=1`` turns it off. A node tunes it
:data:`TUNE_DELAY` seconds after it starts, so that loading ctypes is not on
the way to a script's first publish (a start makes no large buffer).
"""

from __future__ import annotations

import os
import sys

from rostui.core.libc import libc_function

M_TRIM_THRESHOLD = -1
M_MMAP_THRESHOLD = -3
MMAP_THRESHOLD_BYTES = 64 * 1024 * 1024
TRIM_THRESHOLD_BYTES = 256 * 1024 * 1024

TUNE_DELAY = 0.5
"""Seconds after a node's start when it tunes the allocator (:func:`tune_allocator`)."""

_tuned = False


def tune_allocator() -> bool:
    """Raise glibc's mmap/trim thresholds once; True if the tuning is in effect."""
    global _tuned
    if _tuned:
        return True
    if not sys.platform.startswith("linux") or os.environ.get("ROSTUI_NO_MALLOC_TUNING") == "1":
        return False
    mallopt = libc_function("mallopt")
    if mallopt is None:
        return False
    import ctypes  # here, not at import: 1.6 ms of a node's start (libc_function has imported it already)

    mallopt.argtypes = [ctypes.c_int, ctypes.c_int]
    mallopt.restype = ctypes.c_int
    _tuned = bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES)) and bool(
        mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD_BYTES))
    return _tuned
