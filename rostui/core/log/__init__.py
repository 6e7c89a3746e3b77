"""Log levels and console output in ROS's format.

DEBUG and INFO go to stdout, WARN and above to stderr, one line each, in the
ROSCONSOLE_FORMAT (default ``[${severity}] [${time}]: ${message}``, the time
as seconds.nanoseconds since the epoch).
"""

from __future__ import annotations

import enum
import os
import sys
import time
from typing import TextIO


class Level(enum.IntEnum):
    """Severities with rosgraph_msgs/Log's byte values."""

    DEBUG = 1
    INFO = 2
    WARN = 4
    ERROR = 8
    FATAL = 16

    @property
    def label(self) -> str:
        """The five-character label roscpp prints (`` INFO``, ``ERROR``...)."""
        return self.name.rjust(5)

    @classmethod
    def parse(cls, text: str) -> "Level":
        """A level from its name, case-insensitive (``warning`` is WARN)."""
        key = text.strip().upper()
        if key == "WARNING":
            key = "WARN"
        try:
            return cls[key]
        except KeyError:
            raise ValueError(f"unknown log level '{text}' (use debug, info, warn, error or fatal)") from None


DEFAULT_FORMAT = "[${severity}] [${time}]: ${message}"


def wall_time_text(now: float | None = None) -> str:
    """Seconds.nanoseconds since the epoch, as ROS prints log times."""
    ns = time.time_ns() if now is None else int(now * 1e9)
    return f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"


def format_line(level: Level, message: str, node: str = "", *, fmt: str | None = None,
                file: str = "", line: int = 0, function: str = "", logger: str = "") -> str:
    """One console line in the ROSCONSOLE_FORMAT."""
    fmt = fmt or os.environ.get("ROSCONSOLE_FORMAT") or DEFAULT_FORMAT
    values = {
        "severity": level.label, "time": wall_time_text(), "message": message, "node": node,
        "file": file, "line": str(line), "function": function, "logger": logger,
    }
    out = fmt
    for key, value in values.items():
        out = out.replace("${" + key + "}", value)
    return out


def console_stream(level: Level) -> TextIO:
    """stdout for DEBUG/INFO, stderr for WARN and above."""
    return sys.stdout if level <= Level.INFO else sys.stderr


class ConsoleLogger:
    """Writes a node's messages at or above its level to the console."""

    def __init__(self, node: str = "", level: Level = Level.INFO) -> None:
        self.node = node
        self.level = level

    def log(self, level: Level, message: str) -> None:
        """Write one message if its level is enabled."""
        if level < self.level:
            return
        stream = console_stream(level)
        stream.write(format_line(level, message, self.node) + "\n")
        stream.flush()

    def debug(self, message: str) -> None:
        """Log at DEBUG."""
        self.log(Level.DEBUG, message)

    def info(self, message: str) -> None:
        """Log at INFO."""
        self.log(Level.INFO, message)

    def warn(self, message: str) -> None:
        """Log at WARN."""
        self.log(Level.WARN, message)

    def error(self, message: str) -> None:
        """Log at ERROR."""
        self.log(Level.ERROR, message)

    def fatal(self, message: str) -> None:
        """Log at FATAL."""
        self.log(Level.FATAL, message)
