"""Log severities with rosgraph_msgs/Log's byte values."""

from __future__ import annotations

import enum
from typing import Iterable

__all__ = ["Level"]

_PYTHON_NAMES = {"WARN": "WARNING", "FATAL": "CRITICAL"}
_ALIASES = {"ERR": "ERROR", **{python: ros for ros, python in _PYTHON_NAMES.items()}}


class Level(enum.IntEnum):
    """Severities with rosgraph_msgs/Log's byte values (DEBUG=1 ... FATAL=16)."""

    DEBUG = 1
    INFO = 2
    WARN = 4
    ERROR = 8
    FATAL = 16

    @property
    def label(self) -> str:
        """The five-character label roscpp prints on the console (`` INFO``, ``ERROR``...)."""
        return self.name.rjust(5)

    @property
    def python_name(self) -> str:
        """Python's logging name for this severity (``WARNING``, ``CRITICAL``...), as in rospy's log files."""
        return _PYTHON_NAMES.get(self.name, self.name)

    @property
    def text(self) -> str:
        """The lowercase name roscpp's ``~get_loggers`` answers with (``info``, ``warn``...)."""
        return self.name.lower()

    @classmethod
    def parse(cls, text: str | int | "Level") -> "Level":
        """A level from its name, case-insensitive (``warning`` is WARN), or its byte value.

        Raises ValueError with the accepted names for anything else.
        """
        if isinstance(text, int):
            try:
                return cls(int(text))
            except ValueError:
                values = _either(str(level.value) for level in cls)
                raise ValueError(f"unknown log level {int(text)} (use {values})") from None
        key = str(text).strip().upper()
        key = _ALIASES.get(key, key)
        try:
            return cls[key]
        except KeyError:
            names = _either(level.text for level in cls)
            raise ValueError(f"unknown log level '{text}' (use {names})") from None


def _either(words: Iterable[str]) -> str:
    """``a, b or c``."""
    *most, last = words
    return f"{', '.join(most)} or {last}"
