#!/usr/bin/env python3
"""The no-ROS latency floor: a TCP ping-pong with the threading of a rospy-style ping.

``tcp_floor.py pong PORT`` echoes on 127.0.0.1:PORT; ``tcp_floor.py ping PORT N``
sends from the main thread while a receive thread wakes it through an Event,
as the ROS peers' ``ping`` does, and prints the same lines as they do.  No
ROS library can beat this on the same machine: it has the same process and
thread wake-ups and nothing else.

Two more echoing ends show what an event loop and a message cost on their own
(the venv's Python; the ping's frames are TCPROS frames of a std_msgs/String):
``pong-uvloop PORT`` echoes from a uvloop protocol, as rostui's engine reads
and writes; ``pong-msg PORT`` does the same but decodes each frame with
rostui's std_msgs/String class and sends it encoded again, with nothing else
of a node (no header, no callbacks, no counts, no locks).
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
            print("timing", flush=True)
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


def pong_uvloop(port: int, decode: bool) -> None:
    """Echo every read from a uvloop protocol; with ``decode``, every whole frame as a std_msgs/String."""
    import asyncio
    import struct

    import uvloop

    length = struct.Struct("<I")
    string = None
    if decode:
        from rostui.core.msg import get_message_class
        string = get_message_class("std_msgs/String")

    class Echo(asyncio.Protocol):
        def connection_made(self, transport: asyncio.BaseTransport) -> None:
            self.transport = transport
            transport.get_extra_info("socket").setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

        def data_received(self, data: bytes) -> None:
            if string is not None and length.unpack_from(data)[0] + 4 == len(data):
                payload = string.deserialize(data[4:]).serialize()
                data = length.pack(len(payload)) + payload
            self.transport.write(data)

    async def serve() -> None:
        server = await asyncio.get_running_loop().create_server(Echo, "127.0.0.1", port)
        async with server:
            await server.serve_forever()

    uvloop.run(serve())


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "pong":
        pong(int(sys.argv[2]))
    elif len(sys.argv) == 3 and sys.argv[1] in ("pong-uvloop", "pong-msg"):
        pong_uvloop(int(sys.argv[2]), decode=sys.argv[1] == "pong-msg")
    elif len(sys.argv) == 4 and sys.argv[1] == "ping":
        ping(int(sys.argv[2]), int(sys.argv[3]))
    else:
        sys.exit(__doc__)
