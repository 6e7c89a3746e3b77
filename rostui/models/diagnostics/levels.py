"""The levels of diagnostic_msgs/DiagnosticStatus, their names and how severe each is."""

from __future__ import annotations

__all__ = ["OK", "WARN", "ERROR", "STALE", "LEVEL_NAMES", "level_name", "severity", "parse_level"]

OK, WARN, ERROR, STALE = 0, 1, 2, 3

#: The level constants as diagnostic_msgs names them.
LEVEL_NAMES = {OK: "OK", WARN: "WARN", ERROR: "ERROR", STALE: "STALE"}


def level_name(level: int) -> str:
    """``OK``, ``WARN``, ``ERROR``, ``STALE``, or ``level 7`` for a byte no version of the message defines."""
    return LEVEL_NAMES.get(level, f"level {level}")


def severity(level: int) -> int:
    """How bad a level is, for sorting and for a parent's worst child: OK < WARN < ERROR < STALE; a level no
    version of the message defines counts as an error."""
    return level if level in LEVEL_NAMES else ERROR


def parse_level(text: str) -> int:
    """A level from its name or number (``warn``, ``WARN``, ``1``); ValueError naming the choices otherwise."""
    word = text.strip().upper()
    for level, name in LEVEL_NAMES.items():
        if word in (name, str(level)) or (name == "WARN" and word == "WARNING"):
            return level
    raise ValueError(f"unknown level {text!r}: choose ok, warn, error or stale")
