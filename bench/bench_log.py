#!/usr/bin/env python3
"""Logging benchmark: rostui's loginfo/logdebug against rospy's, in the same run.

Starts a ``rostui core`` (master + rosout, so /rosout has a subscriber) on a
free port with a private ROS_HOME, then runs bench/log_peer.py for each library
in turn: N enabled calls (console, redirected to /dev/null, + /rosout + log
file) and 10 N disabled calls.  Prints calls per second, ns per disabled call,
the ratios, and whether a disabled call costs under 1 µs.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BENCH = Path(__file__).resolve().parent
sys.path.insert(0, str(BENCH))
from bench_pubsub import SYSTEM_PYTHON, free_port, venv_python  # noqa: E402


def run_peer(lib: str, n: int, env: dict[str, str]) -> dict[str, float]:
    """One library's numbers."""
    python = SYSTEM_PYTHON if lib == "rospy" else venv_python()
    done = subprocess.run([python, str(BENCH / "log_peer.py"), lib, str(n)], env=env, timeout=300,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    fields = dict(re.findall(r"(\w+)=([\d.]+)", done.stderr))
    if "enabled_per_s" not in fields:
        raise RuntimeError(f"{lib} log peer failed: {done.stderr[-2000:]}")
    return {k: float(v) for k, v in fields.items()}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-n", type=int, default=20000, help="enabled calls per library (disabled: 10x)")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    port = free_port()
    home = tempfile.mkdtemp(prefix="rostui-bench-log-")
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1", ROS_HOME=home)
    core = subprocess.Popen([venv_python(), "-m", "rostui", "core", "-p", str(port)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    results: dict[str, list[dict[str, float]]] = {"rospy": [], "rostui": []}
    try:
        time.sleep(2.0)
        for i in range(args.rounds):
            for lib in (("rospy", "rostui") if i % 2 == 0 else ("rostui", "rospy")):
                row = run_peer(lib, args.n, env)
                results[lib].append(row)
                print(f"round {i + 1} {lib:<7} enabled {row['enabled_per_s']:>10,.0f}/s"
                      f"   disabled {row['disabled_ns']:>7,.1f} ns/call", flush=True)
    finally:
        core.send_signal(2)
        core.wait(timeout=10)
    med = {lib: {k: sorted(r[k] for r in rows)[len(rows) // 2] for k in rows[0]} for lib, rows in results.items()}
    print(f"\nmedian of {args.rounds} rounds, {args.n} enabled and {args.n * 10} disabled calls per round")
    for lib, row in med.items():
        print(f"{lib:<8} enabled {row['enabled_per_s']:>10,.0f} calls/s   disabled {row['disabled_ns']:>7,.1f} ns/call")
    ours, theirs = med["rostui"], med["rospy"]
    print(f"rostui/rospy enabled throughput {ours['enabled_per_s'] / theirs['enabled_per_s']:.2f}x,"
          f" disabled cost {ours['disabled_ns'] / theirs['disabled_ns']:.2f}x")
    ok = ours["disabled_ns"] < 1000
    print(f"target disabled call < 1 µs: {ours['disabled_ns']:.1f} ns  {'met' if ok else 'MISSED'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
