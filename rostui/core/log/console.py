"""Console output in ROS's format: one line per record, colored by level on a terminal.

DEBUG and INFO go to stdout, WARN and above to stderr.  The line follows
``ROSCONSOLE_FORMAT`` (default ``[${severity}] [${time}]: ${message}``, the time
as seconds.nanoseconds since the epoch, as roscpp prints it).  Colors are
roscpp's (DEBUG green, INFO plain, WARN yellow, ERROR and FATAL red) but, unlike
roscpp, only on a terminal and never with ``NO_COLOR``; ``ROSTUI_FORCE_COLOR=1``
forces them.
"""

from __future__ import annotations

import os
import re
import sys
import threading
import time
from typing import Callable, Mapping, TextIO

from rostui.core.log.levels import Level
from rostui.core.log.record import LogRecord

__all__ = [
    "DEFAULT_FORMAT", "COLORS", "RESET", "Console", "ConsoleLogger", "color_wanted",
    "compile_format", "console_stream", "format_line", "stamp_text", "wall_time_text",
]

#: roscpp's default console format.
DEFAULT_FORMAT = "[${severity}] [${time}]: ${message}"

#: The ANSI prefix roscpp puts before a line of each level.
COLORS: dict[Level, str] = {
    Level.DEBUG: "\033[32m",
    Level.INFO: "\033[0m",
    Level.WARN: "\033[33m",
    Level.ERROR: "\033[31m",
    Level.FATAL: "\033[31m",
}

#: The ANSI suffix roscpp puts after every colored line.
RESET = "\033[0m"

_TOKEN = re.compile(r"\$\{([a-z]+)\}")

_FIELDS: dict[str, Callable[[LogRecord], str]] = {
    "severity": lambda r: r.level.label,
    "time": lambda r: stamp_text(r.stamp),
    "walltime": lambda r: stamp_text(time.time_ns()),
    "message": lambda r: r.message,
    "node": lambda r: r.node,
    "file": lambda r: r.file,
    "line": lambda r: str(r.line),
    "function": lambda r: r.function,
    "logger": lambda r: r.logger,
    "thread": lambda r: str(threading.get_ident()),
}


def stamp_text(ns: int) -> str:
    """Nanoseconds since the epoch as ``seconds.nanoseconds`` (nine digits), as ROS prints times."""
    return f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"


def wall_time_text(now: float | None = None) -> str:
    """The wall-clock time (or ``now``, in seconds) as seconds.nanoseconds since the epoch."""
    return stamp_text(time.time_ns() if now is None else int(now * 1e9))


def compile_format(fmt: str) -> Callable[[LogRecord], str]:
    """A function rendering a record in ``fmt``; unknown ``${tokens}`` stay as written."""
    parts: list[str | Callable[[LogRecord], str]] = []
    pos = 0
    for match in _TOKEN.finditer(fmt):
        field = _FIELDS.get(match.group(1))
        if field is None:
            continue
        if match.start() > pos:
            parts.append(fmt[pos:match.start()])
        parts.append(field)
        pos = match.end()
    if pos < len(fmt):
        parts.append(fmt[pos:])
    frozen = tuple(parts)

    def render(record: LogRecord) -> str:
        return "".join(p if isinstance(p, str) else p(record) for p in frozen)

    return render


def color_wanted(stream: TextIO, env: Mapping[str, str] | None = None) -> bool:
    """True when lines to ``stream`` should be colored.

    ``ROSTUI_FORCE_COLOR=1`` forces color; otherwise a non-empty ``NO_COLOR``
    disables it; otherwise only a TTY gets color.
    """
    env = os.environ if env is None else env
    if env.get("ROSTUI_FORCE_COLOR") == "1":
        return True
    if env.get("NO_COLOR"):
        return False
    try:
        return stream.isatty()
    except (ValueError, OSError, AttributeError):
        return False


def console_stream(level: Level) -> TextIO:
    """stdout for DEBUG/INFO, stderr for WARN and above."""
    return sys.stdout if level <= Level.INFO else sys.stderr


class Console:
    """Writes records to the console, one flushed line each.

    ``fmt`` defaults to ``ROSCONSOLE_FORMAT`` from ``env`` (then :data:`DEFAULT_FORMAT`);
    ``stdout``/``stderr`` default to the process streams current at each write;
    ``color`` None decides per stream (see :func:`color_wanted`).  A closed or
    broken stream is ignored, never raised.
    """

    def __init__(self, fmt: str | None = None, *, stdout: TextIO | None = None,
                 stderr: TextIO | None = None, color: bool | None = None,
                 env: Mapping[str, str] | None = None) -> None:
        env = os.environ if env is None else env
        self.fmt = fmt or env.get("ROSCONSOLE_FORMAT") or DEFAULT_FORMAT
        self._render = compile_format(self.fmt)
        self._stdout = stdout
        self._stderr = stderr
        self._color = color
        self._env = dict(env)
        self._tty: dict[int, tuple[TextIO, bool]] = {}
        self._lock = threading.Lock()

    def format(self, record: LogRecord, color: bool = False) -> str:
        """The line for ``record`` (without newline), wrapped in roscpp's colors if asked."""
        text = self._render(record)
        if color:
            return f"{COLORS.get(record.level, '')}{text}{RESET}"
        return text

    def stream_for(self, level: Level) -> TextIO:
        """The stream a record of ``level`` is written to."""
        if level <= Level.INFO:
            return self._stdout if self._stdout is not None else sys.stdout
        return self._stderr if self._stderr is not None else sys.stderr

    def _colored(self, stream: TextIO) -> bool:
        if self._color is not None:
            return self._color
        cached = self._tty.get(id(stream))
        if cached is None or cached[0] is not stream:
            cached = (stream, color_wanted(stream, self._env))
            self._tty[id(stream)] = cached
        return cached[1]

    def write(self, record: LogRecord) -> None:
        """Write one line for ``record`` and flush; errors of a closed stream are swallowed."""
        stream = self.stream_for(record.level)
        if stream is None:  # no console at all (pythonw, daemon)
            return
        line = self.format(record, self._colored(stream)) + "\n"
        with self._lock:
            try:
                stream.write(line)
                stream.flush()
            except (BrokenPipeError, ValueError, OSError):
                pass

    __call__ = write


def format_line(level: Level, message: str, node: str = "", *, fmt: str | None = None,
                file: str = "", line: int = 0, function: str = "", logger: str = "") -> str:
    """One console line (no color) in ``fmt`` or ROSCONSOLE_FORMAT, stamped with the wall time now."""
    fmt = fmt or os.environ.get("ROSCONSOLE_FORMAT") or DEFAULT_FORMAT
    record = LogRecord(Level(level), message, node, logger, file, line, function, time.time_ns())
    return compile_format(fmt)(record)


class ConsoleLogger:
    """Console-only logger kept for older callers; new code uses :class:`NodeLog`."""

    def __init__(self, node: str = "", level: Level = Level.INFO) -> None:
        self.node = node
        self.level = level

    def log(self, level: Level, message: str) -> None:
        """Write one message if its level is enabled."""
        if level < self.level:
            return
        Console().write(LogRecord(Level(level), message, self.node, "", stamp=time.time_ns()))

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
