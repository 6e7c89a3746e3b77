"""ROS package discovery: ROS_PACKAGE_PATH first, then rostui's built-in ``share/``, then Debian's.

A package is a directory holding a ``package.xml`` (or a rosbuild ``manifest.xml``); each root is searched
recursively (without descending into a package, like rospack) and the first
package of a given name wins.  Results are cached and the cache is rebuilt
whenever ROS_PACKAGE_PATH changes (or :func:`clear_cache` is called).

:func:`find_package_dirs` also gives the later directories of the same name:
a file a package should hold but does not (Debian's ``/usr/share/rosgraph_msgs``
has no ``msg/``) is then looked for there, down to rostui's built-in copy.

Debian installs ROS packages as ``/usr/share/<pkg>/package.xml`` and its
rospack finds them with no ROS_PACKAGE_PATH at all; rostui looks there last
(one level deep, as Debian's rospack does), so a package rostui has built in
keeps rostui's own tools.  A directory there holding ``msg/`` or ``srv/``
definitions counts as a package even without a package.xml (Debian's
ros-nav-msgs installs no package.xml).
"""

from __future__ import annotations

import os
import stat
import threading
from collections.abc import Iterator
from pathlib import Path

__all__ = [
    "PackageNotFoundError",
    "BUILTIN_SHARE",
    "SYSTEM_SHARE",
    "package_roots",
    "list_packages",
    "find_package",
    "find_package_dirs",
    "iter_package_dirs",
    "get_package_path",
    "clear_cache",
    "package_of",
    "package_files",
    "executable_dirs",
    "is_executable_file",
    "find_executables",
    "list_executables",
]

BUILTIN_SHARE: Path = Path(__file__).resolve().parent.parent / "share"
"""Directory holding rostui's built-in packages (``rostui/share``)."""

SYSTEM_SHARE: Path = Path("/usr/share")
"""Where Debian installs ROS packages (each directly below it); searched one level deep, last."""

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
_cache_all: dict[str, list[Path]] = {}
_roots_key: tuple[str, ...] | None = None
_roots: dict[str, list[Path]] = {}


def package_roots() -> list[Path]:
    """The recursive package search roots in precedence order: ROS_PACKAGE_PATH entries, then built-ins.

    :data:`SYSTEM_SHARE` comes after them and is not among them: it is searched one level deep.
    """
    roots: list[Path] = []
    for entry in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        if entry.strip():
            roots.append(Path(entry.strip()).expanduser())
    roots.append(BUILTIN_SHARE)
    return roots


def _entries(d: str) -> tuple[set[str], list[str]]:
    """The names of the files and of the directories in *d* (symbolic links followed); OSError if unreadable."""
    files: set[str] = set()
    dirs: list[str] = []
    with os.scandir(d) as it:
        for entry in it:
            try:
                if entry.is_dir():
                    dirs.append(entry.name)
                elif entry.is_file():
                    files.add(entry.name)
            except OSError:
                continue
    return files, dirs


def _scan_root(root: Path, found: dict[str, list[Path]]) -> None:
    """Add every package below *root* to *found*: each name's directories in precedence order."""
    # os.scandir and plain strings: this runs over every package at a node's start, and pathlib costs more than
    # the system calls
    stack = [str(root)]
    seen: set[tuple[int, int]] = set()
    while stack:
        d = stack.pop()
        try:
            st = os.stat(d)
            files, subdirs = _entries(d)
        except OSError:
            continue
        if (st.st_dev, st.st_ino) in seen:
            continue
        seen.add((st.st_dev, st.st_ino))
        if "package.xml" in files or "manifest.xml" in files:  # catkin's, or rosbuild's (rospack)
            path = Path(d)
            dirs = found.setdefault(_package_name(path), [])
            if path not in dirs:
                dirs.append(path)
            continue
        if "CATKIN_IGNORE" in files or "rospack_nosubdirs" in files \
                or "CATKIN_IGNORE" in subdirs or "rospack_nosubdirs" in subdirs:
            continue
        children = sorted((c for c in subdirs if c not in _SKIP_DIRS and not c.startswith(".")), reverse=True)
        stack.extend(os.path.join(d, c) for c in children)


def _scan_share(share: Path, found: dict[str, list[Path]]) -> None:
    """Add the packages directly below *share* (``<share>/<pkg>/package.xml``) to *found*, after the others."""
    try:
        children = sorted(c for c in os.listdir(share) if not c.startswith("."))
    except OSError:
        return
    for name in children:
        d = os.path.join(share, name)
        if os.path.isfile(os.path.join(d, "package.xml")) or _holds_definitions(d):
            path = Path(d)
            dirs = found.setdefault(_package_name(path), [])
            if path not in dirs:
                dirs.append(path)


