"""FrameBudget: whether one panel may draw its next frame now, so its frames stay within a share of one core.

A camera can send more frames than a terminal can show for the CPU a user
would grant a viewer.  Each panel keeps its own account of CPU time: it earns
``share`` seconds of CPU per second of wall time (up to a small reserve, so
a pause does not buy a long burst) and spends what its own frames cost: the
CPU time of the thread that decodes and draws each one, measured around it
with :meth:`FrameBudget.spending`.  What no panel's frames account for
(Textual composing the screen and writing it, the node receiving) is a
:class:`SharedCost`, shared out equally between the panels that drew lately,
so one panel alone still keeps the whole viewer within its share.  A frame
may be drawn while the account is not overdrawn; frames that arrive
meanwhile are dropped by the caller, never queued.  A heavy topic thus drops
its own frames, not its neighbours': what another panel's frames cost is
never charged here.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from typing import Callable, Iterator

__all__ = ["FrameBudget", "SharedCost", "VIEW_CPU_SHARE"]

#: The share of one core a sensor view may use (issue: a 30 fps 640x480 camera within half a core).
VIEW_CPU_SHARE = 0.45

#: Wall seconds of earnings the account may hold in reserve.
RESERVE_SECONDS = 0.5

#: A panel that drew a frame this many wall seconds ago takes its part of the shared cost.
ACTIVE_SECONDS = 1.0


class SharedCost:
    """The process's CPU time no panel's frames account for, shared out between the panels' budgets.

    ``cpu`` is the whole process's CPU clock.  Each settling charges what the process used since the last,
    less what the budgets were charged for their own frames meanwhile, equally to the budgets that drew a
    frame in the last :data:`ACTIVE_SECONDS` (to every budget when none did).
    """

    def __init__(self, *, cpu: Callable[[], float] = time.process_time) -> None:
        self._cpu = cpu
        self._at = cpu()
        self._budgets: list[FrameBudget] = []
        self._own = 0.0
        self._credit = 0.0

    def join(self, budget: FrameBudget) -> None:
        """Share the cost with ``budget`` too."""
        self._budgets.append(budget)

    def noted(self, seconds: float) -> None:
        """A budget was charged ``seconds`` for its own frames."""
        self._own += seconds

    def settle(self) -> None:
        """Charge the unaccounted CPU since the last settling.

        A frame decoded on a worker thread across a settling is charged to its panel when it ends, after
        the process's clock counted it: what was shared of it then is credited back against later costs.
        """
        now = self._cpu()
        rest = now - self._at - self._own + self._credit
        self._at, self._own, self._credit = now, 0.0, min(rest, 0.0)
        active = [b for b in self._budgets if b.drawing_lately()] or self._budgets
        if rest > 0 and active:
            for budget in active:
                budget.take_share(rest / len(active))


class FrameBudget:
    """An account of one panel's CPU time against ``share`` of a core.

    ``cpu`` is the clock :meth:`spending` reads (the calling thread's CPU time: other threads' and other
    panels' work is not this panel's); ``wall`` the clock the account earns by; ``shared`` the viewer's
    cost no panel accounts for, which this budget takes its part of.
    """

    def __init__(self, share: float = VIEW_CPU_SHARE, *, wall: Callable[[], float] = time.monotonic,
                 cpu: Callable[[], float] = time.thread_time, shared: SharedCost | None = None) -> None:
        if not 0 < share <= 1:
            raise ValueError(f"CPU share must be in (0, 1], not {share}")
        self.share = share
        self._wall = wall
        self._cpu = cpu
        self._shared = shared
        self._balance = 0.0
        self._at_wall = wall()
        self._charged_at = -ACTIVE_SECONDS
        self.spent = 0.0
        """CPU seconds charged so far for this panel's own frames."""
        if shared is not None:
            shared.join(self)

    def balance(self) -> float:
        """CPU seconds in hand now: earned at ``share`` per wall second, less what was charged."""
        if self._shared is not None:
            self._shared.settle()
        return self._earn()

    def _earn(self) -> float:
        wall = self._wall()
        earned = (wall - self._at_wall) * self.share
        self._balance = min(self._balance + earned, RESERVE_SECONDS * self.share)
        self._at_wall = wall
        return self._balance

    def take_share(self, seconds: float) -> None:
        """Take ``seconds`` of the viewer's shared cost from the account (not this panel's own frames)."""
        self._earn()
        self._balance -= seconds

    def charge(self, seconds: float) -> None:
        """Take ``seconds`` of CPU from the account (what one of this panel's frames cost)."""
        seconds = max(0.0, seconds)
        self.take_share(seconds)
        self.spent += seconds
        self._charged_at = self._at_wall
        if self._shared is not None:
            self._shared.noted(seconds)

    def drawing_lately(self) -> bool:
        """True when this panel was charged for a frame in the last :data:`ACTIVE_SECONDS`."""
        return self._wall() - self._charged_at < ACTIVE_SECONDS

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
