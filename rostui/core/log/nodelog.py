"""The per-node logging facade behind ``loginfo`` & co.

The level is checked before anything else: a disabled call costs one
attribute read and one integer comparison, and never formats its message.
Enabled calls build one :class:`LogRecord` (call site from the caller's frame)
and hand it to the console and to every sink (``/rosout`` publisher, log
file...), in the calling thread.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from types import CodeType, FrameType
from typing import Any, Callable

from rostui.core.log.console import Console
from rostui.core.log.levels import Level
from rostui.core.log.record import LogRecord
from rostui.core.log.tree import ROOT_LOGGER, LoggerTree

__all__ = ["NodeLog", "Sink", "package_logger"]

#: Something that receives every emitted record.
Sink = Callable[[LogRecord], None]

_NS = 1_000_000_000
_DEBUG, _INFO, _WARN, _ERROR, _FATAL = (level.value for level in Level)  # plain ints for the level gate


def package_logger(package: str | None) -> str:
    """roscpp's default logger name for a package: ``ros.<package>`` (``ros.unknown_package`` without one)."""
    return f"{ROOT_LOGGER}.{package or 'unknown_package'}"


def _function_name(frame: FrameType) -> str:
    code = frame.f_code
    name = getattr(code, "co_qualname", code.co_name)
    cut = name.rfind(".<locals>.")
    return name[cut + 10:] if cut >= 0 else name


