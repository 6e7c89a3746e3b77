"""`rostui pkg`: rospack list / rospack find / rosls over rostui's package roots."""

from __future__ import annotations

import locale
import os
from pathlib import Path
from typing import Callable

from rostui.core import packages

__all__ = ["PackageToolError", "list_lines", "find", "ls_target", "ls_entries", "columns"]

EXIT_FIND = 1
"""rospack's exit status when a package is not found."""
EXIT_LS = 2
"""rosls's (ls's) exit status when the path cannot be listed."""


class PackageToolError(Exception):
    """A package or path was not found; ``message`` is the one line, ``code`` the exit status."""

    def __init__(self, message: str, code: int) -> None:
        """Keep the line and the exit status."""
        super().__init__(message)
        self.message = message
        self.code = code


def _not_found(package: str, code: int) -> PackageToolError:
    return PackageToolError(f"[rospack] Error: package '{package}' not found", code)


def list_lines() -> list[str]:
    """``rospack list``: ``name path`` per package, sorted by name."""
    return [f"{name} {path}" for name, path in sorted(packages.list_packages().items())]


def find(package: str) -> Path:
    """``rospack find``: the package directory; raises :class:`PackageToolError` (exit 1)."""
    path = packages.find_package(package)
    if path is None:
        raise _not_found(package, EXIT_FIND)
    return path


def ls_target(spec: str) -> Path:
    """The path ``rosls PKG[/sub]`` lists; raises :class:`PackageToolError` (exit 2) like ls."""
    package, _, rest = spec.partition("/")
    root = packages.find_package(package)
    if root is None:
        raise _not_found(package, EXIT_LS)
    target = Path(f"{root}/{rest}") if rest else root
    try:
        target.stat()
    except NotADirectoryError:
        raise PackageToolError(f"ls: cannot access '{target}': Not a directory", EXIT_LS) from None
    except OSError as exc:
        raise PackageToolError(f"ls: cannot access '{target}': {exc.strerror or 'No such file or directory'}",
                               EXIT_LS) from None
    return target


def _collate_key() -> Callable[[str], str]:
    """Sort key matching ls's order in the current locale (LC_COLLATE)."""
    try:
        locale.setlocale(locale.LC_COLLATE, "")
    except locale.Error:
        pass
    return locale.strxfrm


def ls_entries(target: Path) -> list[str]:
    """What ``ls TARGET`` prints: a file's own path, or a directory's visible entries in ls order."""
    if not target.is_dir():
        return [str(target)]
    try:
        names = [n for n in os.listdir(target) if not n.startswith(".")]
    except OSError as exc:
        raise PackageToolError(f"ls: cannot open directory '{target}': {exc.strerror}", EXIT_LS) from None
    return sorted(names, key=_collate_key())


def columns(names: list[str], width: int) -> list[str]:
    """Lay *names* out in columns, top to bottom then left to right, like ``ls -C``."""
    if not names:
        return []
    n = len(names)
    for rows in range(1, n + 1):
        cols = (n + rows - 1) // rows
        widths = [max(len(names[c * rows + r]) for r in range(rows) if c * rows + r < n) for c in range(cols)]
        if sum(widths) + 2 * (cols - 1) <= width or rows == n:
            break
    lines = []
    for r in range(rows):
        cells = [names[c * rows + r] for c in range(cols) if c * rows + r < n]
        line = "".join(cell.ljust(widths[c] + 2) for c, cell in enumerate(cells[:-1])) + cells[-1]
        lines.append(line)
    return lines
