"""Benchmark: rostui's master against Debian's rosmaster, same client, same run.

Starts ``rosmaster --core -p PORT`` (system Python) and ``python -m
rostui.core.master -p PORT`` (uvloop) on free ports, then for each:

1. registerPublisher/s: client processes, each with several concurrent
   asyncio XmlRpcClient connections, register distinct topics for a fixed time;
2. getSystemState latency (p50/p90) with 2000 topics registered.

Prints both numbers and the rostui/rosmaster ratios.  Not a test.
"""

from __future__ import annotations

import argparse
import asyncio
import multiprocessing as mp
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
sys.path.insert(0, str(REPO))

from rostui.core.xmlrpc import XmlRpcClient, call_sync  # noqa: E402


def free_port() -> int:
    """A free TCP port on 127.0.0.1."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_ready(uri: str, timeout: float = 20.0) -> None:
    """Block until the master at ``uri`` answers getUri."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            call_sync(uri, "getUri", "/bench", timeout=1.0)
            return
        except Exception:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.1)


def start_master(kind: str, port: int, home: str) -> subprocess.Popen:
    """Start a rosmaster or rostui master on ``port``."""
    env = dict(os.environ, ROS_HOME=home, ROS_IP="127.0.0.1",
               ROS_MASTER_URI=f"http://127.0.0.1:{port}/")
    if kind == "rosmaster":
        cmd = ["/usr/bin/python3", shutil.which("rosmaster") or "/usr/bin/rosmaster", "--core", "-p", str(port)]
    else:
        cmd = [sys.executable, "-m", "rostui.core.master", "-p", str(port)]
    proc = subprocess.Popen(cmd, env=env, cwd=str(REPO), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_ready(f"http://127.0.0.1:{port}/")
    return proc


async def _hammer(uri: str, worker: int, conns: int, seconds: float) -> int:
    clients = [XmlRpcClient(uri) for _ in range(conns)]
    deadline = time.monotonic() + seconds
    counts = [0] * conns

    async def loop(i: int, client: XmlRpcClient) -> None:
        caller = f"/bench_w{worker}_c{i}"
        api = f"http://127.0.0.1:{40000 + worker * 100 + i}/"
        n = 0
        while time.monotonic() < deadline:
            await client.call("registerPublisher", caller, f"/bench/w{worker}/c{i}/t{n}", "std_msgs/String", api)
            n += 1
        counts[i] = n

    await asyncio.gather(*(loop(i, c) for i, c in enumerate(clients)))
    for c in clients:
        await c.close()
    return sum(counts)


def _worker(uri: str, worker: int, conns: int, seconds: float, out: "mp.Queue[int]") -> None:
    try:
        import uvloop
        uvloop.install()
    except ImportError:
        pass
    out.put(asyncio.run(_hammer(uri, worker, conns, seconds)))


def bench_register(uri: str, procs: int, conns: int, seconds: float) -> float:
    """registerPublisher calls per second, summed over all client processes."""
    ctx = mp.get_context("fork")
    out: "mp.Queue[int]" = ctx.Queue()
    workers = [ctx.Process(target=_worker, args=(uri, w, conns, seconds, out)) for w in range(procs)]
    start = time.monotonic()
    for w in workers:
        w.start()
    total = sum(out.get() for _ in workers)
    for w in workers:
        w.join()
    return total / max(time.monotonic() - start, seconds)


async def _state_latency(uri: str, topics: int, samples: int) -> tuple[list[float], list[float]]:
    async with XmlRpcClient(uri, timeout=60) as c:
        for i in range(topics):
            await c.call("registerPublisher", "/state_pub", f"/state/t{i}", "std_msgs/String",
                         "http://127.0.0.1:39999/")
            if i % 4 == 0:
                await c.call("registerSubscriber", "/state_sub", f"/state/t{i}", "std_msgs/String",
                             "http://127.0.0.1:39998/")
        times = []
        for _ in range(samples):
            t0 = time.perf_counter()
            await c.call("getSystemState", "/bench")
            times.append(time.perf_counter() - t0)
    return times, await _raw_latency(uri, samples)


async def _raw_latency(uri: str, samples: int) -> list[float]:
    """getSystemState round trips without client-side XML parsing (the server's share)."""
    host, port = uri[len("http://"):].rstrip("/").split(":")
    body = (b"<?xml version='1.0'?><methodCall><methodName>getSystemState</methodName><params>"
            b"<param><value><string>/bench</string></value></param></params></methodCall>")
    request = b"POST / HTTP/1.1\r\nHost: x\r\nContent-Type: text/xml\r\nContent-Length: %d\r\n\r\n" % len(body) + body
    reader, writer = await asyncio.open_connection(host, int(port))
    times = []
    for _ in range(samples):
        t0 = time.perf_counter()
        writer.write(request)
        head = await reader.readuntil(b"\r\n\r\n")
        length = int(head.lower().split(b"content-length:")[1].split(b"\r\n")[0])
        await reader.readexactly(length)
        times.append(time.perf_counter() - t0)
    writer.close()
    return times


def main() -> int:
    """Run both benchmarks against both masters and print the ratios."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0, help="duration of the register phase")
    parser.add_argument("--procs", type=int, default=2, help="client processes")
    parser.add_argument("--conns", type=int, default=8, help="connections per client process")
    parser.add_argument("--topics", type=int, default=2000)
    parser.add_argument("--samples", type=int, default=50)
    args = parser.parse_args()
    if shutil.which("rosmaster") is None:
        print("rosmaster not installed (Debian ros-core); cannot compare", file=sys.stderr)
        return 2
    results: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as home:
        for kind in ("rosmaster", "rostui"):
            port = free_port()
            proc = start_master(kind, port, home)
            uri = f"http://127.0.0.1:{port}/"
            try:
                rate = bench_register(uri, args.procs, args.conns, args.seconds)
                proc.terminate()
                proc.wait(10)
                port = free_port()
                proc = start_master(kind, port, home)
                uri = f"http://127.0.0.1:{port}/"
                lat, raw = asyncio.run(_state_latency(uri, args.topics, args.samples))
            finally:
                proc.terminate()
                try:
                    proc.wait(10)
                except subprocess.TimeoutExpired:
                    proc.kill()
            lat.sort()
            raw.sort()
            results[kind] = {
                "rate": rate,
                "p50": statistics.median(lat) * 1e3,
                "p90": lat[int(len(lat) * 0.9) - 1] * 1e3,
                "raw50": statistics.median(raw) * 1e3,
            }
            r = results[kind]
            print(f"{kind:10s} registerPublisher/s: {r['rate']:9.0f}   getSystemState({args.topics} topics) "
                  f"full call p50 {r['p50']:7.2f} ms p90 {r['p90']:7.2f} ms; "
                  f"server round trip (no client parse) p50 {r['raw50']:7.2f} ms", flush=True)
    ros, ours = results["rosmaster"], results["rostui"]
    print(f"ratio rostui/rosmaster registerPublisher/s: {ours['rate'] / ros['rate']:.2f}x")
    print(f"getSystemState full-call p50: rostui {ros['p50'] / ours['p50']:.2f}x faster than rosmaster")
    print(f"getSystemState server round-trip p50: rostui {ros['raw50'] / ours['raw50']:.2f}x faster than rosmaster")
    return 0


if __name__ == "__main__":
    sys.exit(main())
