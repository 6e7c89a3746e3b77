#!/usr/bin/env python3
"""The no-ROS latency floor: a TCP ping-pong with the threading of a rospy-style ping.

``tcp_floor.py pong PORT`` echoes on 127.0.0.1:PORT; ``tcp_floor.py ping PORT N``
sends from the main thread while a receive thread wakes it through an Event,
as the ROS peers' ``ping`` does, and prints the same line as they do.  No
ROS library can beat this on the same machine: it has the same process and
thread wake-ups and nothing else.
"""

import socket
import sys
import threading
import time


def pong(port: int) -> None:
    """Echo every chunk back until the peer closes."""
    server = socket.create_server(("127.0.0.1", port))
    conn, _ = server.accept()
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    while True:
        data = conn.recv(65536)
        if not data:
            return
        conn.sendall(data)


def ping(port: int, n: int) -> None:
    """Time n round trips after a warm-up; print percentiles like the ROS peers."""
    conn = socket.create_connection(("127.0.0.1", port))
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    got = threading.Event()

    def receive() -> None:
        while conn.recv(65536):
            got.set()

    threading.Thread(target=receive, daemon=True).start()
    warm = max(100, n // 10)
    rtt = []
    cpu0 = 0.0
    for i in range(warm + n):
        if i == warm:
            cpu0 = time.process_time()
        got.clear()
        t0 = time.perf_counter()
        conn.sendall(b"\x0c\x00\x00\x00\x08\x00\x00\x00ping %03d" % (i % 1000))
        got.wait(5.0)
        if i >= warm:
            rtt.append((time.perf_counter() - t0) * 1e6)
    rtt.sort()
    k = len(rtt)
    cpu = (time.process_time() - cpu0) / n * 1e6
    print("n=%d p50_us=%.1f p99_us=%.1f mean_us=%.1f min_us=%.1f max_us=%.1f cpu_us=%.1f"
          % (k, rtt[k // 2], rtt[min(k - 1, int(0.99 * k))], sum(rtt) / k, rtt[0], rtt[-1], cpu), flush=True)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "pong":
        pong(int(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "ping":
        ping(int(sys.argv[2]), int(sys.argv[3]))
    else:
        sys.exit(__doc__)
