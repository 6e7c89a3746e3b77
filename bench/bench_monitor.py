#!/usr/bin/env python3
"""`rostui monitor` on 200 topics at 100 Hz each: keypress-to-repaint latency and the monitor's CPU.

Publisher processes (this script in ``publish`` mode; default 4 processes x
50 topics of std_msgs/String, 64 characters) publish every topic at 100 Hz on
the CPUs other than CPU 0; the master runs there too.  The real `rostui
monitor` command runs in a 120x40 pseudo-terminal pinned to CPU 0, so it
subscribes to the ~37 topics whose rows fit on screen (its rule: only what
is shown).  The script presses keys and times each one from the write to the
first bytes on the terminal that show its effect:

- ``s`` (sort by the next column: the table is re-sorted and redrawn) until
  the status line says ``sort <column>``; ``S`` (reverse) until the arrow flips;
- ``/`` until the filter line says how it works, then ``t``, ``1``, ``9``
  until the status line shows the filter ``'t19'``, then ctrl+u (the line
  emptied) until every topic is shown again; Enter leaves the line (not
  timed; Escape is not timed either: a lone Escape waits out the terminal's
  escape-sequence delay, 100 ms in any Textual app);
- Enter on the cursor row until its message tree's heading appears (Enter
  again collapses it).

The monitor's CPU (psutil) is measured over the key phase and over a quiet
phase with no keys.  In the same run, with the same publishers, the peer
tools measure the same topics the monitor subscribed to (read from the
master): real ``rostopic hz`` (rospy) and ``rostui topic hz``, each pinned
to CPU 0 for the quiet phase's length; the ratios say what the monitor costs
next to the one-topic tools it replaces.  The same keys are also timed with
no publishers first, so the table shows what the load adds.  The load
average is printed: the machine is shared.

    .venv/bin/python bench/bench_monitor.py
    .venv/bin/python bench/bench_monitor.py --topics 200 --rate 100 --procs 4 --seconds 30 --json out.json
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import xmlrpc.client
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import psutil

from _common import APP_CPU, REPO, RecordingPty, free_port, other_cpus, ros_env, wait_port

COLS, ROWS = 120, 40
PAYLOAD = "x" * 64
SORTS = ("type", "pubs", "subs", "rate", "bandwidth", "age", "live", "topic")


# -- publish mode (a separate process) --------------------------------------------------------
async def publish(first: int, count: int, rate: float) -> None:
    """Publish ``/bench/tNNN`` for NNN in [first, first+count) at ``rate`` Hz until SIGINT; print what was sent."""
    from rostui.core.msg import get_message_class
    from rostui.core.node import AsyncNode

    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    node = await AsyncNode("bench_monitor_pub", anonymous=True, argv=[]).start(publish_rosout=False)
    string = get_message_class("std_msgs/String")
    pubs = [await node.advertise(f"/bench/t{i:03d}", string, queue_size=10) for i in range(first, first + count)]
    msg = string(data=PAYLOAD)
    print("advertised", flush=True)
    period = 1.0 / rate
    due = start = loop.time()
    rounds = 0
    while not stop.is_set():
        for pub in pubs:
            pub.publish(msg)
        rounds += 1
        due += period
        delay = due - loop.time()
        if delay < -1.0:  # fell far behind: do not burst to catch up
            due = loop.time()
            delay = 0.0
        if delay > 0:
            try:
                await asyncio.wait_for(stop.wait(), delay)
            except asyncio.TimeoutError:
                pass
    took = loop.time() - start
    print(f"rounds={rounds} seconds={took:.3f} rate={rounds / took:.2f}", flush=True)
    await node.shutdown("done")


# -- the terminal --------------------------------------------------------------------------------
class Terminal(RecordingPty):
    """`rostui monitor` on a pty; every byte it writes is kept."""

    def wait_for(self, pattern: bytes, timeout: float = 60.0) -> re.Match[bytes]:
        """Block until ``pattern`` (a regex) matches the output; return the last match."""
        deadline = time.monotonic() + timeout
        while True:
            matches = list(re.finditer(pattern, self.since(max(0, self.size - 400_000))))
            if matches:
                return matches[-1]
            if time.monotonic() > deadline or (self.proc and self.proc.poll() is not None):
                tail = self.since(max(0, self.size - 2000)).decode(errors="replace")
                raise SystemExit(f"the monitor never showed {pattern!r}; last output:\n{tail}")
            time.sleep(0.05)


@dataclass
class KeyTimes:
    """Key-to-screen times (ms) by key and keys that never showed their effect."""

    latencies: dict[str, list[float]] = field(default_factory=dict)
    misses: dict[str, int] = field(default_factory=dict)

    def add(self, name: str, took: float | None) -> None:
        """Record one press."""
        if took is None:
            self.misses[name] = self.misses.get(name, 0) + 1
        else:
            self.latencies.setdefault(name, []).append(took * 1000)

    def summary(self) -> dict[str, dict[str, float]]:
        """p50, p95 and max per key."""
        return {k: {"n": len(v), "p50": statistics.median(v), "p95": percentile(v, 95), "max": max(v)}
                for k, v in self.latencies.items()}

    def all_values(self) -> list[float]:
        """Every time measured, in ms."""
        return [x for v in self.latencies.values() for x in v]


def percentile(values: list[float], pct: float) -> float:
    """The ``pct`` percentile (nearest rank)."""
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, round(pct / 100 * len(ordered)) - 1))]


def press_keys(term: Terminal, seconds: float, total: int, expanded: bytes) -> KeyTimes:
    """Play the key cycle for ``seconds``.

    ``total`` is the number of topics (shown again after Escape); ``expanded``
    is the heading of the first row's message tree.
    """
    times = KeyTimes()
    start = time.monotonic()
    reverse = False
    pause = 0.3
    while time.monotonic() - start < seconds:
        for column in SORTS:
            times.add("s sort", term.press(b"s", f"sort {column} ".encode()))
            time.sleep(pause)
        reverse = not reverse
        times.add("S reverse", term.press(b"S", ("sort topic ↑" if reverse else "sort topic ↓").encode()))
        time.sleep(pause)
        times.add("/ open filter", term.press(b"/", b"Enter keeps, Esc clears"))
        time.sleep(pause)
        typed = ""
        for char in "t19":
            typed += char
            times.add("type filter", term.press(char.encode(), f"filter '{typed}'".encode()))
            time.sleep(pause)
        times.add("ctrl+u clear filter", term.press(b"\x15", f"{total} shown".encode()))
        time.sleep(pause)
        term.press(b"\r", b"/ filter")  # Enter gives the keyboard back to the table (not timed)
        time.sleep(pause)
        times.add("Enter expand", term.press(b"\r", expanded))
        time.sleep(pause)
        term.press(b"\r", b"\x1b")  # collapse again (not timed: nothing new to look for)
        time.sleep(pause)
    return times


class CpuMeter:
    """CPU seconds a process used between :meth:`start` and :meth:`stop`, as a fraction of one core."""

    def __init__(self, pid: int) -> None:
        self.proc = psutil.Process(pid)
        self.t0 = 0.0
        self.c0 = 0.0

    def _cpu(self) -> float:
        times = self.proc.cpu_times()
        return times.user + times.system + times.children_user + times.children_system

    def start(self) -> None:
        """Begin a window."""
        self.t0, self.c0 = time.monotonic(), self._cpu()

    def stop(self) -> float:
        """Cores used on average since :meth:`start`."""
        return (self._cpu() - self.c0) / (time.monotonic() - self.t0)


def subscribed_topics(master_uri: str) -> list[str]:
    """Topics the monitor's node subscribes to, as the master lists them."""
    code, _, (_, subs, _) = xmlrpc.client.ServerProxy(master_uri).getSystemState("/bench")
    return sorted(t for t, nodes in subs if any(n.startswith("/rostui_monitor") for n in nodes))


