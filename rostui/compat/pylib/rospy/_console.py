"""Console lines as rospy prints them: ``[INFO] [1795660087.370208]: message``.

rospy fills ``ROSCONSOLE_FORMAT`` (default ``[${severity}] [${time}]: ${message}``)
with the level's name unpadded and the time as seconds with six decimals, where
roscpp (and rostui's own nodes) pad the level to five characters and print
nanoseconds. Colours stay rostui's: on a terminal only, never with ``NO_COLOR``.
"""

from __future__ import annotations

import os
import re
import threading
import time
from typing import Callable

from rostui.core.log import Console
from rostui.core.log.console import COLORS, DEFAULT_FORMAT, RESET
from rostui.core.log.record import LogRecord

__all__ = ["RospyConsole"]

_TOKEN = re.compile(r"\$\{([a-z]+)\}")

_FIELDS: dict[str, Callable[[LogRecord], str]] = {
    "severity": lambda r: r.level.name,
    "time": lambda r: "%f" % (r.stamp / 1e9),
    "walltime": lambda r: "%f" % time.time(),
    "message": lambda r: r.message,
    "node": lambda r: r.node,
    "logger": lambda r: r.logger,
    "file": lambda r: r.file,
    "line": lambda r: str(r.line),
    "function": lambda r: r.function,
    "thread": lambda r: str(threading.get_ident()),
}


class RospyConsole(Console):
    """A :class:`~rostui.core.log.Console` that writes rospy's line format; unknown tokens stay as written."""

    def __init__(self) -> None:
        super().__init__(os.environ.get("ROSCONSOLE_FORMAT") or DEFAULT_FORMAT)

    def format(self, record: LogRecord, color: bool = False) -> str:
        """The line for *record* (without newline), coloured if asked."""
        def field(match: re.Match[str]) -> str:
            render = _FIELDS.get(match.group(1))
            return match.group(0) if render is None else render(record)

        text = _TOKEN.sub(field, self.fmt)
        return f"{COLORS.get(record.level, '')}{text}{RESET}" if color else text
