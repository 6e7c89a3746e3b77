#!/usr/bin/env python3
"""Pub/sub benchmark: rostui against rospy and roscpp, measured in the same run.

For each library, a publisher process and a subscriber process of that library
talk through one master (``rostui core`` for all three, so the master is the
same and only the node side differs):

* small throughput: std_msgs/String with a 16-byte payload, flooded as fast as
  the publisher can (queue 1000); messages/s *received* by the subscriber over
  a fixed window that starts at the first message;
* large throughput: the same with a 1 MB payload, in MB/s (10^6 bytes) received;
* latency: ping-pong round trips (N after a warm-up), p50 and p99 in µs, and
  the pinging process's CPU time per round trip (less sensitive to load from
  other work on the machine than wall-clock latency), and the echoing
  process's CPU time per message over the same timed round trips (the cost of
  one receive, callback and publish, the figure to set beside the floor's).

Peers: bench/roscpp_peer.cpp (built here into bench/_build/),
bench/py_peer.py rospy (system /usr/bin/python3) and bench/py_peer.py rostui (this
project's venv).  Everything runs on 127.0.0.1 with a private ROS_HOME and a
free port; every process is stopped at the end.  Not a test: it prints a table
and the ratios rostui/rospy and rostui/roscpp, and the targets.

    .venv/bin/python bench/bench_pubsub.py                 # 3 rounds, about 2 minutes
    .venv/bin/python bench/bench_pubsub.py --libs rostui,rospy --rounds 1
    .venv/bin/python bench/bench_pubsub.py --json out.json --window 5 --round-trips 3000
    git worktree add /tmp/before HEAD~1
    .venv/bin/python bench/bench_pubsub.py --only latency --load 2 --before /tmp/before \
        --libs rostui,rostui-before,rostui-nopoll,rospy,roscpp     # a change against its parent, and no spin
    .venv/bin/python bench/bench_pubsub.py --libs rostui,rospy --only latency --load 2 \
        --floors pong,pong-uvloop,pong-msg     # beside the floor: a uvloop echo, and one that decodes each message

Each round measures every library once (order rotated between rounds) and
the table shows the median per metric with its range, so a burst of load from
other work on the machine moves one round, not the result.
"""

from __future__ import annotations

import argparse
import json
import os
import queue
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client
from pathlib import Path
from typing import IO

BENCH = Path(__file__).resolve().parent
ROOT = BENCH.parent
BUILD = BENCH / "_build"
CPP_SRC = BENCH / "roscpp_peer.cpp"
CPP_BIN = BUILD / "roscpp_peer"
CPP_LIBS = ["-lroscpp", "-lrosconsole", "-lroscpp_serialization", "-lrostime", "-lxmlrpcpp",
            "-lcpp_common", "-lboost_system"]
SYSTEM_PYTHON = "/usr/bin/python3"
LIBS = ("rospy", "roscpp", "rostui")
NO_POLL = "rostui-nopoll"
"""An extra library for ``--libs``: rostui with its busy-poll off (``ROSTUI_BUSY_POLL_US=0``), to see what the spin
gives or costs in the same run."""
BEFORE = "rostui-before"
"""An extra library for ``--libs``: rostui as in the checkout ``--before`` names (``git worktree add DIR COMMIT``),
run by this venv's Python with that checkout first on its path."""
SMALL = 16
LARGE = 1_000_000

TARGETS = {  # metric: (rostui/rospy ratio wanted, higher is better)
    "small_msgs_s": (4.0, True),
    "large_MB_s": (1.5, True),
    "p50_us": (0.5, False),
}


def topic_prefix(lib: str) -> str:
    """The namespace of one library's bench topics (a ROS name: no ``-``)."""
    return "/bench/" + lib.replace("-", "_")


PEER_PYTHON: str | None = None
"""``--python``: the interpreter rostui's peers and the floor run on, when given."""


def venv_python() -> str:
    """The interpreter rostui's peers run on: ``--python``, else the project's venv, else the one running this
    script."""
    if PEER_PYTHON:
        return PEER_PYTHON
    candidate = ROOT / ".venv" / "bin" / "python"
    return str(candidate) if candidate.exists() else sys.executable


