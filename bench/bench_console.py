#!/usr/bin/env python3
"""`rostui console` under a log flood: keypress-to-repaint latency, ingest rate, memory.

A flood publisher (this script in ``flood`` mode, a separate process on the
other CPU) publishes rosgraph_msgs/Log on /rosout at a fixed rate (default
10 000 messages/s for 30 s: 60 % DEBUG, 30 % INFO, 8 % WARN, 2 % ERROR);
the master's rosout relays them to /rosout_agg.  The real `rostui console`
command runs in a 120x40 pseudo-terminal pinned to CPU 0.  While the flood
runs, this script presses keys in the terminal and times each one from the
write to the first bytes on the terminal that show its effect:

- ``1`` (hide DEBUG: the rows are filtered again, up to --max messages) until
  the status line's "shown" count falls below 70 % of "kept"; ``1`` again
  until they are equal;
- ``/`` until the search prompt's title appears (Enter closes it);
- ``p`` until "PAUSED" appears, ``p`` again until "resumed:" does;
- ``Up`` until "SCROLL" appears, ``End`` until "FOLLOW" is back.

Once a second it samples the app's resident memory and CPU time; at the end
it reads the app's own counters from its status line (shown, kept, dropped).
Before the flood, the same keys are timed with no flood (the console on a
rosout.log of --max messages, same CPU), so the two columns of the table show
what the flood adds on the machine as loaded at that moment; the load average
is printed too.

There is no peer to compare with: rqt_console needs a Qt window.  The target
(issue 6) is keypress-to-repaint under 100 ms with bounded memory.

    .venv/bin/python bench/bench_console.py                     # real roscore if installed, 30 s
    .venv/bin/python bench/bench_console.py --master rostui --rate 10000 --seconds 30 --json out.json
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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from _common import APP_CPU, REPO, RecordingPty, free_port, other_cpus, ros_env, wait_port

COLS, ROWS = 120, 40
LEVEL_MIX = [1] * 60 + [2] * 30 + [4] * 8 + [8] * 2
STATUS = re.compile(rb"([\d,]+) shown / ([\d,]+) kept(?:[^\n]*?([\d,]+) dropped)?")


# -- flood mode (a separate process) -----------------------------------------------------------
async def flood(rate: float, seconds: float) -> None:
    """Publish ``rate`` Log messages per second on /rosout for ``seconds``, in 10 ms batches."""
    from rostui.core.msg import get_message_class
    from rostui.core.node.node import AsyncNode
    from rostui.core.rostime import Time

    node = AsyncNode("console_flood")
    node.log.console = None
    await node.start(publish_rosout=False)
    log_class = get_message_class("rosgraph_msgs/Log")
    pub = await node.advertise("/rosout", log_class, queue_size=100_000)
    loop = asyncio.get_running_loop()
    deadline = loop.time() + 30
    while pub.get_num_connections() == 0 and loop.time() < deadline:
        await asyncio.sleep(0.05)
    print("connected", flush=True)
    tick, sent = 0.01, 0
    start = loop.time()
    while loop.time() - start < seconds:
        due = int((loop.time() - start) * rate)
        while sent < due:
            msg = log_class()
            now = time.time_ns()
            msg.header.stamp = Time(now // 1_000_000_000, now % 1_000_000_000)
            msg.level = LEVEL_MIX[sent % len(LEVEL_MIX)]
            msg.name = "/console_flood"
            msg.msg = f"flood message {sent}: motor {sent % 4} current {sent % 97 / 10:.1f} A"
            msg.file, msg.function, msg.line = "bench_console.py", "flood", 90
            msg.topics = ["/rosout"]
            pub.publish(msg)
            sent += 1
        await asyncio.sleep(tick)
    elapsed = loop.time() - start
    print(f"sent={sent} seconds={elapsed:.2f}", flush=True)
    await asyncio.sleep(1.0)
    await node.shutdown("flood done")


# -- the pseudo-terminal -----------------------------------------------------------------------
class Terminal(RecordingPty):
    """`rostui console` on a pty; every byte it writes is kept."""

    def wait_for(self, marker: bytes, timeout: float = 30.0) -> None:
        """Block until ``marker`` appears anywhere in the output."""
        deadline = time.monotonic() + timeout
        while marker not in self.since(0):
            if time.monotonic() > deadline or (self.proc and self.proc.poll() is not None):
                tail = self.since(max(0, self.size - 2000)).decode(errors="replace")
                raise SystemExit(f"the console never showed {marker!r}; last output:\n{tail}")
            time.sleep(0.05)


def last_status(output: bytes) -> tuple[int, int, int] | None:
    """(shown, kept, dropped) from the last status line in ``output``."""
    found = None
    for match in STATUS.finditer(output):
        found = match
    if found is None:
        return None
    number = lambda b: int(b.replace(b",", b"")) if b else 0  # noqa: E731
    return number(found[1]), number(found[2]), number(found[3])


def filtered(output: bytes) -> bool:
    """The output shows a status line with fewer than 70 % of the kept messages shown."""
    status = last_status(output)
    return status is not None and status[1] > 1000 and status[0] < 0.7 * status[1]


def unfiltered(output: bytes) -> bool:
    """The output shows a status line with every kept message shown."""
    status = last_status(output)
    return status is not None and status[1] > 1000 and status[0] == status[1]


def proc_sample(pid: int) -> tuple[float, float]:
    """(resident MB, CPU seconds) of a process."""
    rss = 0.0
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            rss = int(line.split()[1]) / 1024
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return rss, (int(fields[11]) + int(fields[12])) / ticks


# -- the run ------------------------------------------------------------------------------------
@dataclass
class KeyTimes:
    """Key-to-screen times (ms) by key, keys that never showed their effect, and memory/CPU samples."""

    latencies: dict[str, list[float]] = field(default_factory=dict)
    misses: dict[str, int] = field(default_factory=dict)
    samples: list[tuple[float, float, float]] = field(default_factory=list)

    def summary(self) -> dict[str, dict[str, float]]:
        """p50, p95 and max per key."""
        return {k: {"n": len(v), "p50": statistics.median(v), "p95": percentile(v, 95), "max": max(v)}
                for k, v in self.latencies.items()}


def press_keys(console: Terminal, seconds: float, times: KeyTimes) -> None:
    """Play the key cycle for ``seconds``, sampling the app's memory and CPU once a second."""
    assert console.proc is not None
    start = next_sample = time.monotonic()

    def sample() -> None:
        nonlocal next_sample
        while time.monotonic() >= next_sample:
            times.samples.append((time.monotonic() - start, *proc_sample(console.proc.pid)))
            next_sample += 1.0

    def measure(name: str, key: bytes, done: Callable[[bytes], bool]) -> None:
        sample()
        took = console.press(key, done)
        if took is None:
            times.misses[name] = times.misses.get(name, 0) + 1
        else:
            times.latencies.setdefault(name, []).append(took * 1000)
        time.sleep(0.4)
        sample()

    time.sleep(2.0)
    last_resume = 0.0
    while time.monotonic() - start < seconds - 2:
        measure("1 hide DEBUG (refilter)", b"1", filtered)
        measure("1 show DEBUG (refilter)", b"1", unfiltered)
        measure("/ open search", b"/", lambda out: b"search (text)" in out)
        console.press(b"\r", lambda out: True)  # Enter closes it (Escape then Up could read as Alt+Up)
        time.sleep(0.4)
        measure("Up leave follow", b"\x1b[A", lambda out: b"SCROLL" in out)
        measure("End follow", b"\x1b[F", lambda out: b"FOLLOW" in out)
        if time.monotonic() - last_resume > 5.0:  # the "resumed:" notice from the last one is gone
            measure("p pause", b"p", lambda out: b"PAUSED" in out)
            measure("p resume", b"p", lambda out: b"resumed:" in out)
            last_resume = time.monotonic()
    while time.monotonic() - start < seconds:
        time.sleep(0.2)
        sample()


