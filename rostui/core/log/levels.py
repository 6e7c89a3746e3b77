"""Log severities with rosgraph_msgs/Log's byte values."""

from __future__ import annotations

import enum

__all__ = ["Level"]

_ALIASES = {"WARNING": "WARN", "ERR": "ERROR", "CRITICAL": "FATAL"}


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
                raise ValueError(f"unknown log level {int(text)} (use 1, 2, 4, 8 or 16)") from None
        key = str(text).strip().upper()
        key = _ALIASES.get(key, key)
        try:
            return cls[key]
        except KeyError:
            raise ValueError(f"unknown log level '{text}' (use debug, info, warn, error or fatal)") from None