def build_cpp_peer() -> Path:
    """Compile bench/roscpp_peer.cpp unless the binary is newer than the source."""
    BUILD.mkdir(exist_ok=True)
    if CPP_BIN.exists() and CPP_BIN.stat().st_mtime >= CPP_SRC.stat().st_mtime:
        return CPP_BIN
    cmd = ["g++", "-O2", str(CPP_SRC), "-o", str(CPP_BIN), "-I/usr/include", *CPP_LIBS]
    print("building", CPP_BIN.relative_to(ROOT), "...", flush=True)
    subprocess.run(cmd, check=True, timeout=180)
    return CPP_BIN


def process_cpu_seconds(pid: int) -> float:
    """CPU time of a running process, its live threads' together, in nanoseconds' resolution
    (``/proc/PID/task/*/schedstat``; where that is missing, ``/proc/PID/stat`` in clock ticks)."""
    try:
        total = 0
        for task in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{task}/schedstat") as stat:
                total += int(stat.read().split()[0])
        return total / 1e9
    except (OSError, ValueError, IndexError):
        with open(f"/proc/{pid}/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def timed_echo(pinger: subprocess.Popen[str], ponger: subprocess.Popen[str], timeout: float) -> tuple[str, float | None]:
    """Read a ping's output to its end; return it and the echoing process's CPU seconds from the ping's
    ``timing`` line (its timed round trips start) to its last line (None when no ``timing`` line came)."""
    assert pinger.stdout is not None
    lines: queue.Queue[str | None] = queue.Queue()

    def read(stream: IO[str]) -> None:
        for line in stream:
            lines.put(line)
        lines.put(None)

    threading.Thread(target=read, args=(pinger.stdout,), daemon=True).start()
    deadline = time.monotonic() + timeout
    out: list[str] = []
    cpu_at_start: float | None = None
    cpu = None
    while True:
        try:
            line = lines.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            raise subprocess.TimeoutExpired(pinger.args, timeout) from None
        if line is None:
            break
        if line.strip() == "timing":
            cpu_at_start = process_cpu_seconds(ponger.pid)
        else:
            out.append(line)
            if cpu_at_start is not None and "p50_us=" in line:
                cpu = process_cpu_seconds(ponger.pid) - cpu_at_start
    pinger.wait(max(0.0, deadline - time.monotonic()))
    return "".join(out), cpu


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Run:
    """One benchmark run: a private ROS_HOME, a master, and the processes started."""

    def __init__(self, master: str, before: Path | None = None) -> None:
        self.before = before
        self.tmp = Path(tempfile.mkdtemp(prefix="rostui-bench-"))
        self.port = free_port()
        self.env = dict(os.environ)
        for key in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME"):
            self.env.pop(key, None)
        self.env.update(ROS_IP="127.0.0.1", ROS_HOME=str(self.tmp / "ros_home"),
                        ROS_MASTER_URI=f"http://127.0.0.1:{self.port}", PYTHONUNBUFFERED="1")
        (self.tmp / "ros_home").mkdir()
        self.procs: list[subprocess.Popen[str]] = []
        self.master_kind = master
        self._n = 0

    # -- processes --------------------------------------------------------------
    def spawn(self, cmd: list[str], name: str) -> subprocess.Popen[str]:
        self._n += 1
        err = open(self.tmp / f"{self._n:02d}-{name}.err", "w")
        proc = subprocess.Popen(cmd, env=self.env, stdout=subprocess.PIPE, stderr=err, text=True,
                                start_new_session=True, cwd=str(ROOT))
        err.close()
        self.procs.append(proc)
        return proc

    def stop(self, proc: subprocess.Popen[str], grace: float = 3.0) -> None:
        """SIGINT the process group, then SIGKILL it if it lingers."""
        if proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGINT)
                proc.wait(grace)
            except (ProcessLookupError, subprocess.TimeoutExpired):
                pass
        if proc.poll() is None:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait(5)
        if proc.stdout:
            proc.stdout.close()

    def close(self) -> None:
        for proc in reversed(self.procs):
            self.stop(proc, grace=2.0)
        shutil.rmtree(self.tmp, ignore_errors=True)

    # -- master ------------------------------------------------------------------
    def start_master(self) -> None:
        if self.master_kind == "rostui":
            code = f"import sys; from rostui.cli.core_run import run_core; sys.exit(run_core({self.port}))"
            cmd = [venv_python(), "-c", code]
        else:
            cmd = ["rosmaster", "--core", "-p", str(self.port)]
        self.master = self.spawn(cmd, "master")
        proxy = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"])
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline:
            if self.master.poll() is not None:
                raise RuntimeError(f"master exited with {self.master.returncode}")
            try:
                proxy.getUri("/bench")
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("master did not answer within 15 s")

    # -- peers ---------------------------------------------------------------------
    def peer_cmd(self, lib: str, *args: str) -> list[str]:
        if lib == "roscpp":
            return [str(CPP_BIN), *args]
        if lib == "rospy":
            return [SYSTEM_PYTHON, str(BENCH / "py_peer.py"), "rospy", *args]
        if lib == BEFORE:
            code = ("import runpy, sys; sys.meta_path = [f for f in sys.meta_path if 'editable' not in repr(f).lower()];"
                    " sys.path.insert(0, sys.argv[1]); del sys.argv[:2]; runpy.run_path(sys.argv[0], run_name='__main__')")
            return [venv_python(), "-c", code, str(self.before), str(BENCH / "py_peer.py"), "rostui", *args]
        if lib == NO_POLL:
            return ["env", "ROSTUI_BUSY_POLL_US=0", venv_python(), str(BENCH / "py_peer.py"), "rostui", *args]
        return [venv_python(), str(BENCH / "py_peer.py"), "rostui", *args]

    def throughput(self, lib: str, size: int, window: float) -> dict[str, float]:
        topic = f"{topic_prefix(lib)}/flood_{size}"
        counter = self.spawn(self.peer_cmd(lib, "count", topic, str(window)), f"{lib}-count-{size}")
        flooder = self.spawn(self.peer_cmd(lib, "flood", topic, str(size), str(window + 20)),
                             f"{lib}-flood-{size}")
        try:
            out, _ = counter.communicate(timeout=window + 25)
        except subprocess.TimeoutExpired:
            self.stop(counter)
            raise RuntimeError(f"{lib} count ({size} B) timed out") from None
        finally:
            self.stop(flooder)
        m = re.search(r"count=(\d+) bytes=(\d+) seconds=([\d.]+)", out or "")
        if not m:
            raise RuntimeError(f"{lib} count ({size} B) printed {out!r}, exit {counter.returncode}")
        n, nbytes, secs = int(m[1]), int(m[2]), float(m[3])
        return {"msgs_s": n / secs, "MB_s": nbytes / secs / 1e6, "count": n, "seconds": secs}

    def latency(self, lib: str, round_trips: int) -> dict[str, float]:
        """One ping-pong run: the ping's figures, and ``pong_cpu_us``, the echoing process's CPU a message over
        the timed round trips (from the ping's ``timing`` line to its result)."""
        a, b = f"{topic_prefix(lib)}/ping", f"{topic_prefix(lib)}/pong"
        ponger = self.spawn(self.peer_cmd(lib, "pong", a, b), f"{lib}-pong")
        pinger = self.spawn(self.peer_cmd(lib, "ping", a, b, str(round_trips)), f"{lib}-ping")
        try:
            out, pong_cpu = timed_echo(pinger, ponger, timeout=60)
        except subprocess.TimeoutExpired:
            self.stop(pinger)
            raise RuntimeError(f"{lib} ping timed out") from None
        finally:
            self.stop(ponger)
        fields = dict(re.findall(r"(\w+)=([\d.]+)", out))
        if "p50_us" not in fields or pong_cpu is None:
            raise RuntimeError(f"{lib} ping printed {out!r}, exit {pinger.returncode}")
        return {**{k: float(v) for k, v in fields.items()}, "pong_cpu_us": pong_cpu / round_trips * 1e6}

    def floor(self, round_trips: int, pong: str = "pong") -> tuple[float, float]:
        """p50 of a no-ROS TCP ping-pong with the ROS ping's threading (bench/tcp_floor.py, ``pong`` naming its
        echoing end), and the echoing process's CPU a message (µs) over the timed round trips."""
        port = free_port()
        ponger = self.spawn([venv_python(), str(BENCH / "tcp_floor.py"), pong, str(port)], f"floor-{pong}")
        time.sleep(0.3)
        pinger = self.spawn([venv_python(), str(BENCH / "tcp_floor.py"), "ping", str(port), str(round_trips)],
                            f"floor-{pong}-ping")
        try:
            out, pong_cpu = timed_echo(pinger, ponger, timeout=60)
        finally:
            self.stop(pinger)
            self.stop(ponger)
        fields = dict(re.findall(r"(\w+)=([\d.]+)", out))
        if "p50_us" not in fields or pong_cpu is None:
            raise RuntimeError(f"the floor's ping against {pong} printed {out!r}")
        return float(fields["p50_us"]), pong_cpu / round_trips * 1e6


