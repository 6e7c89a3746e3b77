"""Adaptive busy-polling of an event loop while messages arrive close together.

A thread that sleeps in ``epoll_wait`` on an idle machine pays a slow wake-up
(CPU idle states, scheduler latency) for every message: on a quiet 2-CPU
machine that is most of a small round trip's time.  While traffic is dense
(the gap between two arrivals is shorter than the window, as in a
request/reply exchange or a fast stream), :class:`BusyPoll` keeps the loop
turning with a zero-timeout poll for up to ``window`` seconds after the last
arrival instead of letting it sleep.  Sparse traffic (a 1 kHz IMU, a 10 Hz
pose) never triggers it, so it costs nothing there.

The price is CPU: while it spins, the loop's thread uses a whole core.  So it
only spins while :class:`IdleGauge` sees at least one CPU that the rest of the
machine leaves idle (counting this process's own use as available) and fewer
other runnable threads than CPUs: on a loaded machine wake-ups are fast anyway
and the core belongs to others.  The second test is there because the first
cannot tell a spin's own use from a spare CPU: with a busy loop on each of two
cores, ping and pong still counted their spinning as spare and spun, at
107.5 µs p50 and 92 µs of CPU a round trip against 91.8 and 62 µs with no
spin at all (8 interleaved rounds).  It
decides nothing before it has watched the machine for :data:`FIRST_LOOK`
seconds: a gauge that said yes until its first half-second period ended let a
short exchange spin through its whole life on a loaded machine (round trip
p50 125 against 110 µs sleeping, 114 against 81 µs of CPU per round trip,
with a busy loop on each of two cores).

Each turn of the spin gives the CPU away (``sched_yield``) before it polls
again. Two spinning loops on a 2-CPU machine (ping's and pong's) otherwise hold
both CPUs while the thread a callback woke (a user thread waiting on an Event,
as rospy code does) waits for the scheduler to preempt one of them: on a quiet
2-vCPU VM, spinning without yielding gave a round trip p50 of 116-162 µs and
137-175 µs of the pinging process's CPU, no spin at all 101-144 µs and 74-112 µs,
and spinning with a yield each turn 62-81 µs and 75-99 µs (4 alternations).
A turn with nothing else runnable returns from the yield at once.
``ROSTUI_BUSY_POLL_US`` sets the window in microseconds (``0`` turns it off).
"""

from __future__ import annotations

import asyncio
import os
import time
from typing import Callable

DEFAULT_WINDOW_US = 250
FIRST_LOOK = 0.1
"""Seconds of watching the machine before the first decision (later ones take a whole period)."""
ENV_WINDOW = "ROSTUI_BUSY_POLL_US"


def window_from_env(default_us: int = DEFAULT_WINDOW_US) -> float:
    """The spin window in seconds from ``ROSTUI_BUSY_POLL_US`` (0 when off or unreadable as a number >= 0)."""
    text = os.environ.get(ENV_WINDOW)
    if text is None or not text.strip():
        return default_us / 1e6
    try:
        micros = float(text)
    except ValueError:
        return 0.0
    return micros / 1e6 if micros > 0 else 0.0


CROWD_STEP = 0.005
"""Seconds between two counts of the machine's runnable threads (each one read of ``/proc/loadavg``)."""


