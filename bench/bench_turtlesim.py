#!/usr/bin/env python3
"""turtlesim in a terminal: update rate, frame rate and CPU with 10 turtles; bytes written per second.

(a) ``load``: the turtlesim app runs in an 80x24 (and a 200x60) pseudo-terminal,
    pinned to CPU 0, against a `rostui core` master on the other CPU.  This
    script spawns 9 more turtles through ``/spawn`` and keeps all 10 circling
    with ``cmd_vel``.  The app samples its own counters once a second: world
    updates, frames drawn, time spent in ``TurtleView.draw_frame`` and the
    process's CPU time.  Targets: 62.5 updates/s, 30 frames/s, within one core.
(b) ``bytes``: `rostui turtlesim` itself (the console command, embedded master)
    in an 80x24 pseudo-terminal; turtle1 circles continuously on ``cmd_vel``
    from this process while the bytes the app writes to the terminal are
    counted per second, for truecolor, 256 and 16 colours, and with the
    turtle standing still.  Target: under 50 KB/s.

There is no peer: ROS turtlesim needs a Qt window, which a terminal does not have.

    .venv/bin/python bench/bench_turtlesim.py [--seconds 10] [--only load|bytes] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from _common import APP_CPU, REPO, PtyApp, free_port, other_cpus, ros_env, wait_port

TURTLES = 10
LINEAR, ANGULAR = 1.5, 1.5  # circles of 1 m radius
SPAWN_GRID = (2.3, 5.5, 8.7)


# -- the pseudo-terminal -----------------------------------------------------------------------
@dataclass
class Terminal(PtyApp):
    """A process on a pty of a fixed size; every byte it writes is counted."""

    chunks: list[tuple[float, int]] = field(default_factory=list)

    def received(self, chunk: bytes) -> None:
        """Count ``chunk`` with the time it arrived."""
        self.chunks.append((time.monotonic(), len(chunk)))

    def bytes_between(self, start: float, end: float) -> int:
        """Bytes the process wrote in [start, end)."""
        return sum(n for t, n in list(self.chunks) if start <= t < end)

    def per_second(self, start: float, end: float) -> list[int]:
        """Bytes written in each whole second of [start, end)."""
        return [self.bytes_between(start + i, start + i + 1) for i in range(int(end - start))]


# -- the child for (a): the app sampling its own counters ---------------------------------------
def child_app(stats_path: str, ros_args: list[str]) -> int:
    """Run TurtlesimApp in this terminal, appending one JSON line of counters per second."""
    from rostui.turtlesim import render
    from rostui.turtlesim.app import TurtlesimApp

    draw = {"seconds": 0.0, "calls": 0}
    original = render.TurtleView.draw_frame

    def timed_draw(self: render.TurtleView) -> bool:
        start = time.perf_counter()
        try:
            return original(self)
        finally:
            draw["seconds"] += time.perf_counter() - start
            draw["calls"] += 1

    render.TurtleView.draw_frame = timed_draw  # type: ignore[method-assign]
    out = open(stats_path, "a", buffering=1)

    class SampledApp(TurtlesimApp):
        def on_mount(self) -> None:
            super().on_mount()
            self.set_interval(1.0, self.sample)

        def sample(self) -> None:
            out.write(json.dumps({
                "t": time.monotonic(), "cpu": time.process_time(), "updates": self.sim.updates,
                "frames": self.view.frames, "draw_s": draw["seconds"], "draw_calls": draw["calls"],
                "turtles": len(self.sim.world.turtles), "rate": self.sim.rate,
            }) + "\n")

    app = SampledApp(ros_args)
    app.run()
    out.close()
    return app.return_code or 0


# -- the driver: spawn and steer turtles with rostui's own tools, as separate processes -----------
class Driver:
    """Spawns turtles with `rostui service call /spawn` and keeps them circling with `rostui topic pub -r 5`."""

    def __init__(self, env: dict[str, str]) -> None:
        self.env = env
        self.publishers: list[subprocess.Popen] = []

    def rostui(self, *args: str) -> str:
        """Run one rostui command to completion; its stdout."""
        result = subprocess.run([sys.executable, "-m", "rostui", *args], env=self.env, cwd=REPO,
                                capture_output=True, text=True, timeout=60)
        if result.returncode != 0:
            raise SystemExit(f"rostui {' '.join(args)} failed: {result.stderr.strip()}")
        return result.stdout

    def wait_for_simulator(self, timeout: float = 30.0) -> None:
        """Wait until the turtlesim node serves /spawn."""
        deadline = time.monotonic() + timeout
        while subprocess.run([sys.executable, "-m", "rostui", "service", "type", "/spawn"], env=self.env, cwd=REPO,
                             capture_output=True, timeout=60).returncode != 0:
            if time.monotonic() > deadline:
                raise SystemExit("the turtlesim node did not serve /spawn in time")
            time.sleep(0.2)

    def spawn(self, count: int) -> list[str]:
        """turtle1 plus ``count - 1`` turtles spawned on a grid; returns all names."""
        names = ["turtle1"]
        spots = [(x, y) for x in SPAWN_GRID for y in SPAWN_GRID]
        for i in range(count - 1):
            x, y = spots[i % len(spots)]
            out = self.rostui("service", "call", "/spawn", f"{{x: {x}, y: {y}, theta: {0.7 * i}, name: ''}}")
            names.append(out.split("name:", 1)[1].strip().strip("\"'"))
        return names

    def circle(self, names: list[str], linear: float = LINEAR, angular: float = ANGULAR) -> None:
        """Start one publisher process per turtle: a circling Twist 5 times a second."""
        twist = f"{{linear: {{x: {linear}}}, angular: {{z: {angular}}}}}"
        for name in names:
            self.publishers.append(subprocess.Popen(
                [sys.executable, "-m", "rostui", "topic", "pub", "-r", "5", f"/{name}/cmd_vel",
                 "geometry_msgs/Twist", twist],
                env=self.env, cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))

    def stop(self) -> None:
        """Stop the publisher processes."""
        for proc in self.publishers:
            proc.terminate()
        for proc in self.publishers:
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
        self.publishers.clear()


def base_env(port: int, home: str) -> dict[str, str]:
    """The environment every process of the bench shares."""
    env = ros_env(port, home, TERM="xterm-256color", COLORTERM="truecolor", LANG="C.UTF-8")
    env.pop("NO_COLOR", None)
    return env


def wait_for(predicate: Any, what: str, timeout: float = 30.0) -> None:
    """Poll until ``predicate()`` holds."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise SystemExit(f"timed out waiting for {what}")
        time.sleep(0.05)


