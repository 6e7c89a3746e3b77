"""``rosout.log``: the file the rosout node writes in the run's log directory.

Format (taken from real rosout's output): the file opens with two empty lines
and ``<secs>.<nsecs>  Node Startup``; then one line per /rosout message::

    1795347562.722323656 INFO /talker [talker.py:6(<module>)] [topics: /chatter, /rosout] hello

stamp (the message's header stamp, nine-digit nanoseconds), level name, node
name, ``[file:line(function)]``, the node's topics comma-separated, the text
(written as is, newlines included).
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path
from typing import Any, Callable, Sequence, TextIO

from rostui.core.log.files import close_quietly
from rostui.core.log.levels import Level
from rostui.core.log.record import LogRecord

__all__ = ["ROSOUT_LEVEL_NAMES", "RosoutLogWriter", "format_rosout_line", "startup_text"]

#: Level byte -> the name rosout writes.
ROSOUT_LEVEL_NAMES: dict[int, str] = {level.value: level.name for level in Level}


def startup_text(stamp_ns: int) -> str:
    """The lines rosout writes when it opens ``rosout.log``."""
    return f"\n\n{stamp_ns // 1_000_000_000}.{stamp_ns % 1_000_000_000:09d}  Node Startup\n"


def format_rosout_line(secs: int, nsecs: int, level: int, name: str, file: str, line: int,
                       function: str, topics: Sequence[str], msg: str) -> str:
    """One ``rosout.log`` line (with newline) for a rosgraph_msgs/Log message's fields.

    A level byte outside DEBUG..FATAL is written as its number (real rosout
    writes garbage there).
    """
    label = ROSOUT_LEVEL_NAMES.get(int(level), str(int(level)))
    return (f"{int(secs)}.{int(nsecs):09d} {label} {name} [{file}:{int(line)}({function})] "
            f"[topics: {', '.join(topics)}] {msg}\n")


class RosoutLogWriter:
    """Appends /rosout messages to a ``rosout.log``, flushing every line, rotating when big.

    When the file would pass ``max_bytes`` it becomes ``rosout.log.1`` (older
    ones shift up to ``.<backups>``, the oldest dropped) and a fresh file starts.
    Write errors are swallowed after being counted in :attr:`errors`.
    """

    def __init__(self, path: Path | str, *, max_bytes: int = 100 * 1024 * 1024, backups: int = 10,
                 clock: Callable[[], int] = time.time_ns) -> None:
        self.path = Path(path)
        self.max_bytes = max_bytes
        self.backups = backups
        self.clock = clock
        self.errors = 0
        self._file: TextIO | None = None
        self._size = 0
        self._lock = threading.Lock()

    def open(self) -> None:
        """Open (append) and write the startup lines; called by the first write if not before."""
        with self._lock:
            self._open(header=True)

    def _open(self, header: bool) -> None:
        if self._file is not None:
            return
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._file = open(self.path, "a", encoding="utf-8", errors="replace")
            self._size = self._file.tell()
            if header:
                self._put(startup_text(self.clock()))
        except OSError:
            self.errors += 1
            self._file = None

    def _put(self, text: str) -> None:
        assert self._file is not None
        self._file.write(text)
        self._file.flush()
        self._size += len(text.encode("utf-8", "replace"))

    def _rotate(self) -> None:
        assert self._file is not None
        self._file.close()
        self._file = None
        base = str(self.path)
        if self.backups > 0:
            for index in range(self.backups - 1, 0, -1):
                older = f"{base}.{index}"
                if os.path.exists(older):
                    os.replace(older, f"{base}.{index + 1}")
            os.replace(base, f"{base}.1")
        else:
            os.unlink(base)
        self._open(header=False)

    def write(self, secs: int, nsecs: int, level: int, name: str, file: str, line: int,
              function: str, topics: Sequence[str], msg: str) -> None:
        """Append the line for one message's fields (see :func:`format_rosout_line`)."""
        text = format_rosout_line(secs, nsecs, level, name, file, line, function, topics, msg)
        with self._lock:
            try:
                if self._file is None:
                    self._open(header=True)
                    if self._file is None:
                        return
                if self.max_bytes > 0 and self._size and self._size + len(text) > self.max_bytes:
                    self._rotate()
                    if self._file is None:
                        return
                self._put(text)
            except (OSError, ValueError):
                self.errors += 1

    def write_message(self, msg: Any) -> None:
        """Append a rosgraph_msgs/Log message (any object with its fields)."""
        stamp = msg.header.stamp
        self.write(stamp.secs, stamp.nsecs, msg.level, msg.name, msg.file, msg.line,
                   msg.function, list(msg.topics), msg.msg)

    def write_record(self, record: LogRecord, topics: Sequence[str] = ()) -> None:
        """Append a local :class:`LogRecord` as rosout would log it."""
        self.write(record.secs, record.nsecs, int(record.level), record.node, record.file,
                   record.line, record.function, topics, record.message)

    def close(self) -> None:
        """Close the file."""
        with self._lock:
            close_quietly(self._file)
            self._file = None