def peer_cpu(argv: list[str], env: dict[str, str], seconds: float) -> float | None:
    """Cores a peer tool uses on average over ``seconds`` (after 3 s to connect), pinned to the app's CPU."""
    try:
        proc = subprocess.Popen(argv, env=env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                start_new_session=True, preexec_fn=lambda: os.sched_setaffinity(0, {APP_CPU}))
    except OSError:
        return None
    try:
        time.sleep(3.0)
        if proc.poll() is not None:
            return None
        meter = CpuMeter(proc.pid)
        meter.start()
        time.sleep(seconds)
        return meter.stop()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGINT)
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()


def start_monitor(env: dict[str, str]) -> Terminal:
    """The real `rostui monitor` on a pty pinned to CPU 0."""
    term = Terminal([sys.executable, "-m", "rostui", "monitor", "--period", "1"], env, COLS, ROWS, pin={APP_CPU})
    term.start()
    return term


def topic_total(term: Terminal, at_least: int) -> int:
    """Wait until the status line counts at least ``at_least`` topics; return the count."""
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        found = term.wait_for(rb"(\d+) topics")
        if int(found[1]) >= at_least:
            return int(found[1])
        time.sleep(0.2)
    raise SystemExit(f"the monitor never counted {at_least} topics")


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Baseline with no publishers, then the publishers, the monitor with keys, the quiet phase and the peers."""
    port = free_port()
    home = tempfile.mkdtemp(prefix="bench_monitor_")
    env = ros_env(port, home, TERM="xterm-256color", COLORTERM="truecolor", PYTHONUNBUFFERED="1")
    env.pop("NO_COLOR", None)
    master_uri = env["ROS_MASTER_URI"]
    rest = other_cpus()
    pin_rest = lambda: os.sched_setaffinity(0, rest)  # noqa: E731
    load = [os.getloadavg()[0]]
    if args.master == "roscore":
        master_argv = ["roscore", "-p", str(port)]
    else:
        master_argv = [sys.executable, "-m", "rostui", "core", "-p", str(port)]
    master = subprocess.Popen(master_argv, env=env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              start_new_session=True, preexec_fn=pin_rest)
    publishers: list[subprocess.Popen] = []
    result: dict[str, Any] = {"master": args.master, "topics": args.topics, "rate": args.rate, "procs": args.procs,
                              "seconds": args.seconds}
    try:
        wait_port(port)
        time.sleep(1.0)
        term = start_monitor(env)
        try:
            quiet_total = topic_total(term, 1)
            time.sleep(1.0)
            result["baseline"] = press_keys(term, args.baseline_seconds, quiet_total, b"/rosout [rosgraph_msgs/Log]")
        finally:
            term.quit()
        per = -(-args.topics // args.procs)
        for first in range(0, args.topics, per):
            count = min(per, args.topics - first)
            proc = subprocess.Popen([sys.executable, __file__, "publish", str(first), str(count), str(args.rate)],
                                    env=env, cwd=REPO, stdout=subprocess.PIPE, text=True, preexec_fn=pin_rest)
            publishers.append(proc)
        for proc in publishers:
            assert proc.stdout is not None
            if proc.stdout.readline().strip() != "advertised":
                raise SystemExit("a publisher never advertised its topics")
        term = start_monitor(env)
        try:
            total = topic_total(term, args.topics)
            time.sleep(3.0)  # subscriptions to the rows on screen settle
            meter = CpuMeter(term.proc.pid)  # type: ignore[union-attr]
            meter.start()
            result["loaded"] = press_keys(term, args.seconds, total, b" [std_msgs/String]")
            result["cpu_keys"] = meter.stop()
            time.sleep(1.0)
            shown = subscribed_topics(master_uri)
            meter.start()
            time.sleep(args.quiet_seconds)
            result["cpu_quiet"] = meter.stop()
        finally:
            result["exit_code"] = term.quit()
        result["subscribed"] = len(shown)
        bench_topics = [t for t in shown if t.startswith("/bench/")]
        ros_python = shutil.which("rostopic")
        result["peer_rostopic"] = peer_cpu(["rostopic", "hz", *bench_topics], env, args.quiet_seconds) \
            if ros_python else None
        result["peer_rostui_hz"] = peer_cpu([sys.executable, "-m", "rostui", "topic", "hz", *bench_topics], env,
                                            args.quiet_seconds)
    finally:
        for proc in publishers:
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
        sent = []
        for proc in publishers:
            try:
                out, _ = proc.communicate(timeout=15)
                found = re.search(r"rate=([\d.]+)", out or "")
                if found:
                    sent.append(float(found[1]))
            except subprocess.TimeoutExpired:
                proc.kill()
        result["publisher_rates"] = sent
        master.send_signal(signal.SIGINT)
        try:
            master.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(master.pid, signal.SIGKILL)
        shutil.rmtree(home, ignore_errors=True)
    load.append(os.getloadavg()[0])
    result["load_average"] = [round(x, 2) for x in load]
    return result


def report(result: dict[str, Any]) -> dict[str, Any]:
    """Print the measurements as Markdown; return them as plain data (for --json)."""
    loaded: KeyTimes = result["loaded"]
    quiet: KeyTimes = result["baseline"]
    rates = result["publisher_rates"]
    print(f"master {result['master']}; {result['topics']} topics at {result['rate']:g} Hz in {result['procs']} "
          f"publisher processes (achieved {min(rates, default=0):.1f}-{max(rates, default=0):.1f} rounds/s); "
          f"load average {result['load_average'][0]} before, {result['load_average'][1]} after")
    print(f"the monitor subscribed to {result['subscribed']} topics (the rows on screen); "
          f"exit status {result['exit_code']}")
    print()
    print("| key | samples | no publishers p50 ms | no publishers p95 ms | loaded p50 ms | loaded p95 ms | loaded max ms |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    base = quiet.summary()
    for name, row in loaded.summary().items():
        b = base.get(name)
        b_text = f"{b['p50']:.0f} | {b['p95']:.0f}" if b else "- | -"
        print(f"| {name} | {row['n']} | {b_text} | {row['p50']:.0f} | {row['p95']:.0f} | {row['max']:.0f} |")
    values = loaded.all_values()
    print(f"| all keys | {len(values)} | {statistics.median(quiet.all_values()):.0f} | "
          f"{percentile(quiet.all_values(), 95):.0f} | {statistics.median(values):.0f} | "
          f"{percentile(values, 95):.0f} | {max(values):.0f} |")
    for label, misses in (("loaded", loaded.misses), ("no publishers", quiet.misses)):
        if misses:
            print(f"\nno repaint within 5 s ({label}): {misses}")
    print()
    print("| process (same topics, CPU 0) | cores | monitor / it |")
    print("| --- | --- | --- |")
    print(f"| rostui monitor, keys pressed | {result['cpu_keys']:.2f} | |")
    print(f"| rostui monitor, no keys | {result['cpu_quiet']:.2f} | 1.00 |")
    for label, key in (("rostopic hz (rospy)", "peer_rostopic"), ("rostui topic hz", "peer_rostui_hz")):
        value = result[key]
        ratio = f"{result['cpu_quiet'] / value:.2f}" if value else "-"
        print(f"| {label} | {value:.2f} | {ratio} |" if value is not None else f"| {label} | not run | - |")
    worst = percentile(values, 95)
    verdict = "meets" if worst < 100 and not loaded.misses and result["cpu_keys"] < 1.0 else "misses"
    print(f"\nall-keys p95 {worst:.0f} ms, CPU {result['cpu_keys']:.2f} cores with keys: {verdict} the targets "
          f"(< 100 ms, < 1 core)")
    plain = dict(result)
    plain["loaded"] = {"latency_ms": loaded.summary(), "misses": loaded.misses}
    plain["baseline"] = {"latency_ms": quiet.summary(), "misses": quiet.misses}
    return plain


def main() -> int:
    """Parse arguments; run the publish mode or the benchmark."""
    if len(sys.argv) > 1 and sys.argv[1] == "publish":
        asyncio.run(publish(int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--master", choices=["roscore", "rostui"], default="rostui")
    parser.add_argument("--topics", type=int, default=200)
    parser.add_argument("--rate", type=float, default=100.0)
    parser.add_argument("--procs", type=int, default=4)
    parser.add_argument("--seconds", type=float, default=30, help="seconds of keys under load")
    parser.add_argument("--quiet-seconds", type=float, default=10, help="seconds of CPU measurement without keys")
    parser.add_argument("--baseline-seconds", type=float, default=10, help="seconds of keys with no publishers")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    plain = report(run(args))
    if args.json:
        args.json.write_text(json.dumps(plain, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
