"""One log message, as every destination (console, /rosout, files) sees it."""

from __future__ import annotations

from rostui.core.log.levels import Level

__all__ = ["LogRecord"]


def _frozen(self: object, name: str, value: object = None) -> None:
    raise AttributeError(f"cannot assign to field {name!r}")


class LogRecord:
    """A formatted log message with its origin (immutable).

    ``message`` is final text (``msg % args`` already applied); ``file`` is the
    base name of the calling source file, ``function`` its qualified function
    name (``Class.method``, ``<module>``), ``stamp`` nanoseconds since the epoch
    from the node's clock (ROS time: simulated when the node uses sim time).

    A plain class rather than a dataclass (making one costs about a millisecond of every node's start); it
    keeps a frozen dataclass's constructor, equality, hash and repr.
    """

    __slots__ = ("level", "message", "node", "logger", "file", "line", "function", "stamp")

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
        setter = object.__setattr__
        setter(self, "level", level)
        setter(self, "message", message)
        setter(self, "node", node)
        setter(self, "logger", logger)
        setter(self, "file", file)
        setter(self, "line", line)
        setter(self, "function", function)
        setter(self, "stamp", stamp)

    __setattr__ = _frozen
    __delattr__ = _frozen

    def _key(self) -> tuple[Level, str, str, str, str, int, str, int]:
        return self.level, self.message, self.node, self.logger, self.file, self.line, self.function, self.stamp

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        assert isinstance(other, LogRecord)
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return (f"LogRecord(level={self.level!r}, message={self.message!r}, node={self.node!r}, "
                f"logger={self.logger!r}, file={self.file!r}, line={self.line!r}, function={self.function!r}, "
                f"stamp={self.stamp!r})")

    def __reduce__(self) -> tuple[type[LogRecord], tuple[Level, str, str, str, str, int, str, int]]:
        return LogRecord, self._key()

    @property
    def secs(self) -> int:
        """Whole seconds of the stamp (``header.stamp.secs``)."""
        return self.stamp // 1_000_000_000

    @property
    def nsecs(self) -> int:
        """Nanoseconds past the second (``header.stamp.nsecs``)."""
        return self.stamp % 1_000_000_000