def read_samples(path: Path) -> list[dict[str, float]]:
    """The child's JSON lines so far."""
    if not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def run_load(seconds: float, cols: int, rows: int, driver: Driver, env: dict[str, str], tmp: Path) -> dict[str, Any]:
    """(a): 10 circling turtles; the app's update rate, frame rate, draw time and CPU on one core."""
    stats = tmp / f"load-{cols}x{rows}.jsonl"
    term = Terminal([sys.executable, str(Path(__file__).resolve()), "--child-app", str(stats)], env, cols, rows,
                    pin={APP_CPU})
    term.start()
    try:
        driver.wait_for_simulator()
        names = driver.spawn(TURTLES)
        driver.circle(names)
        time.sleep(3.0)  # warm-up: every turtle moving, rate window filled
        first = read_samples(stats)[-1]
        start_wall = time.monotonic()
        time.sleep(seconds)
        last = read_samples(stats)[-1]
        end_wall = time.monotonic()
    finally:
        driver.stop()
        status = term.quit()
    span = last["t"] - first["t"]
    frames = last["frames"] - first["frames"]
    calls = last["draw_calls"] - first["draw_calls"]
    return {
        "size": f"{cols}x{rows}",
        "turtles": int(last["turtles"]),
        "updates_per_s": (last["updates"] - first["updates"]) / span,
        "frames_per_s": frames / span,
        "draw_ms_per_frame": 1000 * (last["draw_s"] - first["draw_s"]) / max(frames, 1),
        "draw_ms_per_tick": 1000 * (last["draw_s"] - first["draw_s"]) / max(calls, 1),
        "cpu_percent": 100 * (last["cpu"] - first["cpu"]) / span,
        "bytes_per_s": term.bytes_between(start_wall, end_wall) / (end_wall - start_wall),
        "exit_status": status,
    }


