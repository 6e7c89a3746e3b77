#!/usr/bin/env python3
"""rostui launch against real roslaunch in the same run: time from launch to all 50 nodes registered.

A temporary package holds a 50-node launch file; every node is the same small
program (rostui's client: init_node, then spin; run by this Python), so the
launchers are compared, not the nodes.  A measurement starts the launcher and
polls the master's getSystemState every 20 ms until all 50 node names appear
(as publishers of /rosout); the clock starts just before the launcher process
is spawned.  Two cases, rostui and roslaunch interleaved in every round:

- ``master``: a `rostui core` already answers (both launchers reuse it);
- ``fresh``: no master answers, so each launcher starts one (rostui: in its own
  process; roslaunch: rosmaster + rosout as child processes).

    .venv/bin/python bench/bench_launch.py [--rounds 3] [--nodes 50] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import xmlrpc.client
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

NODE_PROGRAM = f"""#!{sys.executable}
from rostui import client as ros

ros.init_node("bench_node")
ros.spin()
"""


def free_port() -> int:
    """A TCP port nothing listens on right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_package(root: Path, count: int) -> Path:
    """A package ``bench_launch`` with the node program and a launch file of ``count`` nodes."""
    pkg = root / "bench_launch"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package format=\"2\"><name>bench_launch</name><version>0.0.0</version>"
                                     "<description>bench</description><maintainer email=\"a@b.c\">b</maintainer>"
                                     "<license>BSD</license></package>\n")
    node = pkg / "bench_node"
    node.write_text(NODE_PROGRAM)
    node.chmod(0o755)
    lines = ["<launch>"] + [f'  <node pkg="bench_launch" type="bench_node" name="node_{i:02d}"/>'
                            for i in range(count)] + ["</launch>"]
    launch = pkg / "fifty.launch"
    launch.write_text("\n".join(lines) + "\n")
    return launch


def registered(uri: str) -> set[str]:
    """Node names the master lists as publishers of any topic."""
    try:
        code, _, state = xmlrpc.client.ServerProxy(uri).getSystemState("/bench")
    except (OSError, xmlrpc.client.Error):
        return set()
    if code != 1:
        return set()
    return {node for _, nodes in state[0] for node in nodes}


def wait_port(port: int, timeout: float = 30.0) -> None:
    """Until something accepts connections on ``port``."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        time.sleep(0.02)
    raise TimeoutError(f"nothing listens on {port}")


def stop(proc: subprocess.Popen, timeout: float = 60.0) -> None:
    """SIGINT, then SIGKILL of the process group."""
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def measure(launcher: str, launch: Path, count: int, case: str, env_base: dict[str, str], home: Path) -> float:
    """Seconds from spawning the launcher to all ``count`` nodes registered."""
    port = free_port()
    uri = f"http://127.0.0.1:{port}"
    env = dict(env_base, ROS_MASTER_URI=uri, ROS_HOME=str(home / f"{launcher}-{case}-{port}"))
    core = None
    if case == "master":
        core = subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        wait_port(port)
    argv = [sys.executable, "-m", "rostui", "launch", str(launch)] if launcher == "rostui" else \
        ["roslaunch", str(launch)]
    if launcher == "roslaunch":
        argv += ["-p", str(port)]
    wanted = {f"/node_{i:02d}" for i in range(count)}
    started = time.perf_counter()
    proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            stdin=subprocess.DEVNULL, start_new_session=True)
    try:
        deadline = time.monotonic() + 180
        while not wanted <= registered(uri):
            if time.monotonic() > deadline or proc.poll() is not None:
                raise RuntimeError(f"{launcher} ({case}): nodes never all registered")
            time.sleep(0.02)
        return time.perf_counter() - started
    finally:
        stop(proc)
        if core is not None:
            stop(core)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--nodes", type=int, default=50)
    parser.add_argument("--json", type=Path)
    options = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench_launch_") as tmp:
        root = Path(tmp)
        (root / "pkgs").mkdir()
        launch = make_package(root / "pkgs", options.nodes)
        env = dict(os.environ, ROS_PACKAGE_PATH=f"{root / 'pkgs'}:{REPO / 'rostui' / 'share'}", ROS_IP="127.0.0.1",
                   PYTHONUNBUFFERED="1")
        env.pop("ROS_HOSTNAME", None)
        results: dict[str, dict[str, list[float]]] = {case: {"rostui": [], "roslaunch": []}
                                                      for case in ("master", "fresh")}
        for round_no in range(options.rounds):
            for case in ("master", "fresh"):
                order = ("rostui", "roslaunch") if round_no % 2 == 0 else ("roslaunch", "rostui")
                for launcher in order:
                    seconds = measure(launcher, launch, options.nodes, case, env, root)
                    results[case][launcher].append(seconds)
                    print(f"round {round_no + 1} {case:6s} {launcher:9s} {seconds:6.2f} s", flush=True)
    print()
    print(f"{options.nodes} nodes, launch -> all registered (median of {options.rounds}, range)")
    summary: dict[str, dict[str, float]] = {}
    for case, by in results.items():
        med = {k: statistics.median(v) for k, v in by.items()}
        ratio = med["rostui"] / med["roslaunch"]
        summary[case] = {**med, "ratio": ratio}
        print(f"  {case:6s}  rostui {med['rostui']:5.2f} s [{min(by['rostui']):.2f}-{max(by['rostui']):.2f}]   "
              f"roslaunch {med['roslaunch']:5.2f} s [{min(by['roslaunch']):.2f}-{max(by['roslaunch']):.2f}]   "
              f"rostui/roslaunch {ratio:.2f}x")
    if options.json:
        options.json.write_text(json.dumps({"runs": results, "summary": summary}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
