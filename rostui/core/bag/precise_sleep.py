"""Waking at a given moment without spinning: a sleep with Linux's timer slack lowered.

A plain ``time.sleep`` wakes late here by the kernel's timer slack (50 µs by
default) plus the scheduler's wake-up (30-80 µs on this VM). Spinning through
the end of each wait made a player exact to a microsecond, but it spun that
whole wake-up time before every message: at 400 messages a second, 45 µs a
message was a third of ``rostui bag play``'s CPU, more than ``rosbag play``
spends in all. Neither player spins now: :func:`sleep_until` sleeps and
returns, and :func:`lower_timer_slack` removes the slack, so a message leaves
as late as the scheduler wakes the thread, and by about as much each time
(what a subscriber sees as jitter is the spread of that lateness, level with
``rosbag play``'s: bench/README.md, "Bag play CPU").
"""

from __future__ import annotations

import time
from collections.abc import Callable

from rostui.core.libc import libc_function

PR_SET_TIMERSLACK = 29


def lower_timer_slack(nanoseconds: int = 1) -> bool:
    """Set the calling thread's timer slack (Linux; default 50 µs); False where that cannot be done."""
    prctl = libc_function("prctl")
    return prctl is not None and int(prctl(PR_SET_TIMERSLACK, nanoseconds, 0, 0, 0)) == 0


def sleep_until(moment: float, clock: Callable[[], float] = time.perf_counter,
                sleep: Callable[[float], None] = time.sleep) -> None:
    """Block the calling thread until ``moment`` of ``clock`` (at once when it has passed); no spinning."""
    left = moment - clock()
    if left > 0:
        sleep(left)
