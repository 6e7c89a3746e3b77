"""The console lines rospy prints: ``[INFO] [1700000000.123456]: message``, not roscpp's ``[ INFO] [...]``.

rospy (rosgraph's ``RosStreamHandler``) fills ``ROSCONSOLE_FORMAT`` (default
``[${severity}] [${time}]: ${message}``) with the level's name unpadded and the
wall time as seconds with six decimals; DEBUG and INFO go to stdout, WARN and
above to stderr, and INFO is never colored. Only the look differs from
:class:`rostui.core.log.console.Console`, which does the writing.
"""

from __future__ import annotations

import re
import sys
import threading
from collections.abc import Callable
from typing import TextIO

from rostui.core.log.console import COLORS, RESET, Console
from rostui.core.log.levels import Level
from rostui.core.log.record import LogRecord

__all__ = ["RospyConsole", "RospyConsoleBeforeInit"]

_TOKEN = re.compile(r"\$\{([a-z]+)\}")


def _seconds(record: LogRecord) -> str:
    return f"{record.stamp / 1e9:f}"


_FIELDS: dict[str, Callable[[LogRecord], str]] = {
    "severity": lambda r: r.level.name,
    "message": lambda r: r.message,
    "walltime": _seconds,
    "time": _seconds,
    "thread": lambda r: str(threading.get_ident()),
    "logger": lambda r: r.logger,
    "file": lambda r: r.file,
    "line": lambda r: str(r.line),
    "function": lambda r: r.function,
    "node": lambda r: r.node,
}


class RospyConsole(Console):
    """A :class:`Console` whose lines look like rospy's."""

    def format(self, record: LogRecord, color: bool = False) -> str:
        """The line for ``record`` as rospy prints it (without newline); INFO stays uncolored."""

        def field(match: re.Match[str]) -> str:
            fill = _FIELDS.get(match.group(1))
            return match.group(0) if fill is None else fill(record)

        text = _TOKEN.sub(field, self.fmt)
        if color and record.level is not Level.INFO:
            return f"{COLORS.get(record.level, '')}{text}{RESET}"
        return text


class RospyConsoleBeforeInit(Console):
    """What rospy prints before ``init_node``: its log calls reach Python's logging with no handler set, so
    DEBUG and INFO vanish and WARN and above appear bare (the message alone) on stderr, as Python's
    last-resort handler writes them."""

    def stream_for(self, level: Level) -> TextIO:
        """stderr, for every level that is shown."""
        return sys.stderr

    def write(self, record: LogRecord) -> None:
        """Write the bare message of a WARN or higher record."""
        if record.level < Level.WARN:
            return
        try:
            sys.stderr.write(record.message + "\n")
            sys.stderr.flush()
        except (BrokenPipeError, ValueError, OSError, AttributeError):
            pass

    __call__ = write
