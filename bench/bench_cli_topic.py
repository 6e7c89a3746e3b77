"""Benchmark: `rostui topic` against real `rostopic`, same master, same run.

1. Startup: wall time of ``rostui topic list`` vs ``rostopic list`` (median of
   N interleaved runs each) against one ``rostui core``; target <= 0.5x.
2. hz accuracy at 20 kHz: a rostui AsyncNode publisher (a subprocess) paces
   std_msgs/String messages at 20 kHz and counts exactly what it sent;
   ``rostopic hz`` and ``rostui topic hz`` read it at the same time.  Prints the
   true rate and the median rate each tool reported; target: rostui within 1%.

    .venv/bin/python bench/bench_cli_topic.py [--runs 10] [--rate 20000] [--seconds 10]

Not a test.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import re
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

RATE_LINE = re.compile(r"average rate: (\d+\.\d+)")


def free_port() -> int:
    """A free TCP port on 127.0.0.1."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_port(port: int, timeout: float = 20.0) -> None:
    """Block until something listens on 127.0.0.1:port."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=0.5):
                return
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.05)


# ----------------------------------------------------------------------------- publisher subprocess
async def _publish(topic: str, rate: float, seconds: float, subscribers: int) -> None:
    from rostui.core.msg import get_message_class
    from rostui.core.node import AsyncNode

    String = get_message_class("std_msgs/String")
    node = await AsyncNode("bench_fast_pub", anonymous=True, argv=[]).start(announce=False)
    pub = await node.advertise(topic, String, queue_size=100000)
    print("advertised", flush=True)
    while pub.get_num_connections() < subscribers:
        await asyncio.sleep(0.05)
    await asyncio.sleep(1.0)  # let every subscriber finish connecting
    msg = String(data="x" * 16)
    loop = asyncio.get_running_loop()
    start = loop.time()
    sent = 0
    end = start + seconds
    while True:
        now = loop.time()
        if now >= end:
            break
        due = int((now - start) * rate)
        while sent < due:
            pub.publish(msg)
            sent += 1
        await asyncio.sleep(0.0005)
    elapsed = loop.time() - start
    print(f"sent {sent} in {elapsed:.4f} s", flush=True)
    await asyncio.sleep(1.0)
    await node.shutdown()


def publisher_main(argv: list[str]) -> None:
    """``--publisher TOPIC RATE SECONDS SUBSCRIBERS``: the paced publisher process."""
    import uvloop

    topic, rate, seconds, subs = argv[0], float(argv[1]), float(argv[2]), int(argv[3])
    uvloop.run(_publish(topic, rate, seconds, subs))


# ----------------------------------------------------------------------------- helpers
class Reader:
    """Collect a subprocess's stdout lines on a thread."""

    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        self.proc = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, text=True, start_new_session=True)
        self.lines: list[str] = []
        self._t = threading.Thread(target=self._read, daemon=True)
        self._t.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))

    def wait_line(self, pattern: str, timeout: float = 30.0) -> str:
        deadline = time.monotonic() + timeout
        rx = re.compile(pattern)
        while time.monotonic() < deadline:
            for line in list(self.lines):
                if rx.search(line):
                    return line
            if self.proc.poll() is not None and not self._t.is_alive():
                break
            time.sleep(0.05)
        raise RuntimeError(f"no line matching {pattern!r}: {self.lines[-20:]}")

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(2)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._t.join(5)


def time_cmd(argv: list[str], env: dict[str, str]) -> float:
    t0 = time.perf_counter()
    r = subprocess.run(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        raise RuntimeError(f"{argv} failed: {r.stderr.decode()}")
    return dt


def bench_list(env: dict[str, str], runs: int) -> tuple[float, float]:
    ours_argv = [sys.executable, "-m", "rostui", "topic", "list"]
    real_argv = ["rostopic", "list"]
    time_cmd(ours_argv, env), time_cmd(real_argv, env)  # warm the page cache
    ours, real = [], []
    for _ in range(runs):
        ours.append(time_cmd(ours_argv, env))
        real.append(time_cmd(real_argv, env))
    return statistics.median(ours), statistics.median(real)


def bench_hz(env: dict[str, str], rate: float, seconds: float) -> tuple[float, list[float], list[float]]:
    topic = "/bench_fast"
    pub = Reader([sys.executable, __file__, "--publisher", topic, str(rate), str(seconds), "2"], env)
    readers: list[Reader] = []
    try:
        pub.wait_line("advertised")
        real = Reader(["rostopic", "hz", topic], env)
        ours = Reader([sys.executable, "-m", "rostui", "topic", "hz", topic], env)
        readers = [real, ours]
        line = pub.wait_line(r"^sent \d+", timeout=seconds + 60)
        m = re.match(r"sent (\d+) in ([\d.]+) s", line)
        assert m
        true_rate = int(m.group(1)) / float(m.group(2))
        time.sleep(0.5)
    finally:
        for r in readers:
            r.stop()
        pub.stop()

    def rates(r: Reader) -> list[float]:
        vals = [float(m.group(1)) for m in map(RATE_LINE.search, r.lines) if m]
        # skip the first reports (connection set-up) and the tail after the publisher stopped
        return vals[2:max(2, int(seconds) - 1)] or vals

    return true_rate, rates(real), rates(ours)


def main() -> int:
    if len(sys.argv) > 1 and sys.argv[1] == "--publisher":
        publisher_main(sys.argv[2:])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10, help="runs of each `list` (median)")
    ap.add_argument("--rate", type=float, default=20000.0, help="publisher rate for the hz test (Hz)")
    ap.add_argument("--seconds", type=float, default=10.0, help="how long the fast publisher runs")
    args = ap.parse_args()
    if shutil.which("rostopic") is None:
        print("rostopic (Debian ros-core) is not installed", file=sys.stderr)
        return 1

    port = free_port()
    home = tempfile.mkdtemp(prefix="bench_topic_")
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_IP="127.0.0.1", ROS_HOME=home,
               PYTHONUNBUFFERED="1")
    env.pop("ROS_HOSTNAME", None)
    env.pop("ROS_NAMESPACE", None)
    core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        wait_port(port)
        time.sleep(1.0)
        ours, real = bench_list(env, args.runs)
        print(f"topic list wall time (median of {args.runs}): rostui {ours * 1000:.1f} ms, "
              f"rostopic {real * 1000:.1f} ms, ratio {ours / real:.2f}x (target <= 0.50x) "
              f"{'OK' if ours <= 0.5 * real else 'MISSED'}")
        true_rate, real_rates, our_rates = bench_hz(env, args.rate, args.seconds)
        r_med = statistics.median(real_rates) if real_rates else float("nan")
        o_med = statistics.median(our_rates) if our_rates else float("nan")
        print(f"hz at {args.rate:.0f} Hz: true rate {true_rate:.1f} Hz")
        print(f"  rostopic hz     reported {r_med:10.1f} Hz (median of {len(real_rates)}), "
              f"error {100 * (r_med - true_rate) / true_rate:+.2f}%  reports: {real_rates}")
        print(f"  rostui topic hz reported {o_med:10.1f} Hz (median of {len(our_rates)}), "
              f"error {100 * (o_med - true_rate) / true_rate:+.2f}%  reports: {our_rates}")
        ok = abs(o_med - true_rate) <= 0.01 * true_rate
        print(f"  rostui within 1%: {'OK' if ok else 'MISSED'}")
    finally:
        core.send_signal(2)
        try:
            core.wait(10)
        except subprocess.TimeoutExpired:
            core.kill()
        shutil.rmtree(home, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