class IdleGauge:
    """Whether the machine has a CPU to spare, from ``/proc/stat`` and ``/proc/loadavg``, decided at most every
    ``period`` seconds.

    Spare CPUs = idle CPU time of the whole machine plus this process's own CPU
    time, per second of wall time; and, counted at most every :data:`CROWD_STEP`
    seconds while :meth:`spare` is asked, the runnable threads other than the
    asking one (``/proc/loadavg``'s running count less one) must be fewer than
    the CPUs on average over the period.  Where ``/proc/stat`` cannot be read
    the gauge always says yes; where ``/proc/loadavg`` cannot be, only the idle
    time counts.
    """

    __slots__ = ("_path", "_period", "_own_cpu", "_clock", "_next", "_last_sample", "_idle_spare", "_spare",
                 "_loadavg_path", "_cpus", "_next_count", "_crowd_sum", "_crowd_counts", "_crowded")

    def __init__(self, period: float = 0.5, path: str = "/proc/stat",
                 own_cpu: Callable[[], float] = time.process_time,
                 clock: Callable[[], float] = time.perf_counter,
                 loadavg_path: str = "/proc/loadavg", cpus: int | None = None) -> None:
        self._path = path
        self._period = period
        self._own_cpu = own_cpu
        self._clock = clock
        self._loadavg_path = loadavg_path
        self._cpus = cpus or os.cpu_count() or 1
        self._last_sample: tuple[float, float, float] | None = None
        self._idle_spare = False
        self._spare = False  # until the machine has been watched a while: a loaded one must not get a first spin
        self._crowd_sum = 0
        self._crowd_counts = 0
        self._crowded = False
        now = clock()
        self._next_count = now
        self._next = now + min(period, FIRST_LOOK)
        self._resample(now)

    def spare(self) -> bool:
        """True when at least one CPU was left idle by others, and fewer threads than CPUs waited to run, over the
        last period (False for the first :data:`FIRST_LOOK` seconds of the gauge; True where ``/proc/stat``
        cannot be read)."""
        now = self._clock()
        if now >= self._next_count:
            self._next_count = now + CROWD_STEP
            self._count_runnable()
        if now >= self._next:
            self._next = now + self._period
            self._resample(now)
        return self._spare

    def _count_runnable(self) -> None:
        try:
            with open(self._loadavg_path, "rb") as loadavg:
                running = int(loadavg.read().split()[3].split(b"/")[0])
        except (OSError, IndexError, ValueError):
            return
        self._crowd_sum += running - 1
        self._crowd_counts += 1

    def _resample(self, now: float) -> None:
        if self._crowd_counts:
            self._crowded = self._crowd_sum >= self._cpus * self._crowd_counts
            self._crowd_sum = self._crowd_counts = 0
        idle = self._idle_seconds()
        if idle is None:
            self._spare = True
            return
        sample = (now, idle, self._own_cpu())
        previous, self._last_sample = self._last_sample, sample
        if previous is not None:
            wall = sample[0] - previous[0]
            if wall > 0:
                self._idle_spare = (sample[1] - previous[1] + sample[2] - previous[2]) / wall >= 1.0
        self._spare = self._idle_spare and not self._crowded

    def _idle_seconds(self) -> float | None:
        """Idle and iowait time of all CPUs together, in seconds (None when unreadable)."""
        try:
            with open(self._path, "rb") as stat:
                fields = stat.readline().split()
            return (int(fields[4]) + int(fields[5])) / _CLOCK_TICKS
        except (OSError, IndexError, ValueError):
            return None


def _clock_ticks() -> int:
    try:
        return os.sysconf("SC_CLK_TCK")
    except (AttributeError, ValueError, OSError):
        return 100


_CLOCK_TICKS = _clock_ticks()


class BusyPoll:
    """Keeps one event loop polling for ``window`` seconds after dense traffic, calling ``give_way`` (by default
    ``sched_yield``: any other runnable thread goes first) before each poll."""

    __slots__ = ("_loop", "_window", "_last", "_until", "_spinning", "_clock", "_gauge", "_give_way")

    def __init__(self, loop: asyncio.AbstractEventLoop, window: float,
                 clock: Callable[[], float] = time.perf_counter, gauge: IdleGauge | None = None,
                 give_way: Callable[[], None] | None = None) -> None:
        self._give_way = give_way if give_way is not None else _give_way
        self._loop = loop
        self._gauge = gauge
        self._window = window
        self._last = float("-inf")
        self._until = 0.0
        self._spinning = False
        self._clock = clock

    @property
    def spinning(self) -> bool:
        """True while the loop is being kept awake."""
        return self._spinning

    def traffic(self) -> None:
        """Note an arrival; start or extend the spin when it came soon after the previous one."""
        now = self._clock()
        dense = now - self._last < self._window
        self._last = now
        if not dense or (self._gauge is not None and not self._gauge.spare()):
            return
        self._until = now + self._window
        if not self._spinning:
            self._spinning = True
            self._loop.call_soon(self._spin)

    def _spin(self) -> None:
        # A ready callback makes the loop poll with a zero timeout on its next turn; the CPU goes first to any
        # thread waiting for it (see the module's docstring).
        self._give_way()
        if self._clock() < self._until:
            self._loop.call_soon(self._spin)
        else:
            self._spinning = False


def _no_yield() -> None:
    """Where the platform has no ``sched_yield``: spin without giving the CPU away."""


_give_way: Callable[[], None] = getattr(os, "sched_yield", _no_yield)


def busy_poll_for(loop: asyncio.AbstractEventLoop, window: float | None = None) -> BusyPoll | None:
    """A :class:`BusyPoll` for ``loop`` with the environment's window, or None when it is off."""
    seconds = window_from_env() if window is None else window
    return BusyPoll(loop, seconds, gauge=IdleGauge()) if seconds > 0 else None
