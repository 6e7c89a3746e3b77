"""ROS time of a process's node: the wall clock, or the last ``/clock`` message under ``/use_sim_time``.

Under simulated time the clock is zero until the first ``rosgraph_msgs/Clock``
arrives; every sleep waits on the condition :meth:`Clock.set` notifies, so
it follows the simulated clock however fast or slow it runs.
"""

from __future__ import annotations

import threading
import time

from rostui.core.rostime import Time

__all__ = ["Clock", "CLOCK_TOPIC", "USE_SIM_TIME_PARAM"]

CLOCK_TOPIC = "/clock"
"""The topic simulated time comes from."""
USE_SIM_TIME_PARAM = "/use_sim_time"
"""The parameter that, true when a node starts, makes it follow :data:`CLOCK_TOPIC`."""


class Clock:
    """The current ROS time; thread-safe."""

    def __init__(self) -> None:
        self._sim: Time | None = None
        self._changed = threading.Condition()

    @property
    def is_wallclock(self) -> bool:
        """True while the clock is the wall clock (no simulated time)."""
        return self._sim is None

    def set(self, stamp: Time) -> None:
        """Switch to (or advance) simulated time, waking every sleeper."""
        with self._changed:
            self._sim = Time(stamp.secs, stamp.nsecs)
            self._changed.notify_all()

    def use_wallclock(self) -> None:
        """Go back to the wall clock, waking every sleeper."""
        with self._changed:
            self._sim = None
            self._changed.notify_all()

    def now(self) -> Time:
        """The current ROS time."""
        sim = self._sim
        if sim is not None:
            return Time(sim.secs, sim.nsecs)
        return Time.from_nsec(time.time_ns())

    def now_ns(self) -> int:
        """The current ROS time in nanoseconds since the epoch."""
        sim = self._sim
        return time.time_ns() if sim is None else sim.to_nsec()

    def wait(self, timeout: float) -> None:
        """Block until the clock changes, :meth:`wake` is called, or *timeout* wall seconds pass."""
        with self._changed:
            self._changed.wait(timeout)

    def wake(self) -> None:
        """Wake every sleeper (on shutdown) without changing the time."""
        with self._changed:
            self._changed.notify_all()
