"""ROS 1 ``time`` and ``duration`` values with rospy's semantics.

Both are a pair of integers, ``secs`` and ``nsecs``, kept in canonical form
(``0 <= nsecs < 1e9``; for a negative duration ``secs`` carries the sign).
They serialize as two 32-bit integers (unsigned for time, signed for duration).
"""

from __future__ import annotations

import numbers
import time as _time
from typing import ClassVar, TypeVar, overload

__all__ = ["Time", "Duration", "TVal"]

_NSEC = 1_000_000_000

_T = TypeVar("_T", bound="TVal")


def _canon(secs: int, nsecs: int) -> tuple[int, int]:
    """Fold nanoseconds into ``[0, 1e9)``, carrying whole seconds into ``secs``."""
    over, nsecs = divmod(nsecs, _NSEC)
    return secs + over, nsecs


class TVal:
    """Common base of :class:`Time` and :class:`Duration` (secs + nsecs)."""

    __slots__ = ("secs", "nsecs")

    secs: int
    nsecs: int

    repr_prefix: ClassVar[str] = "rostui"
    """What ``repr()`` names the module: ``rostui.Time[...]``; genpy's shim sets ``genpy``, as genpy prints."""

    def __init__(self, secs: int | float = 0, nsecs: int = 0) -> None:
        """Build from integer secs/nsecs, or from float seconds (then nsecs must be 0)."""
        if not isinstance(secs, numbers.Integral):
            if nsecs != 0:
                raise ValueError("if secs is a float, nsecs cannot be set")
            float_secs = float(secs)
            secs = int(float_secs)
            nsecs = int((float_secs - secs) * _NSEC)
        self.secs, self.nsecs = _canon(int(secs), int(nsecs))

    @classmethod
    def from_sec(cls: type[_T], float_secs: float) -> _T:
        """Create a value from float seconds (``time.time()`` style)."""
        secs = int(float_secs)
        return cls(secs, int((float_secs - secs) * _NSEC))

    @classmethod
    def from_nsec(cls: type[_T], nsec: int) -> _T:
        """Create a value from integer nanoseconds."""
        secs, nsecs = divmod(int(nsec), _NSEC)
        return cls(secs, nsecs)

    def is_zero(self) -> bool:
        """True when both secs and nsecs are zero."""
        return self.secs == 0 and self.nsecs == 0

    def set(self, secs: int, nsecs: int) -> None:
        """Set secs and nsecs as given (no canonicalisation)."""
        self.secs = secs
        self.nsecs = nsecs

    def canon(self) -> None:
        """Bring secs/nsecs into canonical form after setting them by hand."""
        self.secs, self.nsecs = _canon(self.secs, self.nsecs)

    def to_sec(self) -> float:
        """The value as float seconds."""
        return float(self.secs) + float(self.nsecs) / 1e9

    def to_nsec(self) -> int:
        """The value as integer nanoseconds."""
        return self.secs * _NSEC + self.nsecs

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __str__(self) -> str:
        return str(self.to_nsec())

    def __bool__(self) -> bool:
        return self.secs != 0 or self.nsecs != 0

    def __getstate__(self) -> list[int]:
        return [self.secs, self.nsecs]

    def __setstate__(self, state: list[int]) -> None:
        self.secs, self.nsecs = state

    def _cmp_key(self, other: object) -> tuple[int, int]:
        if not isinstance(other, type(self)._cmp_base()):
            raise TypeError(f"cannot compare {type(self).__name__} to {type(other).__name__}")
        return self.to_nsec(), other.to_nsec()

    @classmethod
    def _cmp_base(cls) -> type[TVal]:
        return TVal

    def __lt__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a < b

    def __le__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a <= b

    def __gt__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a > b

    def __ge__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a >= b

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, self._cmp_base()):
            return False
        return self.secs == other.secs and self.nsecs == other.nsecs

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)


