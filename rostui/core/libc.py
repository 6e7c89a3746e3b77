"""The C library's functions through ctypes, found among the symbols this process has already loaded.

``ctypes.util.find_library("c")`` runs ``ldconfig -p`` in a child process on
Linux: a fork and an exec at every start of a command that needed one libc
function. ``CDLL(None)`` looks in this process's own symbols, libc's among them.
"""

from __future__ import annotations

import sys
from typing import Any


def libc_function(name: str) -> Any | None:
    """The libc function ``name`` (errno kept for ``ctypes.get_errno``), or None where there is none (not Linux,
    or not in this libc)."""
    if not sys.platform.startswith("linux"):
        return None
    import ctypes

    try:
        return getattr(ctypes.CDLL(None, use_errno=True), name)
    except (OSError, AttributeError):
        return None
