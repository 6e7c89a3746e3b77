"""What every hostile test shares: the victim's memory sampled while it is attacked, a legitimate client timed
alongside, and the figures written down for the record (requests tried, peak RSS, legitimate latency).

Tests assert what a user would see (the victim alive, its memory bounded, the legitimate client served); the
times are recorded, never asserted. ``ROSTUI_HOSTILE_REPORT=FILE`` collects every figure as JSON lines.
"""

from __future__ import annotations

import json
import os
import statistics
import threading
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

import psutil

if TYPE_CHECKING:
    from typing_extensions import Self

MB = 1024 * 1024


class Background:
    """Runs :meth:`_run` on a thread while in a ``with`` block; ``_run`` ends once ``_stop`` is set."""

    def __init__(self) -> None:
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        raise NotImplementedError

    def __enter__(self) -> Self:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


class RssSampler(Background):
    """Samples a process's resident memory every 20 ms from a thread, while in a ``with`` block."""

    def __init__(self, pid: int) -> None:
        self.process = psutil.Process(pid)
        self.baseline = self.process.memory_info().rss
        self.peak = self.baseline
        super().__init__()

    def _run(self) -> None:
        while not self._stop.wait(0.02):
            try:
                self.peak = max(self.peak, self.process.memory_info().rss)
            except psutil.Error:
                return

    @property
    def growth_mb(self) -> float:
        """How far the peak rose above the memory before the attack, in MiB."""
        return (self.peak - self.baseline) / MB


@dataclass
class LegitClient(Background):
    """Runs ``call`` over and over from a thread while in a ``with`` block; keeps each latency and each failure."""

    call: Callable[[], Any]
    pause: float = 0.05
    latencies: list[float] = field(default_factory=list)
    failures: list[str] = field(default_factory=list)

    def __post_init__(self) -> None:
        super().__init__()

    def _run(self) -> None:
        while not self._stop.is_set():
            start = time.perf_counter()
            try:
                self.call()
                self.latencies.append(time.perf_counter() - start)
            except Exception as exc:  # every failure is the finding, whatever its type
                self.failures.append(f"{type(exc).__name__}: {exc}")
            self._stop.wait(self.pause)

    @property
    def median_ms(self) -> float:
        """The median latency in milliseconds (nan when nothing was answered)."""
        return statistics.median(self.latencies) * 1000 if self.latencies else float("nan")

    @property
    def max_ms(self) -> float:
        """The slowest answer in milliseconds (nan when nothing was answered)."""
        return max(self.latencies) * 1000 if self.latencies else float("nan")


def record(test: str, victim: str, **figures: Any) -> None:
    """Print one test's figures, and append them to ``$ROSTUI_HOSTILE_REPORT`` when that is set."""
    line = json.dumps({"test": test, "victim": victim, **figures}, default=str)
    print(line)
    path = os.environ.get("ROSTUI_HOSTILE_REPORT")
    if path:
        with open(path, "a") as f:
            f.write(line + "\n")


def attack_figures(rss: RssSampler, legit: LegitClient, tried: int) -> dict[str, Any]:
    """The figures every hostile test records: requests tried, RSS growth, legitimate latency and failures."""
    return {"tried": tried, "peak_rss_growth_mb": round(rss.growth_mb, 1),
            "legit_calls": len(legit.latencies), "legit_failures": len(legit.failures),
            "legit_median_ms": round(legit.median_ms, 2), "legit_max_ms": round(legit.max_ms, 1)}
