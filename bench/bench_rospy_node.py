#!/usr/bin/env python3
"""A rospy talker under `rostui python` against the same talker on Debian's rospy: start-up and peak RSS.

The talker is rospy_tutorials' (``tests/python_compat/real/ros_tutorials/talker.py``:
``rospy.init_node('talker', anonymous=True)``, a ``chatter`` publisher with
``queue_size=10``, 10 Hz, ``"hello world %s" % rospy.get_time()``), copied to a
temporary folder and run unmodified as
``/usr/bin/python3 talker.py`` (Debian's rospy) and as ``rostui python
talker.py`` (rostui's shim), one at a time, against one ``rostui core`` on a
free port with a private ROS_HOME. A subscriber in this process (rostui's
client) stamps each message's arrival. Per run of a talker:

* start-up: from just before the process starts to the first message arriving
  at the subscriber; also to the talker's own first publish (the time its
  first ``hello world`` line says);
* peak RSS: VmHWM of the talker (and of its children, if any) from
  /proc/PID/status, read after MESSAGES messages, just before it is stopped.

Rounds are interleaved (the order alternates) and the table gives medians with
their ranges, then the ratios rostui / rospy against the targets of issue 35
(peak RSS <= 0.5x, start-up <= 0.4x). ``--load N`` runs N busy-looping
processes during the whole run, for the figure on a loaded machine.

    .venv/bin/python bench/bench_rospy_node.py                         # 6 rounds, about 30 s
    .venv/bin/python bench/bench_rospy_node.py --load 2 --rounds 10 --json out.json
    .venv/bin/python bench/bench_rospy_node.py --rostui /tmp/inst/bin/rostui     # a regular install

``--rostui`` picks the executable (default: the console script beside this
Python); an editable install adds its import hook to every start. ``--before
EXE`` adds a third talker, ``EXE python talker.py`` (another install, say of
the commit before a change), measured in the same rounds.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from _common import REPO, free_port, ros_env, wait_port

DEBIAN_PYTHON = "/usr/bin/python3"
ROSTUI = str(Path(sys.executable).with_name("rostui"))
TARGETS = {"startup_s": 0.4, "first_publish_s": 0.4, "peak_rss_kb": 0.5}
"""rostui / rospy ratios issue 35 asks for (lower is better)."""

TALKER = Path(__file__).resolve().parent.parent / "tests" / "python_compat" / "real" / "ros_tutorials" / "talker.py"
"""rospy_tutorials' talker, as ROS shipped it (tests/python_compat/real/SOURCES.md: BSD, ros/ros_tutorials)."""


def load_average() -> str:
    """The 1, 5 and 15 minute load averages."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


class Arrivals:
    """The subscriber's side: the wall time of each ``hello world`` message that arrives."""

    def __init__(self) -> None:
        self._lock = threading.Condition()
        self._stamps: list[tuple[float, float]] = []  # (arrival, the publish time the message carries)

    def received(self, msg: object) -> None:
        """Stamp one message (called on the engine thread)."""
        now = time.time()
        text = str(getattr(msg, "data", ""))
        try:
            sent = float(text.rsplit(" ", 1)[-1])
        except ValueError:
            return
        with self._lock:
            self._stamps.append((now, sent))
            self._lock.notify_all()

    def wait(self, since: float, count: int, timeout: float) -> list[float]:
        """Arrival times of the first *count* messages published after *since*; fewer if *timeout* passes."""
        deadline = time.monotonic() + timeout
        with self._lock:
            while True:
                got = [at for at, sent in self._stamps if sent >= since]
                left = deadline - time.monotonic()
                if len(got) >= count or left <= 0:
                    return got[:count]
                self._lock.wait(left)


def family(pid: int) -> list[int]:
    """*pid* and every process descended from it."""
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            stat = Path(f"/proc/{entry}/stat").read_text()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        children.setdefault(ppid, []).append(int(entry))
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        out.append(p)
        todo.extend(children.get(p, []))
    return out


def vm_hwm_kb(pid: int) -> int:
    """VmHWM of *pid* in kB, 0 if it is gone."""
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    except OSError:
        pass
    return 0


@dataclass
class Talker:
    """One run of the talker: its process, its first ``hello world`` line, and what was measured."""

    argv: list[str]
    env: dict[str, str]
    log: Path
    proc: subprocess.Popen[bytes] | None = None
    started: float = 0.0
    first_line_stamp: float | None = None
    result: dict[str, float] = field(default_factory=dict)

    def start(self) -> None:
        """Start the process (its own session) and a thread that reads its first ``hello world`` line."""
        err = self.log.open("ab")
        self.started = time.time()
        self.proc = subprocess.Popen(self.argv, env=self.env, cwd=self.log.parent, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.PIPE, stderr=err, start_new_session=True)
        err.close()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc is not None and self.proc.stdout is not None
        for raw in self.proc.stdout:
            line = raw.decode(errors="replace")
            if self.first_line_stamp is None and "hello world" in line and "[" in line:
                try:  # rospy's console line: [INFO] [1700000000.123456]: hello world ...
                    self.first_line_stamp = float(line.split("[", 2)[2].split("]", 1)[0])
                except (IndexError, ValueError):
                    pass

    def stop(self) -> None:
        """SIGINT its process group, as Ctrl-C would; SIGKILL after 10 s."""
        assert self.proc is not None
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGINT)
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
            except ProcessLookupError:
                pass
        if self.proc.stdout is not None:
            self.proc.stdout.close()