class Time(TVal):
    """A point in time: seconds and nanoseconds since the epoch (never negative)."""

    __slots__ = ()

    def __init__(self, secs: int | float = 0, nsecs: int = 0) -> None:
        """Build a time; negative values raise ``TypeError`` as in rospy."""
        super().__init__(secs, nsecs)
        if self.secs < 0:
            raise TypeError("time values must be positive")

    @classmethod
    def _cmp_base(cls) -> type[TVal]:
        return Time

    @classmethod
    def now(cls) -> "Time":
        """The current wall-clock time."""
        ns = _time.time_ns()
        return cls(ns // _NSEC, ns % _NSEC)

    def to_time(self) -> float:
        """Alias of :meth:`to_sec`."""
        return self.to_sec()

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __repr__(self) -> str:
        return f"{TVal.repr_prefix}.Time[{self.to_nsec()}]"

    def __add__(self, other: Duration) -> Time:
        if not isinstance(other, Duration):
            return NotImplemented
        return self.__class__(self.secs + other.secs, self.nsecs + other.nsecs)

    __radd__ = __add__

    @overload
    def __sub__(self, other: Time) -> Duration: ...
    @overload
    def __sub__(self, other: Duration) -> Time: ...
    def __sub__(self, other: object) -> Duration | Time:
        if isinstance(other, Time):
            return Duration(self.secs - other.secs, self.nsecs - other.nsecs)
        if isinstance(other, Duration):
            return self.__class__(self.secs - other.secs, self.nsecs - other.nsecs)
        return NotImplemented


class Duration(TVal):
    """A signed span of time in seconds and nanoseconds."""

    __slots__ = ()

    @classmethod
    def _cmp_base(cls) -> type[TVal]:
        return Duration

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __repr__(self) -> str:
        return f"{TVal.repr_prefix}.Duration[{self.to_nsec()}]"

    def __neg__(self) -> "Duration":
        return self.__class__(-self.secs, -self.nsecs)

    def __abs__(self) -> "Duration":
        return self if self.secs >= 0 else -self

    def __add__(self, other: Duration) -> Duration:
        if isinstance(other, Duration):
            return self.__class__(self.secs + other.secs, self.nsecs + other.nsecs)
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: object) -> "Duration":
        if not isinstance(other, Duration):
            return NotImplemented
        return self.__class__(self.secs - other.secs, self.nsecs - other.nsecs)

    def __mul__(self, val: object) -> "Duration":
        if isinstance(val, numbers.Integral):
            return self.__class__(self.secs * int(val), self.nsecs * int(val))
        if isinstance(val, numbers.Real):
            return self.__class__.from_sec(self.to_sec() * float(val))
        return NotImplemented

    __rmul__ = __mul__

    @overload
    def __floordiv__(self, val: float) -> Duration: ...
    @overload
    def __floordiv__(self, val: Duration) -> int: ...
    def __floordiv__(self, val: object) -> Duration | int:
        if isinstance(val, numbers.Real):
            return self.__class__.from_sec(self.to_sec() // float(val))
        if isinstance(val, Duration):
            return int(self.to_sec() // val.to_sec())
        return NotImplemented

    @overload
    def __truediv__(self, val: float) -> Duration: ...
    @overload
    def __truediv__(self, val: Duration) -> float: ...
    def __truediv__(self, val: object) -> Duration | float:
        if isinstance(val, numbers.Real):
            return self.__class__.from_sec(self.to_sec() / float(val))
        if isinstance(val, Duration):
            return self.to_sec() / val.to_sec()
        return NotImplemented

    def __mod__(self, val: object) -> "Duration":
        if isinstance(val, Duration):
            return self.__class__.from_sec(self.to_sec() % val.to_sec())
        return NotImplemented

    def __divmod__(self, val: Duration) -> tuple[int, Duration]:
        if isinstance(val, Duration):
            q, r = divmod(self.to_sec(), val.to_sec())
            return int(q), self.__class__.from_sec(r)
        return NotImplemented