def write_log(path: Path, count: int) -> None:
    """A rosout.log of ``count`` messages with the flood's level mix (the no-flood baseline opens it)."""
    from rostui.core.log import RosoutLogWriter

    writer = RosoutLogWriter(path, clock=lambda: 1_700_000_000 * 10**9)
    for n in range(count):
        writer.write(1_700_000_000 + n // 1000, (n % 1000) * 10**6, LEVEL_MIX[n % len(LEVEL_MIX)], "/console_flood",
                     "bench_console.py", 90, "flood", ["/rosout"],
                     f"flood message {n}: motor {n % 4} current {n % 97 / 10:.1f} A")
    writer.close()


def baseline(args: argparse.Namespace, env: dict[str, str], home: str) -> KeyTimes:
    """The same keys with no flood: the console on a file of --max messages."""
    path = Path(home) / "baseline_rosout.log"
    write_log(path, args.max)
    console = Terminal([sys.executable, "-m", "rostui", "console", "--max", str(args.max), str(path)], env,
                       COLS, ROWS, pin={APP_CPU})
    times = KeyTimes()
    try:
        console.start()
        console.wait_for(b"FOLLOW")
        press_keys(console, args.baseline_seconds, times)
    finally:
        console.quit()
    return times


def run(args: argparse.Namespace) -> dict[str, Any]:
    """The no-flood baseline, then master, console and flood with the same keys; the measurements."""
    port = free_port()
    home = tempfile.mkdtemp(prefix="bench_console_")
    env = ros_env(port, home, TERM="xterm-256color", COLORTERM="truecolor", PYTHONUNBUFFERED="1")
    env.pop("NO_COLOR", None)
    load_before = os.getloadavg()[0]
    quiet = baseline(args, env, home) if args.baseline_seconds > 0 else KeyTimes()
    rest = other_cpus()
    pin_rest = lambda: os.sched_setaffinity(0, rest)  # noqa: E731
    if args.master == "roscore":
        master_argv = ["roscore", "-p", str(port)]
    else:
        master_argv = [sys.executable, "-m", "rostui", "core", "-p", str(port)]
    master = subprocess.Popen(master_argv, env=env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              start_new_session=True, preexec_fn=pin_rest)
    console = Terminal([sys.executable, "-m", "rostui", "console", "--max", str(args.max)], env, COLS, ROWS,
                       pin={APP_CPU})
    flooder: subprocess.Popen | None = None
    times = KeyTimes()
    try:
        wait_port(port)
        console.start()
        console.wait_for(b"FOLLOW")
        console.wait_for(f"master http://127.0.0.1:{port}".encode())
        time.sleep(1.0)  # rosout's /rosout_agg connection to the console
        flooder = subprocess.Popen([sys.executable, __file__, "flood", str(args.rate), str(args.seconds)], env=env,
                                   cwd=REPO, stdout=subprocess.PIPE, text=True, preexec_fn=pin_rest)
        assert flooder.stdout is not None
        if flooder.stdout.readline().strip() != "connected":
            raise SystemExit("the flood publisher never connected to rosout")
        press_keys(console, args.seconds, times)
        flood_out, _ = flooder.communicate(timeout=60)
        time.sleep(1.5)
        final = last_status(console.since(max(0, console.size - 200_000)))
    finally:
        if flooder is not None and flooder.poll() is None:
            flooder.kill()
        code = console.quit() if console.proc is not None else None
        master.send_signal(signal.SIGINT)
        try:
            master.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(master.pid, signal.SIGKILL)
        shutil.rmtree(home, ignore_errors=True)
    sent = int(re.search(r"sent=(\d+)", flood_out)[1])  # type: ignore[index]
    shown, kept, dropped = final or (0, 0, 0)
    by_second = {round(t): rss for t, rss, _ in times.samples}
    first, last = times.samples[0], times.samples[-1]
    return {
        "master": args.master, "rate": args.rate, "seconds": args.seconds, "max": args.max,
        "load_average": [round(load_before, 2), round(os.getloadavg()[0], 2)],
        "sent": sent, "received": kept + dropped, "kept": kept, "dropped": dropped,
        "latency_ms": times.summary(), "misses": times.misses,
        "baseline_latency_ms": quiet.summary(), "baseline_misses": quiet.misses,
        "rss_mb": {t: round(by_second[t], 1) for t in sorted(by_second) if t % 5 == 0},
        "rss_max_mb": max(r for _, r, _ in times.samples),
        "cpu_percent": 100 * (last[2] - first[2]) / (last[0] - first[0]),
        "exit_code": code,
    }


