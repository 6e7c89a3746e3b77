"""Sleeps, rates and timers on ROS time (wall or simulated), with rospy's semantics.

Each takes the :class:`~rostui.core.node.clock.Clock` it follows and the event
that is set when the node shuts down; :mod:`rostui.core.node.sync` binds both
to the process's node.  Under simulated time a sleep waits for the first
``/clock`` message, then until the clock reaches its end; a clock that jumps
back during a sleep raises :class:`ROSTimeMovedBackwardsException`, which a
``Rate`` or ``Timer`` made with ``reset=True`` takes as a new start.
"""

from __future__ import annotations

import sys
import threading
import time
from typing import Any, Callable

from rostui.core.node.clock import Clock
from rostui.core.node.errors import ROSInterruptException, ROSTimeMovedBackwardsException
from rostui.core.rostime import Duration, Time

__all__ = ["sleep", "Rate", "Timer", "TimerEvent"]

_FIRST_CLOCK_POLL = 0.3
_SIM_POLL = 0.5


def _duration(value: float | Duration) -> Duration:
    return value if isinstance(value, Duration) else Duration.from_sec(float(value))


def sleep(clock: Clock, shutdown: threading.Event, duration: float | Duration) -> None:
    """Sleep *duration* of ROS time; ROSInterruptException on shutdown.

    Under simulated time: ROSTimeMovedBackwardsException when the clock goes back meanwhile.
    """
    if clock.is_wallclock:
        seconds = duration.to_sec() if isinstance(duration, Duration) else float(duration)
        if seconds > 0 and shutdown.wait(seconds):
            raise ROSInterruptException("ROS shutdown request")
        return
    span = _duration(duration)
    start = clock.now()
    while start.is_zero() and not shutdown.is_set():
        clock.wait(_FIRST_CLOCK_POLL)
        start = clock.now()
    end = start + span
    now = clock.now()
    while start <= now < end and not shutdown.is_set():
        clock.wait(_SIM_POLL)
        now = clock.now()
    if now < start:
        raise ROSTimeMovedBackwardsException((start - now).to_sec())
    if shutdown.is_set():
        raise ROSInterruptException("ROS shutdown request")


class Rate:
    """Keeps a loop at *hz* cycles a second of ROS time (like rospy.Rate / ros::Rate).

    With *reset*, a clock that jumps back restarts the cycle instead of raising
    ROSTimeMovedBackwardsException from :meth:`sleep`.
    """

    def __init__(self, hz: float, clock: Clock, shutdown: threading.Event, reset: bool = False) -> None:
        if hz <= 0:
            raise ValueError("rate must be positive")
        self._clock, self._shutdown = clock, shutdown
        self.sleep_dur = Duration(0, int(1e9 / hz))
        self.last_time = clock.now()
        self._reset = reset

    def _remaining(self, now: Time) -> Duration:
        if self.last_time > now:
            self.last_time = now
        return self.sleep_dur - (now - self.last_time)

    def remaining(self) -> Duration:
        """ROS time left in the current cycle."""
        return self._remaining(self._clock.now())

    def sleep(self) -> None:
        """Sleep until the next cycle; ROSInterruptException on shutdown."""
        now = self._clock.now()
        try:
            sleep(self._clock, self._shutdown, self._remaining(now))
        except ROSTimeMovedBackwardsException:
            if not self._reset:
                raise
            self.last_time = self._clock.now()
            return
        if self._shutdown.is_set():
            raise ROSInterruptException("ROS shutdown request")
        self.last_time = self.last_time + self.sleep_dur
        if now - self.last_time > self.sleep_dur * 2:
            self.last_time = now


class TimerEvent:
    """What a Timer callback receives: ROS times as float seconds, *last_duration* in wall seconds."""

    def __init__(self, last_expected: float | None, last_real: float | None, current_expected: float,
                 current_real: float, last_duration: float | None) -> None:
        self.last_expected = last_expected
        self.last_real = last_real
        self.current_expected = current_expected
        self.current_real = current_real
        self.last_duration = last_duration


def _sec(stamp: Time | None) -> float | None:
    return None if stamp is None else stamp.to_sec()


class Timer(threading.Thread):
    """Calls ``callback(event)`` every *period* of ROS time, on its own thread, until shutdown.

    *oneshot* fires once; *reset* restarts the period when the clock jumps
    back (without it the timer stops, as rospy's).  An exception in the
    callback is printed and the timer goes on.
    """

    def __init__(self, period: float | Duration, callback: Callable[[Any], Any], clock: Clock,
                 shutdown: threading.Event, oneshot: bool = False, reset: bool = False) -> None:
        super().__init__(daemon=True, name="rostui-timer")
        self.period = _duration(period)
        if self.period.to_sec() <= 0:
            raise ValueError("timer period must be positive")
        self.callback = callback
        self.oneshot = oneshot
        self._clock, self._node_shutdown = clock, shutdown
        self._reset = reset
        self._stopped = False
        self.start()

    def make_event(self, last_expected: Time | None, last_real: Time | None, current_expected: Time,
                   current_real: Time, last_duration: float | None) -> Any:
        """The object the callback receives (a subclass may give its own kind)."""
        return TimerEvent(_sec(last_expected), _sec(last_real), current_expected.to_sec(), current_real.to_sec(),
                          last_duration)

    def run(self) -> None:
        """Fire the callback each period until shutdown (the thread's body)."""
        rate = Rate(1.0 / self.period.to_sec(), self._clock, self._node_shutdown, reset=self._reset)
        expected = self._clock.now() + self.period
        last_expected: Time | None = None
        last_real: Time | None = None
        last_duration: float | None = None
        while not self._node_shutdown.is_set() and not self._stopped:
            try:
                rate.sleep()
            except ROSTimeMovedBackwardsException as exc:
                sys.stderr.write(f"timer stopped: ROS time moved backwards by {exc.time} s\n")
                return
            except ROSInterruptException:
                return
            if self._stopped:
                return
            real = self._clock.now()
            started = time.time()
            try:
                self.callback(self.make_event(last_expected, last_real, expected, real, last_duration))
            except Exception as exc:
                sys.stderr.write(f"error in timer callback: {exc}\n")
            if self.oneshot:
                self._stopped = True
                return
            last_duration = time.time() - started
            last_expected, last_real = expected, real
            expected = expected + self.period

    def shutdown(self) -> None:
        """Stop firing callbacks."""
        self._stopped = True
