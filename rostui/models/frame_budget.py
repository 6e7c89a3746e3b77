"""FrameBudget: whether one panel may draw its next frame now, so its own frames stay within a share of one core.

A camera can send more frames than a terminal can show for the CPU a user
would grant a viewer.  Each panel keeps its own account of CPU time: it earns
``share`` seconds of CPU per second of wall time (up to a small reserve, so
a pause does not buy a long burst) and spends what its own frames cost:
the CPU time of the thread that decodes and draws them, measured around
each frame with :meth:`FrameBudget.spending`.  A frame may be drawn while
the account is not overdrawn; frames that arrive meanwhile are dropped by
the caller, never queued.  A heavy topic thus drops its own frames, not its
neighbours': what another panel spends is never charged here.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from typing import Callable, Iterator

__all__ = ["FrameBudget", "VIEW_CPU_SHARE"]

#: The share of one core a sensor view may use (issue: a 30 fps 640x480 camera within half a core).
VIEW_CPU_SHARE = 0.45

#: Wall seconds of earnings the account may hold in reserve.
RESERVE_SECONDS = 0.5


class FrameBudget:
    """An account of one panel's CPU time against ``share`` of a core.

    ``cpu`` is the clock :meth:`spending` reads (the calling thread's CPU time: other threads' and other
    panels' work is not this panel's); ``wall`` the clock the account earns by.
    """

    def __init__(self, share: float = VIEW_CPU_SHARE, *, wall: Callable[[], float] = time.monotonic,
                 cpu: Callable[[], float] = time.thread_time) -> None:
        if not 0 < share <= 1:
            raise ValueError(f"CPU share must be in (0, 1], not {share}")
        self.share = share
        self._wall = wall
        self._cpu = cpu
        self._balance = 0.0
        self._at_wall = wall()
        self.spent = 0.0
        """CPU seconds charged so far."""

    def balance(self) -> float:
        """CPU seconds in hand now: earned at ``share`` per wall second, less what was charged."""
        wall = self._wall()
        earned = (wall - self._at_wall) * self.share
        self._balance = min(self._balance + earned, RESERVE_SECONDS * self.share)
        self._at_wall = wall
        return self._balance

    def charge(self, seconds: float) -> None:
        """Take ``seconds`` of CPU from the account (what one frame cost)."""
        self.balance()
        self._balance -= max(0.0, seconds)
        self.spent += max(0.0, seconds)

    @contextmanager
    def spending(self) -> Iterator[None]:
        """Charge the CPU time the ``with`` block takes on this thread."""
        start = self._cpu()
        try:
            yield
        finally:
            self.charge(self._cpu() - start)

    def wait(self) -> float:
        """Seconds to wait before the next frame may be drawn (0: draw now)."""
        balance = self.balance()
        return 0.0 if balance >= 0 else -balance / self.share