def percentile(values: list[float], pct: float) -> float:
    """The ``pct`` percentile (nearest rank)."""
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, round(pct / 100 * len(ordered)) - 1))]


def report(result: dict[str, Any]) -> None:
    """Print the measurements as Markdown tables."""
    print(f"master {result['master']}, {result['rate']:,.0f} msg/s for {result['seconds']:g} s, "
          f"--max {result['max']:,}; load average {result['load_average'][0]} before, "
          f"{result['load_average'][1]} after")
    print(f"sent {result['sent']:,}, the console received {result['received']:,} "
          f"({100 * result['received'] / max(1, result['sent']):.1f} %), kept {result['kept']:,}, "
          f"dropped {result['dropped']:,}; app CPU {result['cpu_percent']:.0f} % of one core; "
          f"exit status {result['exit_code']}")
    print()
    quiet = result["baseline_latency_ms"]
    print("| key | samples | no flood p50 ms | no flood p95 ms | flood p50 ms | flood p95 ms | flood max ms |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name, row in result["latency_ms"].items():
        base = quiet.get(name)
        base_text = f"{base['p50']:.0f} | {base['p95']:.0f}" if base else "- | -"
        print(f"| {name} | {row['n']} | {base_text} | {row['p50']:.0f} | {row['p95']:.0f} | {row['max']:.0f} |")
    for label, misses in (("flood", result["misses"]), ("no flood", result["baseline_misses"])):
        if misses:
            print(f"\nno repaint within 5 s ({label}): {misses}")
    print()
    print("| s | " + " | ".join(str(t) for t in result["rss_mb"]) + " |")
    print("| --- | " + " | ".join("---" for _ in result["rss_mb"]) + " |")
    print("| RSS MB | " + " | ".join(str(v) for v in result["rss_mb"].values()) + " |")
    worst = max((row["p95"] for row in result["latency_ms"].values()), default=float("inf"))
    verdict = "meets" if worst < 100 and not result["misses"] else "misses"
    print(f"\nworst p95 under the flood {worst:.0f} ms: {verdict} the 100 ms target")


def main() -> int:
    """Parse arguments; run the flood mode or the benchmark."""
    if len(sys.argv) > 1 and sys.argv[1] == "flood":
        asyncio.run(flood(float(sys.argv[2]), float(sys.argv[3])))
        return 0
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--master", choices=["roscore", "rostui"],
                        default="roscore" if shutil.which("roscore") else "rostui")
    parser.add_argument("--rate", type=float, default=10_000)
    parser.add_argument("--seconds", type=float, default=30)
    parser.add_argument("--max", type=int, default=100_000)
    parser.add_argument("--baseline-seconds", type=float, default=20,
                        help="seconds of the same keys with no flood first (0: skip)")
    parser.add_argument("--json", type=Path)
    args = parser.parse_args()
    result = run(args)
    report(result)
    if args.json:
        args.json.write_text(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