def run_one(name: str, argv: list[str], env: dict[str, str], arrivals: Arrivals, messages: int,
            log: Path) -> dict[str, float]:
    """Start a talker, wait for its first *messages* messages, read its peak RSS, stop it."""
    talker = Talker(argv, env, log)
    talker.start()
    try:
        got = arrivals.wait(talker.started, messages, timeout=60)
        if not got:
            raise SystemExit(f"{name}: no message arrived within 60 s (see {log})")
        assert talker.proc is not None
        peak = sum(vm_hwm_kb(p) for p in family(talker.proc.pid))
    finally:
        talker.stop()
    out = {"startup_s": got[0] - talker.started, "peak_rss_kb": float(peak)}
    if talker.first_line_stamp is not None:
        out["first_publish_s"] = talker.first_line_stamp - talker.started
    return out


def summary(results: dict[str, list[dict[str, float]]]) -> dict[str, dict[str, list[float]]]:
    """Each talker's medians, minimum and maximum per metric."""
    out: dict[str, dict[str, list[float]]] = {}
    for name, runs in results.items():
        out[name] = {}
        for key in TARGETS:
            values = [r[key] for r in runs if key in r]
            if values:
                out[name][key] = [statistics.median(values), min(values), max(values)]
    return out


def show(stats: dict[str, dict[str, list[float]]]) -> None:
    """Print the table, the ratios and the targets."""
    units = {"startup_s": ("start-up to first arrival", 1e3, "ms"),
             "first_publish_s": ("start-up to first publish", 1e3, "ms"),
             "peak_rss_kb": ("peak RSS", 1 / 1024, "MB")}
    for key, (label, scale, unit) in units.items():
        cells = []
        for name in stats:
            if key in stats.get(name, {}):
                med, lo, hi = (v * scale for v in stats[name][key])
                cells.append(f"{name} {med:7.1f} {unit} ({lo:.1f}..{hi:.1f})")
        print(f"{label:<28}" + "   ".join(cells))
    for name in (n for n in stats if n != "rospy"):
        for key, want in TARGETS.items():
            if key in stats.get("rospy", {}) and key in stats[name]:
                ratio = stats[name][key][0] / stats["rospy"][key][0]
                print(f"{name + '/rospy':<14}{units[key][0]:<28}{ratio:6.2f}x  (want <= {want}x)  "
                      f"{'met' if ratio <= want else 'MISSED'}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=6)
    parser.add_argument("--messages", type=int, default=5, help="messages to receive before reading the peak RSS")
    parser.add_argument("--rostui", default=ROSTUI, help="the rostui executable (default: beside this Python)")
    parser.add_argument("--before", help="another rostui executable to measure alongside (say, an older install)")
    parser.add_argument("--load", type=int, default=0, help="run this many busy-looping processes throughout")
    parser.add_argument("--json", help="write the runs and the summary to this file")
    args = parser.parse_args()
    if not Path(DEBIAN_PYTHON).exists():
        raise SystemExit(f"{DEBIAN_PYTHON} not found: no Debian rospy to compare with")

    tmp = Path(tempfile.mkdtemp(prefix="rostui-bench-node-"))
    (tmp / "ros_home").mkdir()
    (tmp / "talker.py").write_text(TALKER.read_text())
    port = free_port()
    env = ros_env(port, str(tmp / "ros_home"), PYTHONUNBUFFERED="1")
    for key in ("PYTHONPATH", "VIRTUAL_ENV", "PYTHONHOME", "ROSTUI_PYTHON"):
        env.pop(key, None)
    os.environ.update(ROS_MASTER_URI=env["ROS_MASTER_URI"], ROS_HOME=env["ROS_HOME"], ROS_IP="127.0.0.1")
    commands = {"rospy": [DEBIAN_PYTHON, "talker.py"], "rostui": [args.rostui, "python", "talker.py"]}
    if args.before:
        commands["before"] = [args.before, "python", "talker.py"]
    burners: list[subprocess.Popen[bytes]] = []
    core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env, cwd=REPO,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    results: dict[str, list[dict[str, float]]] = {name: [] for name in commands}
    record: dict[str, object] = {"args": vars(args), "load_before": load_average()}
    try:
        wait_port(port)
        from rostui import client as ros

        arrivals = Arrivals()
        ros.init_node("bench_listener", disable_signals=True)
        ros.Subscriber("/chatter", ros.msg("std_msgs/String"), arrivals.received)
        burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.load)]
        print(f"files in {tmp}; {args.load} busy-looping processes; load average {load_average()}", flush=True)
        for name, argv in commands.items():  # warm the page cache once
            run_one(name, argv, env, arrivals, 1, tmp / f"{name}.log")
        for round_no in range(args.rounds):
            order = list(commands)[round_no % len(commands):] + list(commands)[:round_no % len(commands)]
            for name in order:
                run = run_one(name, commands[name], env, arrivals, args.messages, tmp / f"{name}.log")
                results[name].append(run)
                print(f"round {round_no + 1} {name:<7} start-up {run['startup_s'] * 1e3:7.1f} ms, first publish "
                      f"{run.get('first_publish_s', float('nan')) * 1e3:7.1f} ms, peak RSS "
                      f"{run['peak_rss_kb'] / 1024:5.1f} MB; load {load_average()}", flush=True)
        record["load_after"] = load_average()
    finally:
        if "rostui.client" in sys.modules:
            sys.modules["rostui.client"].signal_shutdown("benchmark done")
        for burner in burners:
            burner.kill()
            burner.wait()
        try:
            os.killpg(core.pid, signal.SIGINT)
            core.wait(10)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            os.killpg(core.pid, signal.SIGKILL)
            core.wait()
    stats = summary(results)
    print(f"medians over {args.rounds} rounds ({args.load} busy-looping processes; load average "
          f"{record['load_before']} before, {record.get('load_after', '?')} after):")
    show(stats)
    if args.json:
        record.update(runs=results, summary=stats)
        Path(args.json).write_text(json.dumps(record, indent=1))
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
