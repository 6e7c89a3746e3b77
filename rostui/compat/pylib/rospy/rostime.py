"""rospy.rostime: ``rospy.Time`` and ``rospy.Duration`` (genpy's, printing as rospy's) and the clock.

Their bases are rostui's times, which are the shim's ``genpy.Time`` and ``genpy.Duration``.
"""

from __future__ import annotations

import time

from rostui.core import rostime as _base

__all__ = ["Time", "Duration", "get_rostime", "get_time"]


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
    def from_seconds(cls, float_secs: float) -> "Time":
        """The time *float_secs* after the epoch (rospy's older spelling of ``from_sec``)."""
        return cls(float(float_secs))


def get_rostime() -> Time:
    """The current time as a :class:`Time` (wall clock: rostui has no simulated time for rospy yet)."""
    return Time.from_nsec(time.time_ns())


def get_time() -> float:
    """The current time in float seconds."""
    return get_rostime().to_sec()
