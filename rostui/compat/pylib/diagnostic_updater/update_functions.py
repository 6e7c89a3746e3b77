"""Ready-made diagnostic tasks: an event rate within bounds, timestamps within bounds, a heartbeat."""

from __future__ import annotations

import threading
from typing import Any

import rospy

from .tasks import DiagnosticTask

__all__ = ["FrequencyStatus", "FrequencyStatusParam", "Heartbeat", "TimeStampStatus", "TimeStampStatusParam"]

OK, WARN, ERROR = 0, 1, 2


class FrequencyStatusParam:
    """The rate a FrequencyStatus accepts: ``freq_bound`` {'min': hz, 'max': hz (optional)}, a relative tolerance,
    and how many updates the measuring window spans."""

    def __init__(self, freq_bound: dict[str, float], tolerance: float = 0.1, window_size: int = 5) -> None:
        self.freq_bound = freq_bound
        self.tolerance = tolerance
        self.window_size = window_size


class FrequencyStatus(DiagnosticTask):
    """Counts ``tick()`` events and reports their rate over the last ``window_size`` updates against the bounds."""

    def __init__(self, params: FrequencyStatusParam, name: str = "FrequencyStatus") -> None:
        super().__init__(name)
        self.params = params
        self.lock = threading.Lock()
        self.clear()

    def clear(self) -> None:
        """Start counting again."""
        with self.lock:
            self.count = 0
            now = rospy.Time.now()
            self.times = [now] * self.params.window_size
            self.seq_nums = [0] * self.params.window_size
            self.hist_indx = 0

    def tick(self) -> None:
        """Count one event."""
        with self.lock:
            self.count += 1

    def run(self, stat: Any) -> Any:
        """The rate over the window: too low, too high, none, or met; with the counts and bounds as key-values."""
        bound, tolerance = self.params.freq_bound, self.params.tolerance
        with self.lock:
            now = rospy.Time.now()
            events = self.count - self.seq_nums[self.hist_indx]
            window = (now - self.times[self.hist_indx]).to_sec()
            freq = events / window if window > 0 else float("inf") if events else 0.0  # (a clock standing still)
            self.seq_nums[self.hist_indx] = self.count
            self.times[self.hist_indx] = now
            self.hist_indx = (self.hist_indx + 1) % self.params.window_size
            if events == 0:
                stat.summary(ERROR, "No events recorded.")
            elif freq < bound["min"] * (1 - tolerance):
                stat.summary(WARN, "Frequency too low.")
            elif "max" in bound and freq > bound["max"] * (1 + tolerance):
                stat.summary(WARN, "Frequency too high.")
            else:
                stat.summary(OK, "Desired frequency met")
            stat.add("Events in window", "%d" % events)
            stat.add("Events since startup", "%d" % self.count)
            stat.add("Duration of window (s)", "%f" % window)
            stat.add("Actual frequency (Hz)", "%f" % freq)
            if "max" in bound and bound["min"] == bound["max"]:
                stat.add("Target frequency (Hz)", "%f" % bound["min"])
            if bound["min"] > 0:
                stat.add("Minimum acceptable frequency (Hz)", "%f" % (bound["min"] * (1 - tolerance)))
            if "max" in bound:
                stat.add("Maximum acceptable frequency (Hz)", "%f" % (bound["max"] * (1 + tolerance)))
        return stat


class TimeStampStatusParam:
    """How far from now (seconds, past positive) the stamps a TimeStampStatus sees may lie."""

    def __init__(self, min_acceptable: float = -1, max_acceptable: float = 5) -> None:
        self.max_acceptable = max_acceptable
        self.min_acceptable = min_acceptable


class TimeStampStatus(DiagnosticTask):
    """Reports the earliest and latest delay of the stamps given to ``tick()`` since the last update."""

    def __init__(self, params: TimeStampStatusParam | None = None, name: str = "Timestamp Status") -> None:
        super().__init__(name)
        self.params = params if params is not None else TimeStampStatusParam()
        self.lock = threading.Lock()
        self.early_count = self.late_count = self.zero_count = 0
        self.zero_seen = False
        self.max_delta = self.min_delta = 0.0
        self.deltas_valid = False

    def tick(self, stamp: Any) -> None:
        """See a stamp (a rospy.Time or float seconds); 0 is counted as a zero stamp."""
        seconds = stamp if isinstance(stamp, float) else stamp.to_sec()
        with self.lock:
            if seconds == 0:
                self.zero_seen = True
                return
            delta = rospy.Time.now().to_sec() - seconds
            if not self.deltas_valid or delta > self.max_delta:
                self.max_delta = delta
            if not self.deltas_valid or delta < self.min_delta:
                self.min_delta = delta
            self.deltas_valid = True

    def run(self, stat: Any) -> Any:
        """Whether the stamps since the last update were within the bounds, and the counts of those that were not."""
        with self.lock:
            stat.summary(OK, "Timestamps are reasonable.")
            if not self.deltas_valid:
                stat.summary(WARN, "No data since last update.")
            else:
                if self.min_delta < self.params.min_acceptable:
                    stat.summary(ERROR, "Timestamps too far in future seen.")
                    self.early_count += 1
                if self.max_delta > self.params.max_acceptable:
                    stat.summary(ERROR, "Timestamps too far in past seen.")
                    self.late_count += 1
                if self.zero_seen:
                    stat.summary(ERROR, "Zero timestamp seen.")
                    self.zero_count += 1
            stat.add("Earliest timestamp delay:", "%f" % self.min_delta)
            stat.add("Latest timestamp delay:", "%f" % self.max_delta)
            stat.add("Earliest acceptable timestamp delay:", "%f" % self.params.min_acceptable)
            stat.add("Latest acceptable timestamp delay:", "%f" % self.params.max_acceptable)
            stat.add("Late diagnostic update count:", "%i" % self.late_count)
            stat.add("Early diagnostic update count:", "%i" % self.early_count)
            stat.add("Zero seen diagnostic update count:", "%i" % self.zero_count)
            self.deltas_valid = False
            self.min_delta = self.max_delta = 0.0
            self.zero_seen = False
        return stat


class Heartbeat(DiagnosticTask):
    """Always OK, "Alive"."""

    def __init__(self) -> None:
        super().__init__("Heartbeat")

    def run(self, stat: Any) -> Any:
        """Say it is alive."""
        stat.summary(OK, "Alive")
        return stat
