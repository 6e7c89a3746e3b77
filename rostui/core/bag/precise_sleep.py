"""Waking at a given moment to a few microseconds while spinning as little as this machine's sleeps allow.

A plain ``time.sleep`` wakes 50-150 µs late here (the kernel's timer slack plus
the scheduler's wake-up); spinning the last 0.2 ms before every message made
that exact, but at hundreds of messages a second the spin was most of a bag
player's CPU. :class:`PreciseSleeper` learns how late its own sleeps wake (the
median of the recent ones), sleeps until that much before the moment and spins
only what is left, which is a few microseconds when wake-ups are regular.
:func:`lower_timer_slack` asks Linux to stop rounding this thread's sleeps up
by its default 50 µs.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable

from rostui.core.libc import libc_function

MAX_EARLY = 0.0002
"""The most a sleep is cut short to be spun instead (s): wake-ups later than this are not chased."""
HISTORY = 15
PR_SET_TIMERSLACK = 29


def lower_timer_slack(nanoseconds: int = 1) -> bool:
    """Set the calling thread's timer slack (Linux; default 50 µs); False where that cannot be done."""
    prctl = libc_function("prctl")
    return prctl is not None and int(prctl(PR_SET_TIMERSLACK, nanoseconds, 0, 0, 0)) == 0


class PreciseSleeper:
    """Blocks the calling thread until a moment of ``clock``; learns its sleeps' lateness to spin little."""

    __slots__ = ("_clock", "_sleep", "_late", "_early")

    def __init__(self, clock: Callable[[], float] = time.perf_counter,
                 sleep: Callable[[float], None] = time.sleep) -> None:
        self._clock = clock
        self._sleep = sleep
        self._late: deque[float] = deque(maxlen=HISTORY)
        self._early = MAX_EARLY  # until sleeps have been seen, cut them short by the most

    @property
    def early(self) -> float:
        """How long before the moment the next sleep ends (s); the rest is spun."""
        return self._early

    def sleep_until(self, moment: float) -> None:
        """Return at ``moment`` (or at once when it has passed)."""
        clock = self._clock
        asked = moment - self._early - clock()
        if asked > 0:
            self._sleep(asked)
            woke = clock()
            self._learn(woke - (moment - self._early))
        while clock() < moment:
            pass

    def _learn(self, late: float) -> None:
        self._late.append(max(0.0, late))
        ordered = sorted(self._late)
        self._early = min(MAX_EARLY, ordered[len(ordered) // 2])