METRICS = ("small_msgs_s", "large_MB_s", "p50_us", "p99_us", "ping_cpu_us", "pong_cpu_us")


def measure(run: Run, lib: str, args: argparse.Namespace) -> dict[str, float]:
    """One round for one library: both throughputs (unless ``--only latency``), then latency."""
    nothing = {"msgs_s": float("nan"), "MB_s": float("nan")}
    small = run.throughput(lib, SMALL, args.window) if args.only is None else nothing
    large = run.throughput(lib, LARGE, args.window) if args.only is None else nothing
    lat = run.latency(lib, args.round_trips)
    return {"small_msgs_s": small["msgs_s"], "large_MB_s": large["MB_s"],
            "p50_us": lat["p50_us"], "p99_us": lat["p99_us"], "ping_cpu_us": lat.get("cpu_us", float("nan")),
            "pong_cpu_us": lat["pong_cpu_us"]}


def median(values: list[float]) -> float:
    values = sorted(values)
    k = len(values)
    return values[k // 2] if k % 2 else (values[k // 2 - 1] + values[k // 2]) / 2


def summarize(rounds: dict[str, list[dict[str, float]]]) -> dict[str, dict[str, float]]:
    """Per library, the median of each metric over the rounds."""
    return {lib: {key: median([r[key] for r in rows]) for key in METRICS} for lib, rows in rounds.items() if rows}


def report(rounds: dict[str, list[dict[str, float]]], master: str, args: argparse.Namespace,
           floors: dict[str, list[tuple[float, float]]]) -> None:
    results = summarize(rounds)
    cols = [("small_msgs_s", "16 B msgs/s", "{:,.0f}"), ("large_MB_s", "1 MB MB/s", "{:,.1f}"),
            ("p50_us", "RTT p50 µs", "{:,.1f}"), ("p99_us", "RTT p99 µs", "{:,.1f}"),
            ("ping_cpu_us", "ping CPU µs/RT", "{:,.1f}"), ("pong_cpu_us", "pong CPU µs/msg", "{:,.1f}")]
    print()
    print(f"std_msgs/String pub/sub, publisher and subscriber in separate processes of the same library,"
          f" one master ({master}), 127.0.0.1")
    print(f"median of {args.rounds} interleaved rounds; throughput window {args.window:g} s;"
          f" {args.round_trips} round trips per round after warm-up;"
          f" {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}"
          + (f"; {args.load} busy-looping processes beside it" if args.load else ""))
    w = 19
    print(f"{'library':<14}" + "".join(f"{title:>{w}}" for _, title, _ in cols))
    for lib, row in results.items():
        print(f"{lib:<14}" + "".join(f"{fmt.format(row[key]):>{w}}" for key, _, fmt in cols))
        if len(rounds[lib]) > 1:
            spread = ["{}..{}".format(fmt.format(min(r[key] for r in rounds[lib])),
                                      fmt.format(max(r[key] for r in rounds[lib]))) for key, _, fmt in cols]
            print(f"{'  (range)':<14}" + "".join(f"{x:>{w}}" for x in spread))
    if "rostui" not in results:
        return
    ours = results["rostui"]
    for peer in ("rospy", "roscpp"):
        if peer in results:
            print(f"{'rostui/' + peer:<14}" + "".join(
                f"{ours[key] / results[peer][key]:>{w - 1}.2f}x" for key, _, _ in cols))
    if "rospy" in results:
        print()
        if floors.get("pong"):
            floor = median([p50 for p50, _ in floors["pong"]])
            floor_pong = median([cpu for _, cpu in floors["pong"]])
            print(f"no-ROS floor: a Python TCP ping-pong with the same threading (bench/tcp_floor.py) has"
                  f" p50 {floor:,.1f} µs = {floor / results['rospy']['p50_us']:.2f}x rospy's p50;"
                  f" rostui is {ours['p50_us'] / floor:.2f}x the floor; its ponger takes {floor_pong:,.1f} µs of"
                  f" CPU a message (rostui's {ours['pong_cpu_us']:,.1f}, rospy's {results['rospy']['pong_cpu_us']:,.1f})")
        for pong, rows in floors.items():
            if pong != "pong" and rows:
                print(f"the floor's ping against tcp_floor.py {pong}: p50 {median([p50 for p50, _ in rows]):,.1f} µs,"
                      f" its ponger {median([cpu for _, cpu in rows]):,.1f} µs of CPU a message")
        for key, (want, higher) in TARGETS.items():
            ratio = ours[key] / results["rospy"][key]
            ok = ratio >= want if higher else ratio <= want
            sign = ">=" if higher else "<="
            print(f"target {key:<13} rostui/rospy {ratio:6.2f}x  (want {sign} {want}x)  {'met' if ok else 'MISSED'}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--libs", default=",".join(LIBS), help=f"comma list of rospy,roscpp,rostui (and {NO_POLL}, {BEFORE})")
    parser.add_argument("--rounds", type=int, default=3, help="interleaved rounds; the table shows medians")
    parser.add_argument("--window", type=float, default=3.0, help="throughput window per round, seconds")
    parser.add_argument("--round-trips", type=int, default=5000, help="timed ping-pong round trips per round")
    parser.add_argument("--master", choices=("rostui", "rosmaster"), default="rostui",
                        help="which master all peers use (default: rostui core)")
    parser.add_argument("--json", help="also write every round's results to this file")
    parser.add_argument("--load", type=int, default=0,
                        help="start this many busy-looping processes for the whole run (a loaded machine)")
    parser.add_argument("--only", choices=("latency",), help="measure the round trips only")
    parser.add_argument("--before", type=Path, help=f"a checkout of an earlier commit, measured as {BEFORE}")
    parser.add_argument("--python", help="the Python rostui's peers and the floor run on (one with rostui installed; "
                                         "default: the project's .venv)")
    parser.add_argument("--floors", default="pong",
                        help="the no-ROS echoing ends measured each round: a comma list of tcp_floor.py's pong (the"
                             " floor), pong-uvloop, pong-msg")
    args = parser.parse_args()
    global PEER_PYTHON
    PEER_PYTHON = args.python
    libs = [x for x in args.libs.split(",") if x]
    unknown = set(libs) - set(LIBS) - {NO_POLL, BEFORE}
    if unknown or not libs:
        parser.error(f"unknown libraries: {', '.join(sorted(unknown))}")
    if set(args.floors.split(",")) - {"pong", "pong-uvloop", "pong-msg", ""}:
        parser.error(f"unknown floors in {args.floors!r}")
    if (BEFORE in libs) != (args.before is not None):
        parser.error(f"--before DIR and {BEFORE} in --libs go together")
    if "roscpp" in libs:
        build_cpp_peer()
    run = Run(args.master, args.before)
    rounds: dict[str, list[dict[str, float]]] = {lib: [] for lib in libs}
    floors: dict[str, list[tuple[float, float]]] = {pong: [] for pong in args.floors.split(",") if pong}
    started = time.monotonic()
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.load)]
    try:
        run.start_master()
        for i in range(args.rounds):
            order = libs[i % len(libs):] + libs[:i % len(libs)]  # rotate so no library always goes first
            for pong, rows in floors.items():
                rows.append(run.floor(args.round_trips, pong))
                print(f"round {i + 1} floor {pong}  p50_us={rows[-1][0]:,.1f}  pong_cpu_us={rows[-1][1]:,.1f}", flush=True)
            for lib in order:
                t = time.monotonic()
                row = measure(run, lib, args)
                rounds[lib].append(row)
                shown = "  ".join(f"{k}={v:,.1f}" for k, v in row.items())
                print(f"round {i + 1} {lib:<7} {time.monotonic() - t:5.1f} s  {shown}", flush=True)
    except KeyboardInterrupt:
        return 130
    finally:
        for proc in busy:
            proc.kill()
            proc.wait()
        run.close()
    master = "rostui core" if args.master == "rostui" else "rosmaster"
    report(rounds, master, args, floors)
    print(f"\nwhole run {time.monotonic() - started:.0f} s")
    if args.json:
        Path(args.json).write_text(json.dumps({"master": args.master, "window": args.window,
                                               "round_trips": args.round_trips, "rounds": rounds,
                                               "median": summarize(rounds)}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
