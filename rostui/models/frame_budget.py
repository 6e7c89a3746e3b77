"""FrameBudget: whether a view may draw its next frame now, so the process stays within a share of one core.

A camera can send more frames than a terminal can show for the CPU a user
would grant a viewer.  The budget keeps an account of CPU time: it earns
``share`` seconds of CPU per second of wall time (up to a small reserve, so
a pause does not buy a long burst) and spends what the whole process really
used (decoding, drawing, writing to the terminal, receiving, on every
thread).  A frame may be drawn while the account is not overdrawn; frames
that arrive meanwhile are dropped by the caller, never queued.  On a loaded
machine each frame costs more, so fewer are drawn and the share holds.
"""

from __future__ import annotations

import time
from typing import Callable

__all__ = ["FrameBudget", "VIEW_CPU_SHARE"]

#: The share of one core a sensor view may use (issue: a 30 fps 640x480 camera within half a core).
VIEW_CPU_SHARE = 0.45

#: Wall seconds of earnings the account may hold in reserve.
RESERVE_SECONDS = 0.5


class FrameBudget:
    """An account of the process's CPU time against ``share`` of a core."""

    def __init__(self, share: float = VIEW_CPU_SHARE, *, wall: Callable[[], float] = time.monotonic,
                 cpu: Callable[[], float] = time.process_time) -> None:
        if not 0 < share <= 1:
            raise ValueError(f"CPU share must be in (0, 1], not {share}")
        self.share = share
        self._wall = wall
        self._cpu = cpu
        self._balance = 0.0
        self._at_wall = wall()
        self._at_cpu = cpu()

    def balance(self) -> float:
        """CPU seconds in hand now: earned at ``share`` per wall second, less what the process used."""
        wall, cpu = self._wall(), self._cpu()
        earned = (wall - self._at_wall) * self.share
        self._balance = min(self._balance + earned, RESERVE_SECONDS * self.share) - max(0.0, cpu - self._at_cpu)
        self._at_wall, self._at_cpu = wall, cpu
        return self._balance

    def wait(self) -> float:
        """Seconds to wait before the next frame may be drawn (0: draw now)."""
        balance = self.balance()
        return 0.0 if balance >= 0 else -balance / self.share