class NodeLog:
    """A node's logging entry point: level gate, once/throttle per call site, console and sinks.

    ``default_logger`` (e.g. ``ros.my_pkg``) is the logger of calls without
    ``logger=``; ``logger="sub"`` names the child ``<default_logger>.sub``, like
    roscpp's ``ROS_INFO_NAMED``.  Levels live in ``tree`` (changed at run time by
    ``~set_logger_level``); ``console`` None means no console output.  ``clock``
    returns the record stamp in nanoseconds since the epoch (pass ROS time for
    sim time) and also drives throttling.  ``stacklevel`` counts frames above
    the logging method: 1 is its direct caller, 2 the caller's caller (for
    wrappers such as ``rospy.loginfo``-style functions).
    """

    def __init__(self, node_name: str, default_logger: str, tree: LoggerTree | None = None,
                 console: Console | None = None, *, clock: Callable[[], int] = time.time_ns) -> None:
        self.node_name = node_name
        self.default_logger = default_logger
        self.tree = tree if tree is not None else LoggerTree()
        self.console = console
        self.clock = clock
        self._sinks: tuple[Sink, ...] = ()
        self._broken_sinks: set[int] = set()
        self._named: dict[str, tuple[str, int]] = {}
        self._once: set[tuple[CodeType, int]] = set()
        self._last: dict[tuple[CodeType, int], int] = {}
        self._gate = threading.Lock()
        self.tree.register(default_logger)
        self._threshold = int(self.tree.effective_level(default_logger))
        self.tree.add_listener(self._refresh)

    # -- levels ---------------------------------------------------------------------------
    def _refresh(self) -> None:
        self._threshold = int(self.tree.effective_level(self.default_logger))
        self._named = {}

    @property
    def level(self) -> Level:
        """The effective level of the default logger."""
        return Level(self._threshold)

    def set_level(self, level: Level | str | int, logger: str | None = None) -> None:
        """Set the level of the default logger (or of its child ``logger``)."""
        self.tree.set_level(self._full_name(logger)[0], level)

    def _full_name(self, logger: str | None) -> tuple[str, int]:
        if logger is None:
            return self.default_logger, self._threshold
        entry = self._named.get(logger)
        if entry is None:
            full = f"{self.default_logger}.{logger}"
            self.tree.register(full)
            entry = (full, int(self.tree.effective_level(full)))
            self._named[logger] = entry
        return entry

    def enabled(self, level: Level | int, logger: str | None = None) -> bool:
        """True when a message at ``level`` (on child ``logger``) would be emitted."""
        if logger is None:
            return level >= self._threshold
        return level >= self._full_name(logger)[1]

    # -- sinks ----------------------------------------------------------------------------
    def add_sink(self, sink: Sink) -> None:
        """Also hand every emitted record to ``sink`` (called in the logging thread, after the console)."""
        self._sinks = (*self._sinks, sink)

    def remove_sink(self, sink: Sink) -> None:
        """Stop handing records to ``sink``; unknown sinks are ignored."""
        self._sinks = tuple(s for s in self._sinks if s is not sink)

    # -- emission ---------------------------------------------------------------------------
    def _emit(self, level: int, msg: Any, args: tuple[Any, ...], logger: str | None, frame: FrameType,
              stamp: int | None = None) -> None:
        name = self._full_name(logger)[0]
        text = (msg % args) if args else (msg if isinstance(msg, str) else str(msg))
        record = LogRecord(
            Level(level), text, self.node_name, name, os.path.basename(frame.f_code.co_filename),
            frame.f_lineno, _function_name(frame), self.clock() if stamp is None else stamp,
        )
        if self.console is not None:
            self.console.write(record)
        for sink in self._sinks:
            try:
                sink(record)
            except Exception as exc:  # a broken sink must not break the caller
                if id(sink) not in self._broken_sinks:
                    self._broken_sinks.add(id(sink))
                    try:
                        sys.stderr.write(f"rostui: log sink {sink!r} failed: {exc!r}\n")
                    except (ValueError, OSError):
                        pass

    def _threshold_of(self, logger: str | None) -> int:
        return self._threshold if logger is None else self._full_name(logger)[1]

    def log(self, level: Level | int, msg: Any, *args: Any, logger: str | None = None,
            stacklevel: int = 1) -> None:
        """Emit ``msg % args`` at ``level`` if enabled; disabled calls return before formatting."""
        if level < (self._threshold if logger is None else self._full_name(logger)[1]):
            return
        self._emit(int(level), msg, args, logger, sys._getframe(stacklevel))

    def debug(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """Log at DEBUG."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _DEBUG:
            return
        self._emit(_DEBUG, msg, args, logger, sys._getframe(stacklevel))

    def info(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """Log at INFO."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _INFO:
            return
        self._emit(_INFO, msg, args, logger, sys._getframe(stacklevel))

    def warn(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """Log at WARN."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _WARN:
            return
        self._emit(_WARN, msg, args, logger, sys._getframe(stacklevel))

    def error(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """Log at ERROR."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _ERROR:
            return
        self._emit(_ERROR, msg, args, logger, sys._getframe(stacklevel))

    def fatal(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """Log at FATAL."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _FATAL:
            return
        self._emit(_FATAL, msg, args, logger, sys._getframe(stacklevel))

    # -- once -------------------------------------------------------------------------------
    def _emit_once(self, level: int, msg: Any, args: tuple[Any, ...], logger: str | None, frame: FrameType) -> None:
        key = (frame.f_code, frame.f_lineno)
        with self._gate:
            if key in self._once:
                return
            self._once.add(key)
        self._emit(level, msg, args, logger, frame)

    def log_once(self, level: Level | int, msg: Any, *args: Any, logger: str | None = None,
                 stacklevel: int = 1) -> None:
        """Emit only the first enabled call from this call site (caller's code and line).

        A call made while the level is disabled does not use up the site, as in roscpp.
        """
        if level < self._threshold_of(logger):
            return
        self._emit_once(int(level), msg, args, logger, sys._getframe(stacklevel))

    def debug_once(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """DEBUG, first enabled call per call site only."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _DEBUG:
            return
        self._emit_once(_DEBUG, msg, args, logger, sys._getframe(stacklevel))

    def info_once(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """INFO, first enabled call per call site only."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _INFO:
            return
        self._emit_once(_INFO, msg, args, logger, sys._getframe(stacklevel))

    def warn_once(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """WARN, first enabled call per call site only."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _WARN:
            return
        self._emit_once(_WARN, msg, args, logger, sys._getframe(stacklevel))

    def error_once(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """ERROR, first enabled call per call site only."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _ERROR:
            return
        self._emit_once(_ERROR, msg, args, logger, sys._getframe(stacklevel))

    def fatal_once(self, msg: Any, *args: Any, logger: str | None = None, stacklevel: int = 1) -> None:
        """FATAL, first enabled call per call site only."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _FATAL:
            return
        self._emit_once(_FATAL, msg, args, logger, sys._getframe(stacklevel))

    # -- throttle ---------------------------------------------------------------------------
    def _emit_throttled(self, period: float, level: int, msg: Any, args: tuple[Any, ...], logger: str | None,
                        frame: FrameType) -> None:
        key = (frame.f_code, frame.f_lineno)
        now = self.clock()
        with self._gate:
            last = self._last.get(key)
            if last is not None and last <= now < last + int(period * _NS):
                return
            self._last[key] = now
        self._emit(level, msg, args, logger, frame, now)

    def log_throttle(self, period: float, level: Level | int, msg: Any, *args: Any,
                     logger: str | None = None, stacklevel: int = 1) -> None:
        """Emit at most once per ``period`` seconds (of ``clock``) from this call site.

        The first enabled call always passes; a clock that jumps backwards re-arms the site.
        """
        if level < self._threshold_of(logger):
            return
        self._emit_throttled(period, int(level), msg, args, logger, sys._getframe(stacklevel))

    def debug_throttle(self, period: float, msg: Any, *args: Any, logger: str | None = None,
                       stacklevel: int = 1) -> None:
        """DEBUG, at most once per ``period`` seconds per call site."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _DEBUG:
            return
        self._emit_throttled(period, _DEBUG, msg, args, logger, sys._getframe(stacklevel))

    def info_throttle(self, period: float, msg: Any, *args: Any, logger: str | None = None,
                      stacklevel: int = 1) -> None:
        """INFO, at most once per ``period`` seconds per call site."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _INFO:
            return
        self._emit_throttled(period, _INFO, msg, args, logger, sys._getframe(stacklevel))

    def warn_throttle(self, period: float, msg: Any, *args: Any, logger: str | None = None,
                      stacklevel: int = 1) -> None:
        """WARN, at most once per ``period`` seconds per call site."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _WARN:
            return
        self._emit_throttled(period, _WARN, msg, args, logger, sys._getframe(stacklevel))

    def error_throttle(self, period: float, msg: Any, *args: Any, logger: str | None = None,
                       stacklevel: int = 1) -> None:
        """ERROR, at most once per ``period`` seconds per call site."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _ERROR:
            return
        self._emit_throttled(period, _ERROR, msg, args, logger, sys._getframe(stacklevel))

    def fatal_throttle(self, period: float, msg: Any, *args: Any, logger: str | None = None,
                       stacklevel: int = 1) -> None:
        """FATAL, at most once per ``period`` seconds per call site."""
        if (self._threshold if logger is None else self._full_name(logger)[1]) > _FATAL:
            return
        self._emit_throttled(period, _FATAL, msg, args, logger, sys._getframe(stacklevel))

    def close(self) -> None:
        """Stop following the tree's level changes and drop all sinks."""
        self.tree.remove_listener(self._refresh)
        self._sinks = ()
