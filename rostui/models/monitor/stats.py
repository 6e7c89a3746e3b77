"""Rate, bandwidth and age of one topic's messages, with a short history for sparklines.

The rate is rostopic hz's computation (arrivals less one over their span,
as :meth:`rostui.tools.topic.rates.HzStats.stats`) over the arrivals of the
last :data:`RATE_WINDOW_SECONDS`, so the monitor agrees with ``rostui topic
hz``, with one difference: a burst at the window's start counts as one
arrival (:func:`window_rate`).  The monitor stamps a message when its
screen's loop hands it over, so a moment when the screen is slow to draw
delivers the messages of that moment together; counted where the window
cuts, they were sent before it and would lift the rate (by a tenth for a
second's stall in ten).  The bandwidth is
:class:`~rostui.tools.topic.rates.BwStats` (rostopic bw's).  Recording a
message is one clock read and two deque appends; statistics are computed
once per :meth:`TopicStats.sample`.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass

from rostui.tools.topic.rates import BURST_FRACTION, BwStats, HzStats, window_rate

__all__ = ["TopicStats", "Sample", "window_rate", "BURST_FRACTION", "RATE_WINDOW_SECONDS", "HISTORY",
           "STALE_MIN_SECONDS", "STALE_PERIODS"]

#: Seconds of arrivals the rate is computed over (at least the last two arrivals are always kept).
RATE_WINDOW_SECONDS = 10.0
#: Arrivals kept at most for the rate (a 1 kHz topic keeps 5 s).
RATE_WINDOW_MESSAGES = 5000
#: Messages the bandwidth is averaged over (rostopic bw's default window).
BW_WINDOW_MESSAGES = 100
#: Samples (one per :meth:`TopicStats.sample`) kept for the sparklines.
HISTORY = 60
#: A topic is stale after this many of its usual periods without a message...
STALE_PERIODS = 5.0
#: ...and never sooner than this many seconds.
STALE_MIN_SECONDS = 2.0


@dataclass(frozen=True)
class Sample:
    """A topic's figures at one moment: rate (Hz), bandwidth (bytes/s), last message age (s)."""

    rate: float | None
    bandwidth: float | None
    age: float | None
    messages: int


class TopicStats:
    """Arrival times and sizes of one topic's messages since it was subscribed."""

    __slots__ = ("hz", "bw", "messages", "last_arrival", "rate", "bandwidth", "rate_history", "bw_history")

    def __init__(self) -> None:
        self.hz = HzStats(RATE_WINDOW_MESSAGES)
        self.bw = BwStats(BW_WINDOW_MESSAGES)
        self.messages = 0
        self.last_arrival: float | None = None
        self.rate: float | None = None
        self.bandwidth: float | None = None
        self.rate_history: deque[float] = deque(maxlen=HISTORY)
        self.bw_history: deque[float] = deque(maxlen=HISTORY)

    def add(self, t: float, size: int) -> None:
        """Record a message of ``size`` bytes arriving at wall time ``t``."""
        self.hz.add(t)
        self.bw.add(t, size)
        self.messages += 1
        self.last_arrival = t

    def sample(self, now: float | None = None) -> Sample:
        """Compute rate and bandwidth now, append them to the history, and return them."""
        now = time.time() if now is None else now
        times = self.hz.times
        while len(times) > 2 and times[0] < now - RATE_WINDOW_SECONDS:
            times.popleft()
        rate = window_rate(times)
        if rate is not None:
            self.rate = rate
        if self.stale_at(now):
            self.rate = None
        self.bandwidth = self.bw.bytes_per_second(now) if self.rate is not None else None
        self.rate_history.append(self.rate or 0.0)
        self.bw_history.append(self.bandwidth or 0.0)
        return Sample(self.rate, self.bandwidth, self.age(now), self.messages)

    def age(self, now: float | None = None) -> float | None:
        """Seconds since the last message (None before the first)."""
        if self.last_arrival is None:
            return None
        now = time.time() if now is None else now
        return max(0.0, now - self.last_arrival)

    def stale_limit(self) -> float:
        """Seconds without a message after which this topic counts as stale."""
        if self.rate:
            return max(STALE_MIN_SECONDS, STALE_PERIODS / self.rate)
        return STALE_MIN_SECONDS

    def stale_at(self, now: float) -> bool:
        """True when messages came but none for longer than :meth:`stale_limit`."""
        age = self.age(now)
        return age is not None and age > self.stale_limit()
