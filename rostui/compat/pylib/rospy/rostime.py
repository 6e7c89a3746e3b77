"""rospy.rostime: ``rospy.Time`` and ``rospy.Duration`` (genpy's, printing as rospy's) and the clock.

Their bases are rostui's times, which are the shim's ``genpy.Time`` and ``genpy.Duration``.
"""

from __future__ import annotations

import time

from rostui.core import rostime as _base
from rostui.core.node import sync as _sync

from .exceptions import ROSInitException
from .names import is_initialized

__all__ = ["Time", "Duration", "get_rostime", "get_time", "is_wallclock", "is_rostime_initialized",
           "set_rostime_initialized"]

_initialized_by_hand = False
_time_set_by_hand: "Time | None" = None


class Duration(_base.Duration):
    """A signed span of time, ``repr()`` ``rospy.Duration[nsecs]``."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"rospy.Duration[{self.to_nsec()}]"


class Time(_base.Time):
    """A point in time, ``repr()`` ``rospy.Time[nsecs]``; ``Time.now()`` is the current time."""

    __slots__ = ()

    def __repr__(self) -> str:
        return f"rospy.Time[{self.to_nsec()}]"

    @classmethod
    def now(cls) -> "Time":
        """The current ROS time (see :func:`get_rostime`)."""
        return get_rostime()

    @classmethod
    def from_seconds(cls, float_secs: float) -> "Time":
        """The time *float_secs* after the epoch (rospy's older spelling of ``from_sec``)."""
        return cls(float(float_secs))


def is_rostime_initialized() -> bool:
    """True once ``init_node`` has run (or :func:`set_rostime_initialized` said so): before, rospy has no time."""
    return _initialized_by_hand or is_initialized()


def set_rostime_initialized(val: bool) -> None:
    """Let a script (an offline unit test) use ROS time without ``init_node``: the wall clock, or the time
    :func:`_set_rostime` gave."""
    global _initialized_by_hand
    _initialized_by_hand = bool(val)


def _set_rostime(t: _base.Time) -> None:
    """Make the current ROS time ``t`` (rospy's hook for simulated time, which unit tests call)."""
    global _time_set_by_hand
    _time_set_by_hand = Time(t.secs, t.nsecs)


def is_wallclock() -> bool:
    """True unless the node follows simulated time from ``/clock`` (``/use_sim_time``)."""
    return _sync.is_wallclock()


def get_rostime() -> Time:
    """The current ROS time: wall clock, or the last ``/clock`` under ``/use_sim_time`` (zero before one).

    ROSInitException before ``init_node``, as in rospy.
    """
    if _time_set_by_hand is not None:
        return Time(_time_set_by_hand.secs, _time_set_by_hand.nsecs)
    if not is_initialized():
        if not _initialized_by_hand:
            raise ROSInitException("time is not initialized. Have you called init_node()?")
        return Time.from_sec(time.time())
    now = _sync.get_rostime()
    return Time(now.secs, now.nsecs)


def get_time() -> float:
    """The current time in float seconds."""
    return get_rostime().to_sec()
