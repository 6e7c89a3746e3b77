"""What rosbag's ``Bag`` is given to open, turned into a file name rostui's bag readers and writers take.

rosbag opens a file name or an open binary file object. rostui's readers and
writers work on paths, so a file object naming a file on disk is used by that
name, and any other stream (``io.BytesIO``, a pipe) goes through a temporary
``.bag`` file: its bytes are copied in when the bag is read or appended to, and
the finished bag is copied back into the stream when the bag is closed.

Time stamps: rosbag gives ``rospy.Time``. When the ``rospy`` a script imports
is rostui's own (:mod:`rostui.compat.pylib.rospy`), the stamps are its
``rospy.Time``, so their type and ``repr()`` are rosbag's; otherwise they are
rostui's ``genpy.Time``.
"""

from __future__ import annotations

import importlib
import io
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

from rostui.core.rostime import Time

__all__ = ["BagTarget", "stamp_class", "open_target"]

_PYLIB = Path(__file__).resolve().parent / "pylib"
_stamp_class: type[Time] | None = None


def stamp_class() -> type[Time]:
    """``rospy.Time`` when rostui's rospy is the one importable, else rostui's ``Time`` (the shim's genpy)."""
    global _stamp_class
    if _stamp_class is None:
        found: type[Time] = Time
        try:
            rostime = importlib.import_module("rospy.rostime")  # whichever rospy the script gets
        except ImportError:
            pass
        else:
            where = Path(getattr(rostime, "__file__", "") or "").resolve()
            candidate = getattr(rostime, "Time", None)
            if _PYLIB in where.parents and isinstance(candidate, type) and issubclass(candidate, Time):
                found = candidate
        _stamp_class = found
    return _stamp_class


class BagTarget:
    """The path rostui reads or writes for one ``Bag``, and the stream (if any) it stands for."""

    def __init__(self, path: str, filename: str | None, stream: Any = None, temporary: bool = False) -> None:
        self.path = path
        """The file rostui's readers and writers open."""
        self.filename = filename
        """What ``Bag.filename`` says: the name given, None for a file object (as rosbag)."""
        self.stream = stream
        self.temporary = temporary

    def finish(self, wrote: bool) -> None:
        """Copy a temporary file back into its stream (after writing), remove it, and close the stream, as
        rosbag closes the file object it was given."""
        try:
            if self.temporary and wrote and self.stream is not None and not self.stream.closed:
                self.stream.seek(0)
                self.stream.truncate()
                with open(self.path, "rb") as f:
                    shutil.copyfileobj(f, self.stream)
                self.stream.flush()
        finally:
            if self.temporary:
                try:
                    os.remove(self.path)
                except OSError:
                    pass
            if self.stream is not None and not self.stream.closed:
                self.stream.close()


def _is_binary(stream: Any) -> bool:
    if isinstance(stream, io.TextIOBase):
        return False
    mode = getattr(stream, "mode", "b")
    return not isinstance(mode, str) or "b" in mode


def _named_file(stream: Any) -> str | None:
    """The path of a file object opened on a regular file by name, or None."""
    name = getattr(stream, "name", None)
    if isinstance(name, bytes):
        name = os.fsdecode(name)
    if not isinstance(name, str) or not os.path.isfile(name):
        return None
    return name


def open_target(f: Any, mode: str) -> BagTarget:
    """A :class:`BagTarget` for a name or a binary file object; ValueError for anything else.

    A text-mode file object raises what rosbag raises for it: :class:`TypeError` when writing (rosbag's first
    write fails), ``ROSBagException`` otherwise (raised by the caller on ``TypeError`` from here as well).
    """
    if isinstance(f, (str, os.PathLike)):
        return BagTarget(os.fspath(f), os.fspath(f))
    if not isinstance(f, io.IOBase):
        raise ValueError("filename (or stream) is invalid")
    if not _is_binary(f):
        if mode == "w":  # rosbag's first write of bytes fails
            raise TypeError("write() argument must be str, not bytes")
        raise TypeError("In Python 3 the bag file must be opened in binary mode")
    named = _named_file(f)
    if named is not None:
        if mode == "w":
            f.flush()
        return BagTarget(named, None, f)
    fd, path = tempfile.mkstemp(prefix="rostui-rosbag-", suffix=".bag")
    try:
        with os.fdopen(fd, "wb") as out:
            if mode in ("r", "a"):
                f.seek(0)
                shutil.copyfileobj(f, out)
    except BaseException:
        os.remove(path)
        raise
    return BagTarget(path, None, f, temporary=True)
