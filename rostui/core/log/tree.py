"""Hierarchical logger levels, as log4cxx gives roscpp nodes.

Logger names are dotted (``ros``, ``ros.rostui``, ``ros.my_pkg.sub``).  A
logger either has its own level or inherits the level of its nearest ancestor
that has one; the root ``ros`` logger starts at INFO.  ``~get_loggers`` lists
every known logger with its effective level, ``~set_logger_level`` sets one.
"""

from __future__ import annotations

import threading
from typing import Callable

from rostui.core.log.levels import Level

__all__ = ["LoggerTree", "ROOT_LOGGER", "LevelListener"]

#: The root of ROS's logger hierarchy.
ROOT_LOGGER = "ros"

#: Called with no arguments after any level in the tree changed.
LevelListener = Callable[[], None]


def _check_name(name: str) -> str:
    name = name.strip()
    if not name or name.startswith(".") or name.endswith(".") or ".." in name or any(c.isspace() for c in name):
        raise ValueError(f"invalid logger name '{name}'")
    return name


class LoggerTree:
    """Logger names with optional own levels; thread-safe; notifies listeners on change."""

    def __init__(self, root_level: Level = Level.INFO) -> None:
        self._lock = threading.RLock()
        self._levels: dict[str, Level | None] = {ROOT_LOGGER: Level(root_level)}
        self._listeners: list[LevelListener] = []

    def register(self, name: str) -> None:
        """Make a logger known (listed by :meth:`loggers`) without giving it a level."""
        name = _check_name(name)
        with self._lock:
            self._levels.setdefault(name, None)

    def set_level(self, name: str, level: Level | str | int) -> Level:
        """Give ``name`` its own level (creating the logger) and notify listeners.

        ``level`` may be a Level, a name (``debug``, ``WARN``...) or a byte value;
        an unknown one raises ValueError and changes nothing.  Returns the level set.
        """
        name = _check_name(name)
        value = Level.parse(level)
        with self._lock:
            self._levels[name] = value
            listeners = list(self._listeners)
        for listener in listeners:
            listener()
        return value

    def clear_level(self, name: str) -> None:
        """Make ``name`` inherit its ancestor's level again (the root keeps its own)."""
        name = _check_name(name)
        with self._lock:
            if name == ROOT_LOGGER or self._levels.get(name) is None:
                return
            self._levels[name] = None
            listeners = list(self._listeners)
        for listener in listeners:
            listener()

    def own_level(self, name: str) -> Level | None:
        """The level set on ``name`` itself, or None when it inherits."""
        with self._lock:
            return self._levels.get(name)

    def effective_level(self, name: str) -> Level:
        """The level of ``name`` or of its nearest ancestor that has one (root ``ros`` last).

        A name outside the ``ros`` hierarchy with no configured ancestor gets the
        root's level.
        """
        with self._lock:
            probe = name
            while True:
                level = self._levels.get(probe)
                if level is not None:
                    return level
                cut = probe.rfind(".")
                if cut < 0:
                    root = self._levels[ROOT_LOGGER]
                    assert root is not None, "the root logger always has a level"
                    return root
                probe = probe[:cut]

    def enabled(self, name: str, level: Level | int) -> bool:
        """True when a message at ``level`` on logger ``name`` would be emitted."""
        return level >= self.effective_level(name)

    def loggers(self) -> list[tuple[str, Level]]:
        """Every known logger with its effective level, sorted by name (as roscpp lists them)."""
        with self._lock:
            names = sorted(self._levels)
            return [(name, self.effective_level(name)) for name in names]

    def add_listener(self, listener: LevelListener) -> None:
        """Call ``listener()`` after every level change (from the changing thread)."""
        with self._lock:
            self._listeners.append(listener)

    def remove_listener(self, listener: LevelListener) -> None:
        """Stop calling ``listener``; unknown listeners are ignored."""
        with self._lock:
            try:
                self._listeners.remove(listener)
            except ValueError:
                pass
