"""The measuring harness both `rostui view` benchmarks share (camera and laser).

One run: `rostui core` and the benchmark's own publisher (its script in
``publish`` mode, printing ``advertised`` and then ``sent N T`` lines) on the
CPUs other than CPU 0; the real `rostui view TOPIC` on a pseudo-terminal
pinned to CPU 0; after a warm-up, the viewer's CPU (psutil), the bytes it
writes, frames sent, and the rates its own figures line reports; then real
``rostopic hz`` on the same topic, pinned the same way, as the ROS peer.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable

import psutil

from _common import APP_CPU, RecordingPty, free_port, other_cpus, ros_env, wait_port


def sent_between(log: Path, start: float, end: float) -> int:
    """Messages the publisher sent between wall times ``start`` and ``end`` (from its "sent N T" lines)."""
    points = [(float(t), int(n)) for n, t in re.findall(r"sent (\d+) ([\d.]+)", log.read_text())]
    before = max((n for t, n in points if t <= start), default=0)
    after = max((n for t, n in points if t <= end), default=0)
    return after - before


def cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of process ``pid``."""
    times = psutil.Process(pid).cpu_times()
    return times.user + times.system


def _pinned(cpus: set[int]) -> Callable[[], None]:
    return lambda: os.sched_setaffinity(0, cpus)


def measure_view(script: str, topic: str, rates: re.Pattern[bytes], *, rate: float, seconds: float, warmup: float,
                 cols: int, rows: int, **env_extra: str) -> dict[str, float]:
    """Run the publisher of ``script`` and `rostui view topic`; the figures described in the module docstring.

    ``rates`` finds (received, drawn) per second in the view's figures line.
    """
    port = free_port()
    home = tempfile.mkdtemp(prefix="bench_view_")
    env = ros_env(port, home, TERM="xterm-256color", COLORTERM="truecolor", **env_extra)
    others = other_cpus()
    procs: list[subprocess.Popen[bytes]] = []
    results: dict[str, float] = {}
    try:
        procs.append(subprocess.Popen([sys.executable, "-m", "rostui", "core", "-p", str(port)], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT,
                                      preexec_fn=_pinned(others)))
        wait_port(port)
        log = Path(home) / "publisher.log"
        with log.open("w") as out:
            publisher = subprocess.Popen([sys.executable, script, "publish", "--rate", str(rate)], env=env,
                                         stdout=out, stderr=subprocess.STDOUT, preexec_fn=_pinned(others))
        procs.append(publisher)
        deadline = time.time() + 30
        while "advertised" not in log.read_text():
            if time.time() > deadline or publisher.poll() is not None:
                raise SystemExit(f"publisher did not start: {log.read_text()}")
            time.sleep(0.1)

        viewer = RecordingPty([sys.executable, "-m", "rostui", "view", topic], env, cols, rows, pin={APP_CPU})
        viewer.start()
        assert viewer.proc is not None
        time.sleep(warmup)
        offset, cpu0, t0 = viewer.size, cpu_seconds(viewer.proc.pid), time.time()
        time.sleep(seconds)
        written, cpu1, t1 = viewer.size - offset, cpu_seconds(viewer.proc.pid), time.time()
        window = viewer.since(offset)
        viewer.quit()
        figures = [(float(a), float(b)) for a, b in rates.findall(window)]
        span = t1 - t0
        received_fps = statistics.mean(r for r, _ in figures) if figures else 0.0
        drawn_fps = statistics.mean(d for _, d in figures) if figures else 0.0
        cpu = cpu1 - cpu0
        results.update({
            "viewer_cores": cpu / span, "viewer_cpu_ms_per_frame_drawn": 1000 * cpu / max(1.0, drawn_fps * span),
            "viewer_cpu_ms_per_message_received": 1000 * cpu / max(1.0, received_fps * span),
            "bytes_per_second": written / span, "sent_fps": sent_between(log, t0, t1) / span,
            "received_fps": received_fps, "drawn_fps": drawn_fps,
        })

        if shutil.which("rostopic"):
            hz = subprocess.Popen(["rostopic", "hz", topic], env=env, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, preexec_fn=_pinned({APP_CPU}))
            procs.append(hz)
            time.sleep(warmup)
            c0, h0 = cpu_seconds(hz.pid), time.time()
            time.sleep(seconds)
            results["rostopic_hz_cores"] = (cpu_seconds(hz.pid) - c0) / (time.time() - h0)
    finally:
        for proc in reversed(procs):
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        shutil.rmtree(home, ignore_errors=True)
    return results


def print_peer(results: dict[str, float]) -> None:
    """The rostopic hz line, when it ran."""
    if "rostopic_hz_cores" in results:
        hz_cores = results["rostopic_hz_cores"]
        print(f"  rostopic hz (rospy) on the same topic: {hz_cores:.2f} cores; "
              f"view/rostopic hz {results['viewer_cores'] / max(hz_cores, 1e-9):.2f}x")


async def publish_at(rate: float, node_name: str, topic: str, type_name: str,
                     make: Callable[[Any, int, float], Any]) -> None:
    """Publish ``make(msg_class, n, period)`` on ``topic`` at ``rate`` Hz until SIGINT (the publisher half).

    Prints ``advertised`` once, then ``sent N T`` once a second, which
    :func:`measure_view` reads; each message is stamped with the wall time.
    """
    import asyncio

    from rostui.core.msg import get_message_class
    from rostui.core.node import AsyncNode
    from rostui.core.rostime import Time

    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    node = await AsyncNode(node_name, anonymous=True, argv=[]).start(publish_rosout=False)
    msg_class = get_message_class(type_name)
    pub = await node.advertise(topic, msg_class, queue_size=1)
    print("advertised", flush=True)
    period = 1.0 / rate
    due = loop.time()
    sent = 0
    while not stop.is_set():
        msg = make(msg_class, sent, period)
        msg.header.stamp = Time.from_sec(time.time())
        pub.publish(msg)
        sent += 1
        if sent % int(rate) == 0:
            print(f"sent {sent} {time.time():.3f}", flush=True)
        due += period
        try:
            await asyncio.wait_for(stop.wait(), max(0.0, due - loop.time()))
        except asyncio.TimeoutError:
            pass
    await node.shutdown("done")
