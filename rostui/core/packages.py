"""ROS package discovery: ROS_PACKAGE_PATH first, then rostui's built-in ``share/``.

A package is a directory holding a ``package.xml``; each root is searched
recursively (without descending into a package, like rospack) and the first
package of a given name wins.  Results are cached and the cache is rebuilt
whenever ROS_PACKAGE_PATH changes (or :func:`clear_cache` is called).
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

__all__ = [
    "PackageNotFoundError",
    "BUILTIN_SHARE",
    "package_roots",
    "list_packages",
    "find_package",
    "get_package_path",
    "clear_cache",
]

BUILTIN_SHARE: Path = Path(__file__).resolve().parent.parent / "share"
"""Directory holding rostui's built-in packages (``rostui/share``)."""

_SKIP_DIRS = {".git", ".hg", ".svn", "__pycache__", "node_modules", ".venv"}


class PackageNotFoundError(LookupError):
    """Raised when a ROS package cannot be found on any package root."""

    def __init__(self, name: str) -> None:
        """Record the missing package *name*."""
        super().__init__(f"package '{name}' not found")
        self.name = name


_lock = threading.Lock()
_cache_key: tuple[str, ...] | None = None
_cache: dict[str, Path] = {}


def package_roots() -> list[Path]:
    """The package search roots in precedence order: ROS_PACKAGE_PATH entries, then built-ins."""
    roots: list[Path] = []
    for entry in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        if entry.strip():
            roots.append(Path(entry.strip()).expanduser())
    roots.append(BUILTIN_SHARE)
    return roots


def _scan_root(root: Path, found: dict[str, Path]) -> None:
    """Add every package below *root* to *found* unless a name is already taken."""
    if not root.is_dir():
        return
    stack = [root]
    seen: set[Path] = set()
    while stack:
        d = stack.pop()
        try:
            real = d.resolve()
        except OSError:
            continue
        if real in seen:
            continue
        seen.add(real)
        if (d / "package.xml").is_file():
            found.setdefault(_package_name(d), d)
            continue
        if (d / "CATKIN_IGNORE").exists() or (d / "rospack_nosubdirs").exists():
            continue
        try:
            children = sorted(
                (c for c in d.iterdir() if c.is_dir() and c.name not in _SKIP_DIRS and not c.name.startswith(".")),
                reverse=True,
            )
        except OSError:
            continue
        stack.extend(children)


def _package_name(pkg_dir: Path) -> str:
    """The ``<name>`` in package.xml, or the directory name if it cannot be read."""
    try:
        text = (pkg_dir / "package.xml").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return pkg_dir.name
    start = text.find("<name>")
    end = text.find("</name>", start + 6)
    if start >= 0 and end > start:
        name = text[start + 6 : end].strip()
        if name:
            return name
    return pkg_dir.name


def _packages() -> dict[str, Path]:
    """The cached name -> directory map, rebuilt when ROS_PACKAGE_PATH changed."""
    global _cache_key, _cache
    key = (os.environ.get("ROS_PACKAGE_PATH", ""),)
    if _cache_key == key:
        return _cache
    with _lock:
        if _cache_key != key:
            found: dict[str, Path] = {}
            for root in package_roots():
                _scan_root(root, found)
            _cache, _cache_key = found, key
        return _cache


def list_packages() -> dict[str, Path]:
    """All known packages, name -> directory (re-scanned when ROS_PACKAGE_PATH changes)."""
    return dict(_packages())


def find_package(name: str) -> Path | None:
    """The directory of package *name*, or None when it is not found."""
    return _packages().get(name)


def get_package_path(name: str) -> Path:
    """The directory of package *name*; raises :class:`PackageNotFoundError` if missing."""
    path = find_package(name)
    if path is None:
        raise PackageNotFoundError(name)
    return path


def clear_cache() -> None:
    """Forget the scanned packages so the next lookup scans again."""
    global _cache_key
    with _lock:
        _cache_key = None


def package_of(path: Path | str) -> str | None:
    """The name of the package holding a file: the nearest package.xml above it, or None."""
    here = Path(path).resolve()
    for folder in [here, *here.parents] if here.is_dir() else here.parents:
        if (folder / "package.xml").is_file():
            return _package_name(folder)
    return None
