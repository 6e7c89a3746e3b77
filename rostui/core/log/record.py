"""One log message, as every destination (console, /rosout, files) sees it."""

from __future__ import annotations

from dataclasses import dataclass

from rostui.core.log.levels import Level

__all__ = ["LogRecord"]


@dataclass(frozen=True, slots=True)
class LogRecord:
    """A formatted log message with its origin.

    ``message`` is final text (``msg % args`` already applied); ``file`` is the
    base name of the calling source file, ``function`` its qualified function
    name (``Class.method``, ``<module>``), ``stamp`` nanoseconds since the epoch
    from the node's clock (ROS time: simulated when the node uses sim time).
    """

    level: Level
    message: str
    node: str
    logger: str
    file: str = ""
    line: int = 0
    function: str = ""
    stamp: int = 0

    @property
    def secs(self) -> int:
        """Whole seconds of the stamp (``header.stamp.secs``)."""
        return self.stamp // 1_000_000_000

    @property
    def nsecs(self) -> int:
        """Nanoseconds past the second (``header.stamp.nsecs``)."""
        return self.stamp % 1_000_000_000
