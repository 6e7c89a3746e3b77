"""One log message, as every destination (console, /rosout, files) sees it."""

from __future__ import annotations

from rostui.core.log.levels import Level
from rostui.core.records import FrozenRecord

__all__ = ["LogRecord"]


class LogRecord(FrozenRecord):
    """A formatted log message with its origin (immutable).

    ``message`` is final text (``msg % args`` already applied); ``file`` is the
    base name of the calling source file, ``function`` its qualified function
    name (``Class.method``, ``<module>``), ``stamp`` nanoseconds since the epoch
    from the node's clock (ROS time: simulated when the node uses sim time).

    A record rather than a dataclass: :mod:`rostui.core.records` says why.
    """

    __slots__ = _fields = ("level", "message", "node", "logger", "file", "line", "function", "stamp")

    level: Level
    message: str
    node: str
    logger: str
    file: str
    line: int
    function: str
    stamp: int

    def __init__(self, level: Level, message: str, node: str, logger: str, file: str = "", line: int = 0,
                 function: str = "", stamp: int = 0) -> None:
        self._set(level, message, node, logger, file, line, function, stamp)

    @property
    def secs(self) -> int:
        """Whole seconds of the stamp (``header.stamp.secs``)."""
        return self.stamp // 1_000_000_000

    @property
    def nsecs(self) -> int:
        """Nanoseconds past the second (``header.stamp.nsecs``)."""
        return self.stamp % 1_000_000_000
