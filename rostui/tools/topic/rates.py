"""``rostui topic hz`` and ``bw`` statistics (rostopic's windows, rates and units), shared with the monitor."""

from __future__ import annotations

import math
from collections import deque
from typing import Sequence

#: ``hz`` keeps at most this many messages when no window is given.
HZ_DEFAULT_WINDOW = 50000
#: ``bw``'s default window.
BW_DEFAULT_WINDOW = 100
#: Arrivals closer than this fraction of a window's mean interval to the next one are one burst.
BURST_FRACTION = 0.1
#: Arrivals spanning less than this many seconds give no rate yet: a reader that was held up takes several
#: messages in one read, and three of a 20 Hz topic arriving within 0.15 ms would read as 13 kHz.
MIN_RATE_SPAN = 0.2


def window_rate(times: Sequence[float]) -> float | None:
    """Messages per second over ``times`` (arrivals, oldest first), a burst at the start counting once.

    rostopic hz's rate (intervals over span) once the arrivals that came in
    one burst with the first are left out but for the burst's last: they were
    sent before the window began.  None with fewer than two arrivals or when
    those counted span less than :data:`MIN_RATE_SPAN`; 0 when they all came at once.
    """
    count = len(times)
    if count < 2:
        return None
    last = times[-1]
    mean = (last - times[0]) / (count - 1)
    if mean <= 0.0:
        return 0.0
    burst = mean * BURST_FRACTION
    start = 0
    while start < count - 2 and times[start + 1] - times[start] < burst:
        start += 1
    span = last - times[start]
    if span < MIN_RATE_SPAN:
        return None
    return (count - 1 - start) / span


class HzStats:
    """Arrival times of one topic's messages; rostopic hz's statistics over a window.

    Adding a message is one clock read and one deque append; the statistics
    are computed when printed (once a second).
    """

    __slots__ = ("times", "last_printed", "window")

    def __init__(self, window: int = -1) -> None:
        self.window = window if window is not None and window >= 0 else HZ_DEFAULT_WINDOW
        self.times: deque[float] = deque(maxlen=max(self.window, 1))
        self.last_printed = 0.0

    def add(self, t: float) -> None:
        """Record an arrival at wall time *t* (seconds); a clock jump back restarts the window."""
        times = self.times
        if times and times[0] > t:
            times.clear()
        times.append(t)

    def stats(self) -> tuple[float, float, float, float, int] | None:
        """``(rate, min_delta, max_delta, std_dev, window)`` or None when there is nothing new."""
        times = list(self.times)
        if len(times) < 2 or times[-1] == self.last_printed:
            return None
        deltas = [b - a for a, b in zip(times, times[1:])]
        n = len(deltas)
        mean = (times[-1] - times[0]) / n
        rate = 1.0 / mean if mean > 0.0 else 0
        std_dev = math.sqrt(sum((x - mean) ** 2 for x in deltas) / n)
        self.last_printed = times[-1]
        return rate, min(deltas), max(deltas), std_dev, n + 1


def format_hz(stats: tuple[float, float, float, float, int] | None) -> str:
    """One topic's report (``average rate: ...`` and its second line, or ``no new messages``)."""
    if stats is None:
        return "no new messages\n"
    rate, lo, hi, sd, window = stats
    return "average rate: %.3f\n\tmin: %.3fs max: %.3fs std dev: %.5fs window: %s\n" % (rate, lo, hi, sd, window)


def format_hz_table(rows: Sequence[tuple[str, tuple[float, float, float, float, int] | None]]) -> str:
    """Several topics' report as rostopic's ASCII table (its window column included, quirks and all)."""
    header = ["topic", "rate", "min_delta", "max_delta", "std_dev", "window"]
    cols: dict[str, list[str]] = {h: [] for h in header}
    for topic, st in rows:
        if st is None:
            continue
        rate, lo, hi, sd, window = st
        # rostopic appends the window twice per topic; rows then take the first entries.
        cols["window"].append(str(window))
        cols["topic"].append(topic)
        cols["rate"].append("{:.4}".format(rate))
        cols["min_delta"].append("{:.4}".format(lo))
        cols["max_delta"].append("{:.4}".format(hi))
        cols["std_dev"].append("{:.4}".format(sd))
        cols["window"].append(str(window))
    if not cols["topic"]:
        return "no new messages\n"
    widths = []
    heads = []
    for h in header:
        w = max(len(h), max(len(x) for x in cols[h]))
        widths.append(w)
        heads.append(h.center(w))
        cols[h] = [x.ljust(w) for x in cols[h]]
    hline = "=" * (sum(widths) + 3 * (len(header) - 1))
    body = "\n".join("   ".join(cols[h][i] for h in header) for i in range(len(cols["topic"])))
    return "   ".join(heads) + "\n" + hline + "\n" + body + "\n\n"


def bandwidth_unit(bps: float) -> tuple[float, str]:
    """rostopic bw's unit for a byte rate, as (divisor, suffix): bytes below 1000, then KB, then MB."""
    if bps < 1000:
        return 1.0, "B"
    if bps < 1_000_000:
        return 1000.0, "KB"
    return 1_000_000.0, "MB"


class BwStats:
    """Sizes and arrival times of the last ``window`` messages (rostopic bw)."""

    def __init__(self, window: int | None = None) -> None:
        self.window = window or BW_DEFAULT_WINDOW
        self.times: deque[float] = deque(maxlen=self.window)
        self.sizes: deque[int] = deque(maxlen=self.window)

    def add(self, t: float, size: int) -> None:
        """Record one message of *size* bytes arriving at *t*."""
        self.times.append(t)
        self.sizes.append(size)

    def bytes_per_second(self, now: float) -> float | None:
        """The window's bytes divided by the time since its first message (None with fewer than two)."""
        if len(self.times) < 2 or now <= self.times[0]:
            return None
        return sum(self.sizes) / (now - self.times[0])

    def report(self, now: float) -> str | None:
        """The two report lines, or None with fewer than two messages."""
        if len(self.times) < 2:
            return None
        n = len(self.times)
        total = sum(self.sizes)
        bps = total / (now - self.times[0])
        mean = total / n
        divisor, unit = bandwidth_unit(bps)
        bw, mean_s, lo, hi = ["%.2f%s" % (v / divisor, unit) for v in (bps, mean, min(self.sizes), max(self.sizes))]
        return "average: %s/s\n\tmean: %s min: %s max: %s window: %s\n" % (bw, mean_s, lo, hi, n)
