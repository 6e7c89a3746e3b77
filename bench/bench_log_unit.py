"""Cost of rostui's NodeLog calls (not a test): disabled levels, named loggers, enabled calls.

Run: .venv/bin/python bench/bench_log_unit.py
The full benchmark against rospy's loginfo (console + /rosout) lives elsewhere.
"""

from __future__ import annotations

import io
import timeit

from rostui.core.log import Console, Level, LoggerTree, NodeLog


def per_call_ns(stmt, number: int = 1_000_000, repeat: int = 5) -> float:
    """Best-of-``repeat`` nanoseconds per call of ``stmt``."""
    return min(timeit.repeat(stmt, number=number, repeat=repeat)) / number * 1e9


def main() -> None:
    """Print per-call costs."""
    tree = LoggerTree()
    sink = io.StringIO()
    log = NodeLog("/bench", "ros.bench", tree, Console(stdout=sink, stderr=sink, color=False))
    value = 42
    rows = [
        ("debug() disabled, no args", lambda: log.debug("counted to")),
        ("debug() disabled, 1 arg", lambda: log.debug("counted to %d", value)),
        ("log(DEBUG) disabled", lambda: log.log(Level.DEBUG, "counted to %d", value)),
        ("debug_once() disabled", lambda: log.debug_once("counted to %d", value)),
        ("debug_throttle() disabled", lambda: log.debug_throttle(1.0, "counted to %d", value)),
        ("debug(logger='sub') disabled", lambda: log.debug("counted to %d", value, logger="sub")),
    ]
    for label, fn in rows:
        print(f"{label:34s} {per_call_ns(fn):8.1f} ns/call")
    enabled = lambda: log.info("counted to %d", value)  # noqa: E731
    print(f"{'info() enabled -> StringIO console':34s} {per_call_ns(enabled, number=100_000):8.1f} ns/call")
    empty = lambda: None  # noqa: E731
    print(f"{'(empty lambda, call overhead)':34s} {per_call_ns(empty):8.1f} ns/call")


if __name__ == "__main__":
    main()
