"""``DiagnosticStatusWrapper``: a diagnostic_msgs/DiagnosticStatus with the helpers tasks fill it with."""

from __future__ import annotations

import importlib
from typing import Any

__all__ = ["DiagnosticArray", "DiagnosticStatus", "DiagnosticStatusWrapper", "KeyValue"]

_messages = importlib.import_module("diagnostic_msgs.msg")  # as the real module imports it: scripts then reach it
DiagnosticStatus: Any = _messages.DiagnosticStatus
KeyValue: Any = _messages.KeyValue
DiagnosticArray: Any = _messages.DiagnosticArray


def _level_and_message(args: tuple[Any, ...]) -> tuple[int, str]:
    """``(status,)`` or ``(level, message)``, as both forms of summary and mergeSummary take them."""
    if len(args) == 1:
        return args[0].level, args[0].message
    level, message = args
    return level, message


class DiagnosticStatusWrapper(DiagnosticStatus):
    """A DiagnosticStatus message (level, name, message, hardware_id, values) with summary and key-value helpers."""

    def summary(self, *args: Any) -> None:
        """Set the level and message: ``summary(status)`` copies another status's, ``summary(level, message)``."""
        if len(args) in (1, 2):
            level, message = _level_and_message(args)
            self.level, self.message = level, message if len(args) == 1 else str(message)

    def clearSummary(self) -> None:  # noqa: N802 (diagnostic_updater's name)
        """Level OK and no message."""
        self.summary(0, "")

    def mergeSummary(self, *args: Any) -> None:  # noqa: N802 (diagnostic_updater's name)
        """Merge another level and message in: the worse level wins; two non-OK messages are joined with "; "."""
        if len(args) not in (1, 2):
            return
        level, message = _level_and_message(args)
        if (level > 0) == (self.level > 0):
            if self.message:
                self.message += "; "
            self.message += message
        elif level > self.level:
            self.message = message
        if level > self.level:
            self.level = level

    def add(self, key: str, val: Any) -> None:
        """Add the key-value pair *key*, ``str(val)``."""
        self.values.append(KeyValue(key, str(val)))
