"""Where ROS logs live on disk, and the per-node log file.

The log root is ``$ROS_LOG_DIR``, else ``$ROS_HOME/log``, else ``~/.ros/log``
(as rospkg resolves it); each master run writes into ``<root>/<run_id>/`` and
``<root>/latest`` is a symlink to the newest run, as roslaunch leaves it.
"""

from __future__ import annotations

import os
import stat
import threading
import time
from pathlib import Path
from typing import Iterator, Mapping, TextIO

from rostui.core.log.levels import Level
from rostui.core.log.record import LogRecord

__all__ = [
    "DISK_CHECK_NOTICE", "DISK_OK_NOTICE", "DISK_WARNING_BYTES", "NodeLogFile", "dir_size",
    "disk_usage_warning", "log_root", "node_log_filename", "ros_home", "run_log_dir",
    "update_latest_link", "walk_stats",
]

#: Above this many bytes (apparent size) roscore warns about the log directory.
DISK_WARNING_BYTES = 1073741824

#: What roscore prints before it measures the log directory.
DISK_CHECK_NOTICE = "Checking log directory for disk usage. This may take a while.\nPress Ctrl-C to interrupt"

#: What roscore prints when the log directory is small enough.
DISK_OK_NOTICE = "Done checking log file disk usage. Usage is <1GB."


def ros_home(env: Mapping[str, str] | None = None) -> Path:
    """``$ROS_HOME``, else ``~/.ros``."""
    env = os.environ if env is None else env
    home = env.get("ROS_HOME")
    return Path(home) if home else Path(os.path.expanduser("~")) / ".ros"


def log_root(env: Mapping[str, str] | None = None) -> Path:
    """The ROS log directory: ``$ROS_LOG_DIR``, else ``$ROS_HOME/log``, else ``~/.ros/log``.

    An empty variable counts as unset (rospkg would take an empty ROS_LOG_DIR
    as the current directory).
    """
    env = os.environ if env is None else env
    explicit = env.get("ROS_LOG_DIR")
    return Path(explicit) if explicit else ros_home(env) / "log"


def run_log_dir(run_id: str, env: Mapping[str, str] | None = None, *, create: bool = True) -> Path:
    """``<log root>/<run_id>`` (created with its parents unless ``create`` is False).

    With ROS_LOG_DIR set this is ``$ROS_LOG_DIR/<run_id>``, as roslaunch makes it.
    """
    if not run_id or "/" in run_id or run_id in (".", ".."):
        raise ValueError(f"invalid run_id '{run_id}'")
    path = log_root(env) / run_id
    if create:
        path.mkdir(parents=True, exist_ok=True)
    return path


def update_latest_link(run_dir: Path | str) -> bool:
    """Point ``<run_dir's parent>/latest`` at ``run_dir`` (absolute), replacing it atomically.

    Returns False (changing nothing) when ``latest`` exists but is not a symlink,
    or when the file system refuses symlinks.
    """
    run_dir = Path(run_dir).absolute()
    latest = run_dir.parent / "latest"
    if os.path.lexists(latest) and not latest.is_symlink():
        return False
    temp = run_dir.parent / f".latest.{os.getpid()}.{threading.get_ident()}"
    try:
        if os.path.lexists(temp):
            os.unlink(temp)
        os.symlink(run_dir, temp)
        os.replace(temp, latest)
    except OSError:
        try:
            os.unlink(temp)
        except OSError:
            pass
        return False
    return True


def walk_stats(path: Path | str) -> Iterator[os.stat_result]:
    """lstat of ``path`` and of everything under it (symlinks not followed), each inode once."""
    seen: set[tuple[int, int]] = set()
    stack = [os.fspath(path)]
    try:
        first = os.lstat(stack[0])
    except OSError:
        return
    seen.add((first.st_dev, first.st_ino))
    yield first
    if not stat.S_ISDIR(first.st_mode):
        return
    while stack:
        current = stack.pop()
        try:
            entries = list(os.scandir(current))
        except OSError:
            continue
        for entry in entries:
            try:
                info = entry.stat(follow_symlinks=False)
            except OSError:
                continue
            key = (info.st_dev, info.st_ino)
            if key in seen:
                continue
            seen.add(key)
            yield info
            if stat.S_ISDIR(info.st_mode):
                stack.append(entry.path)


def dir_size(path: Path | str) -> int:
    """Apparent size in bytes of ``path`` and everything under it (what ``du -sb`` reports); 0 if missing."""
    return sum(info.st_size for info in walk_stats(path))


def disk_usage_warning(root: Path | str | None = None, *, tool: str = "rosclean") -> str | None:
    """roscore's warning when the log directory is over 1 GB, else None.

    The text is roscore's, two lines; ``tool`` names the cleaning command it recommends.
    """
    root = log_root() if root is None else Path(root)
    if dir_size(root) <= DISK_WARNING_BYTES:
        return None
    return (f"WARNING: disk usage in log directory [{root}] is over 1GB.\n"
            f"It's recommended that you use the '{tool}' command.")


def node_log_filename(node_name: str) -> str:
    """rospy's per-node log file name: ``/ns/talker`` -> ``ns_talker.log``."""
    name = node_name.replace("/", "_").lstrip("_")
    if not name:
        raise ValueError(f"invalid node name '{node_name}'")
    return name + ".log"


def close_quietly(handle: TextIO | None) -> None:
    """Close a log file, ignoring the errors a full or vanished disk gives."""
    if handle is not None:
        try:
            handle.close()
        except OSError:
            pass


_PY_LEVEL_NAMES: dict[int, str] = {level.value: level.python_name for level in Level}


class NodeLogFile:
    """A sink appending every record to one node's log file, in rospy's line format.

    Lines read ``[logger][LEVEL] 2026-11-22 11:39:22,721: message`` (local time,
    Python level names, as rospy's per-node files).  The file is opened on the
    first record; write errors (disk full, removed directory) are swallowed.
    """

    def __init__(self, path: Path | str) -> None:
        self.path = Path(path)
        self._file: TextIO | None = None
        self._lock = threading.Lock()
        self._failed = False

    @classmethod
    def for_node(cls, node_name: str, run_dir: Path | str, remapped: str | None = None) -> "NodeLogFile":
        """The file for ``node_name`` in ``run_dir``, or at ``remapped`` (a ``__log:=`` path) if given."""
        if remapped:
            return cls(Path(remapped).absolute())
        return cls(Path(run_dir) / node_log_filename(node_name))

    @staticmethod
    def format(record: LogRecord) -> str:
        """The file line for ``record`` (with newline)."""
        secs, nsecs = divmod(record.stamp, 1_000_000_000)
        when = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(secs))
        level = _PY_LEVEL_NAMES.get(int(record.level), str(int(record.level)))
        return f"[{record.logger}][{level}] {when},{nsecs // 1_000_000:03d}: {record.message}\n"

    def write(self, record: LogRecord) -> None:
        """Append one record and flush."""
        line = self.format(record)
        with self._lock:
            if self._failed:
                return
            try:
                if self._file is None:
                    self.path.parent.mkdir(parents=True, exist_ok=True)
                    self._file = open(self.path, "a", encoding="utf-8", errors="replace")
                self._file.write(line)
                self._file.flush()
            except (OSError, ValueError):
                self._failed = True

    __call__ = write

    def close(self) -> None:
        """Close the file; later records reopen it."""
        with self._lock:
            close_quietly(self._file)
            self._file = None