def _holds_definitions(d: str | Path) -> bool:
    """True for a directory with ``msg/*.msg`` or ``srv/*.srv`` files (Debian's ros-nav-msgs has no package.xml)."""
    for kind in ("msg", "srv"):
        try:
            if any(f.endswith("." + kind) and f != "." + kind for f in os.listdir(os.path.join(d, kind))):
                return True
        except OSError:
            continue
    return False


def _package_name(pkg_dir: Path) -> str:
    """The ``<name>`` in package.xml, or the directory name (a rosbuild package's name, or an unreadable file)."""
    try:
        with open(os.path.join(pkg_dir, "package.xml"), encoding="utf-8", errors="replace") as file:
            text = file.read()
    except OSError:
        return pkg_dir.name
    start = text.find("<name>")
    end = text.find("</name>", start + 6)
    if start >= 0 and end > start:
        name = text[start + 6 : end].strip()
        if name:
            return name
    return pkg_dir.name


def _roots_found(key: tuple[str, ...]) -> dict[str, list[Path]]:
    """The packages below :func:`package_roots` (not :data:`SYSTEM_SHARE`), scanned again when *key* changed;
    the caller holds ``_lock``."""
    global _roots_key, _roots
    if _roots_key != key:
        found: dict[str, list[Path]] = {}
        for root in package_roots():
            _scan_root(root, found)
        _roots, _roots_key = found, key
    return _roots


def _scan_roots() -> dict[str, list[Path]]:
    """The cached name -> directories map of the roots alone: a name found there needs no look at
    :data:`SYSTEM_SHARE` for its first directory (200 folders, most of a node's package lookups)."""
    key = (os.environ.get("ROS_PACKAGE_PATH", ""),)
    if _roots_key == key:
        return _roots
    with _lock:
        return _roots_found(key)


def _scan() -> tuple[dict[str, Path], dict[str, list[Path]]]:
    """The cached maps name -> directory and name -> every directory, rebuilt when ROS_PACKAGE_PATH changed."""
    global _cache_key, _cache, _cache_all
    key = (os.environ.get("ROS_PACKAGE_PATH", ""),)
    if _cache_key == key:
        return _cache, _cache_all
    with _lock:
        if _cache_key != key:
            found = {name: list(dirs) for name, dirs in _roots_found(key).items()}
            _scan_share(SYSTEM_SHARE, found)
            _cache, _cache_all, _cache_key = {name: dirs[0] for name, dirs in found.items()}, found, key
        return _cache, _cache_all


def _packages() -> dict[str, Path]:
    """The cached name -> directory map (the first directory of each name)."""
    return _scan()[0]


def list_packages() -> dict[str, Path]:
    """All known packages, name -> directory (re-scanned when ROS_PACKAGE_PATH changes)."""
    return dict(_packages())


def find_package(name: str) -> Path | None:
    """The directory of package *name*, or None when it is not found."""
    first = _scan_roots().get(name)
    if first:
        return first[0]
    return _packages().get(name)


def find_package_dirs(name: str) -> list[Path]:
    """Every directory of package *name*, first (the one :func:`find_package` gives) to last; [] when none."""
    return list(_scan()[1].get(name, ()))


def iter_package_dirs(name: str) -> Iterator[Path]:
    """The directories :func:`find_package_dirs` gives, in its order, looking in :data:`SYSTEM_SHARE` only
    when the caller asks for more than the roots hold (a lookup the built-in copy answers never scans it)."""
    first = list(_scan_roots().get(name, ()))
    yield from first
    for later in _scan()[1].get(name, ()):
        if later not in first:
            yield later


def get_package_path(name: str) -> Path:
    """The directory of package *name*; raises :class:`PackageNotFoundError` if missing."""
    path = find_package(name)
    if path is None:
        raise PackageNotFoundError(name)
    return path


def clear_cache() -> None:
    """Forget the scanned packages so the next lookup scans again."""
    global _cache_key, _roots_key
    with _lock:
        _cache_key = _roots_key = None


def package_files(name: str, folder: str, pattern: str) -> list[Path]:
    """The files matching *pattern* in *folder* of each directory of package *name*, sorted by file name; where
    two directories hold the same file name, the first directory's (``cfg/*.cfg`` of a package)."""
    found: dict[str, Path] = {}
    for root in find_package_dirs(name):
        try:
            entries = sorted((root / folder).glob(pattern))
        except OSError:
            continue
        for path in entries:
            found.setdefault(path.name, path)
    return [found[file_name] for file_name in sorted(found)]


def package_of(path: Path | str) -> str | None:
    """The name of the package holding a file: the nearest package.xml above it, or None."""
    here = Path(path).resolve()
    for folder in [here, *here.parents] if here.is_dir() else here.parents:
        if (folder / "package.xml").is_file():
            return _package_name(folder)
    return None


# -- executables (``rostui run``) ----------------------------------------------

