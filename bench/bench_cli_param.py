#!/usr/bin/env python3
"""Wall time of `rostui param get /run_id` against `rosparam get /run_id`, same master, one run.

Starts one `rostui core` on a free port with a private ROS_HOME, then runs each
command ROUNDS times, interleaved, and prints medians and the ratio (target:
rostui / rosparam <= 1.0).  Both are run as users run them: the installed
``rostui`` console script (beside this Python) and ROS's ``rosparam`` script.

    python bench/bench_cli_param.py [--rounds 10] [--rostui PATH]

``--rostui`` picks the executable to time (default: the console script beside
this Python).  An editable install (``pip install -e``) adds Python's
editable-finder to every start; measure a regular ``pip install .`` for what
users get.
"""

from __future__ import annotations

import argparse
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
ROSTUI = str(Path(sys.executable).with_name("rostui"))


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def timed(argv: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    proc = subprocess.run(argv, env=env, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed: {proc.stderr.strip()}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=10)
    parser.add_argument("--rostui", default=ROSTUI, help="the rostui executable to time")
    args = parser.parse_args()
    port = free_port()
    home = tempfile.mkdtemp(prefix="rostui-bench-")
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_IP="127.0.0.1")
    core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env, cwd=REPO,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise SystemExit("rostui core did not start")
                time.sleep(0.05)
        commands = {"rostui param get": [args.rostui, "param", "get", "/run_id"]}
        if shutil.which("rosparam"):
            commands["rosparam get"] = ["rosparam", "get", "/run_id"]
        else:
            print("rosparam not installed: no peer to compare with")
        for argv in commands.values():  # warm caches once
            timed(argv, env)
        times: dict[str, list[float]] = {name: [] for name in commands}
        for _ in range(args.rounds):
            for name, argv in commands.items():
                times[name].append(timed(argv, env))
    finally:
        core.terminate()
        core.wait(10)
        shutil.rmtree(home, ignore_errors=True)
    print(f"{'command':<24}{'median ms':>11}{'min ms':>9}{'max ms':>9}")
    med = {name: statistics.median(v) for name, v in times.items()}
    for name, values in times.items():
        print(f"{name:<24}{med[name] * 1e3:>11.1f}{min(values) * 1e3:>9.1f}{max(values) * 1e3:>9.1f}")
    if "rosparam get" in med:
        print(f"ratio rostui param get / rosparam get: {med['rostui param get'] / med['rosparam get']:.2f}"
              " (target <= 1.0)")


if __name__ == "__main__":
    main()