def run_bytes(seconds: float, label: str, term_env: dict[str, str], drive: bool, tmp: Path) -> dict[str, Any]:
    """(b): `rostui turtlesim` in an 80x24 pty (embedded master); bytes written per second."""
    port = free_port()
    home = tempfile.mkdtemp(prefix="rostui-bench-", dir=tmp)
    env = base_env(port, home)
    env.update(term_env)
    for key in [k for k, v in term_env.items() if v is None]:
        env.pop(key, None)
    term = Terminal([sys.executable, "-m", "rostui", "turtlesim"], env, 80, 24, pin={APP_CPU})
    term.start()
    driver = Driver(env)
    try:
        wait_port(port)
        driver.wait_for_simulator()
        if drive:
            driver.circle(["turtle1"], linear=2.0, angular=1.0)
        time.sleep(3.0)
        start = time.monotonic()
        time.sleep(seconds)
        end = time.monotonic()
        seconds_list = term.per_second(start, end)
    finally:
        driver.stop()
        status = term.quit()
    total = term.bytes_between(start, end)
    return {
        "terminal": label,
        "driving": drive,
        "bytes_per_s": total / (end - start),
        "max_second": max(seconds_list) if seconds_list else 0,
        "exit_status": status,
    }


def main() -> int:
    """Run the benchmarks and print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="measuring window of each run")
    parser.add_argument("--only", choices=("load", "bytes"), help="run one part")
    parser.add_argument("--json", help="also write the results here")
    parser.add_argument("--child-app", help=argparse.SUPPRESS)
    args, rest = parser.parse_known_args()
    if args.child_app:
        return child_app(args.child_app, rest)
    os.sched_setaffinity(0, other_cpus())
    results: dict[str, Any] = {"cpus": len(os.sched_getaffinity(0) | {APP_CPU}), "app_cpu": APP_CPU}
    with tempfile.TemporaryDirectory(prefix="rostui-bench-turtlesim-") as tmp_name:
        tmp = Path(tmp_name)
        if args.only in (None, "load"):
            port = free_port()
            env = base_env(port, str(tmp / "home"))
            (tmp / "home").mkdir()
            core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env, cwd=REPO,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            try:
                wait_port(port)
                results["load"] = [run_load(args.seconds, cols, rows, Driver(env), env, tmp)
                                   for cols, rows in ((80, 24), (200, 60))]
            finally:
                core.terminate()
                core.wait(timeout=15)
            print(f"(a) {TURTLES} turtles circling, app pinned to CPU {APP_CPU}, `rostui core` elsewhere, "
                  f"{args.seconds:g} s window")
            print(f"{'terminal':>9} {'updates/s':>10} {'frames/s':>9} {'draw ms/frame':>14} {'CPU %':>6} "
                  f"{'bytes/s':>9}")
            for r in results["load"]:
                print(f"{r['size']:>9} {r['updates_per_s']:10.1f} {r['frames_per_s']:9.1f} "
                      f"{r['draw_ms_per_frame']:14.2f} {r['cpu_percent']:6.1f} {r['bytes_per_s']:9.0f}")
            print("targets: 62.5 updates/s, 30 frames/s, CPU below 100 % of one core\n")
        if args.only in (None, "bytes"):
            cases = [
                ("truecolor", {"TERM": "xterm-256color", "COLORTERM": "truecolor"}, True),
                ("256", {"TERM": "xterm-256color", "COLORTERM": None}, True),
                ("16", {"TERM": "xterm", "COLORTERM": None}, True),
                ("truecolor", {"TERM": "xterm-256color", "COLORTERM": "truecolor"}, False),
            ]
            results["bytes"] = [run_bytes(args.seconds, label, term_env, drive, tmp)
                                for label, term_env, drive in cases]
            print(f"(b) `rostui turtlesim` at 80x24, turtle1 circling on cmd_vel, {args.seconds:g} s window")
            print(f"{'colours':>9} {'turtle':>8} {'KB/s':>7} {'max KB in 1 s':>14}")
            for r in results["bytes"]:
                print(f"{r['terminal']:>9} {'moving' if r['driving'] else 'still':>8} "
                      f"{r['bytes_per_s'] / 1000:7.1f} {r['max_second'] / 1000:14.1f}")
            print("target: under 50 KB/s while driving")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