#: The file that marks a catkin workspace (a devel or install space) in CMAKE_PREFIX_PATH.
CATKIN_MARKER = ".catkin"
#: Where Debian installs ROS packages: catkin's last workspace, always searched.
SYSTEM_PREFIX = Path("/usr")


def catkin_workspaces() -> list[Path]:
    """The catkin workspaces roslib searches, in order: CMAKE_PREFIX_PATH's entries that hold a ``.catkin``
    marker, then ``/usr`` (Debian's catkin always adds it)."""
    entries = [Path(p) for p in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep) if p]
    found = [p for p in entries if (p / CATKIN_MARKER).is_file()]
    return [*found, SYSTEM_PREFIX] if SYSTEM_PREFIX not in found else found


def executable_dirs(package: str) -> list[Path]:
    """Directories searched for *package*'s executables, in roslib's ``find_node`` order (rosrun's too).

    First the first catkin workspace (:func:`catkin_workspaces`) that has ``lib/<pkg>``, ``libexec/<pkg>`` or
    ``share/<pkg>``, those of them that exist; then the package's own directory (ROS_PACKAGE_PATH's, as
    rospack finds it), after the ``<prefix>/lib/<pkg>`` beside it when it lies at ``<prefix>/share/<pkg>``.
    So an installed node (Debian's ``/usr/lib/<pkg>/``) comes before a workspace copy of the same package, as
    roslaunch and rosrun start it. rostui's built-in packages (:data:`BUILTIN_SHARE`,
    found when no ROS_PACKAGE_PATH entry holds the package) are rostui's own install: their executables are
    theirs alone, whatever Debian has installed under the same name.
    Raises :class:`PackageNotFoundError`.
    """
    pkg_dir = get_package_path(package)
    if BUILTIN_SHARE in pkg_dir.parents:
        return [pkg_dir]
    dirs: list[Path] = []
    for workspace in catkin_workspaces():
        dirs = [d for d in (workspace / sub / package for sub in ("lib", "libexec", "share")) if d.is_dir()]
        if dirs:
            break
    prefix_lib = pkg_dir.parent.parent / "lib" / pkg_dir.name  # an install prefix's layout, in no workspace
    if pkg_dir.parent.name == "share" and prefix_lib.is_dir() and prefix_lib not in dirs:
        dirs.append(prefix_lib)
    if pkg_dir not in dirs:
        dirs.append(pkg_dir)
    return dirs


def _walk_entries(top: Path, skip_build: bool, follow: bool = True) -> list[Path]:
    """Every entry below *top* in ``find``'s order (directory order, depth first, pre-order).

    Symlinked directories are followed when *follow* (each real directory once);
    with *skip_build*, ``top/build`` is not entered.
    """
    out: list[Path] = []
    seen: set[tuple[int, int]] = set()

    def visit(d: Path) -> None:
        try:
            st = os.stat(d)
        except OSError:
            return
        if (st.st_dev, st.st_ino) in seen:
            return
        seen.add((st.st_dev, st.st_ino))
        try:
            entries = list(os.scandir(d))
        except OSError:
            return
        for entry in entries:
            path = Path(entry.path)
            out.append(path)
            try:
                is_dir = entry.is_dir(follow_symlinks=follow)
            except OSError:
                is_dir = False
            if is_dir and not (skip_build and d == top and entry.name == "build"):
                visit(path)

    visit(top)
    return out


def is_executable_file(path: Path) -> bool:
    """True for a regular file (after symlinks) with any execute bit set, like ``find -perm /111``."""
    try:
        st = path.stat()
    except OSError:
        return False
    return stat.S_ISREG(st.st_mode) and bool(st.st_mode & 0o111)


def find_executables(package: str, name: str) -> tuple[list[Path], list[Path]]:
    """Files named *name* for ``rostui run``, in rosrun's (``find``'s) order.

    Returns ``(executables, others)``: executable regular files below the
    package's :func:`executable_dirs` (``build/`` directly in the package
    skipped), and every entry named *name* in the package directory that is
    not among them (what rosrun lists as "not files, or not executable").
    Raises :class:`PackageNotFoundError`.
    """
    executables: list[Path] = []
    for top in executable_dirs(package):
        for path in _walk_entries(top, skip_build=True):
            if path.name == name and is_executable_file(path) and path not in executables:
                executables.append(path)
    others = [p for p in _walk_entries(get_package_path(package), skip_build=False, follow=False)
              if p.name == name and p not in executables]
    return executables, others


def list_executables(package: str) -> list[str]:
    """Names of the files ``rostui run`` can start from *package* (executables and ``.py`` files), sorted."""
    names: set[str] = set()
    try:
        dirs = executable_dirs(package)
    except PackageNotFoundError:
        return []
    for top in dirs:
        for path in _walk_entries(top, skip_build=True):
            if path.suffix == ".py" or is_executable_file(path):
                names.add(path.name)
    return sorted(names)
