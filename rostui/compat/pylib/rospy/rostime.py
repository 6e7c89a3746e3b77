"""rospy.rostime: ``rospy.Time`` and ``rospy.Duration`` (genpy's, printing as rospy's) and the clock.

Their bases are rostui's times, which are the shim's ``genpy.Time`` and ``genpy.Duration``.
"""

from __future__ import annotations

from rostui.core import rostime as _base
from rostui.core.node import sync as _sync

from .exceptions import ROSInitException
from .names import is_initialized

__all__ = ["Time", "Duration", "get_rostime", "get_time", "is_wallclock", "is_rostime_initialized"]


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
    """True once ``init_node`` has run: before it rospy has no time to give."""
    return is_initialized()


def is_wallclock() -> bool:
    """True unless the node follows simulated time from ``/clock`` (``/use_sim_time``)."""
    return _sync.is_wallclock()


def get_rostime() -> Time:
    """The current ROS time: wall clock, or the last ``/clock`` under ``/use_sim_time`` (zero before one).

    ROSInitException before ``init_node``, as in rospy.
    """
    if not is_initialized():
        raise ROSInitException("time is not initialized. Have you called init_node()?")
    now = _sync.get_rostime()
    return Time(now.secs, now.nsecs)


def get_time() -> float:
    """The current time in float seconds."""
    return get_rostime().to_sec()
