#!/usr/bin/env python3
"""The floor of a Python bag player: a loop that only sleeps until each message is due and ``sendfile``s it.

    ROS_MASTER_URI=... perf stat -e task-clock .venv/bin/python bench/bag_play_floor.py BAG [RATE]

Advertises the first topic of an uncompressed ``.bag`` with rostui's node,
waits for one subscriber, reads every message's place in the file first (not
timed apart: the whole process is what ``perf stat`` counts), then plays at
RATE (default 4) with nothing between two messages but ``time.sleep`` and
``os.sendfile`` to the subscriber's socket: no status, no controls, no
queue, no checks. ``rostui bag play`` does all of that too; what it spends
above this script is its own per-message work (bench/README.md, "Bag play
CPU", sixth pass). It prints the messages sent and the CPU of the loop.
"""

from __future__ import annotations

import asyncio
import os
import sys
import time

from rostui.core.bag.files import open_reader
from rostui.core.bag.frames import merged_framed_messages
from rostui.core.bag.precise_sleep import lower_timer_slack
from rostui.core.file_region import FileRegion
from rostui.core.node import AsyncNode
from rostui.tools.bag.player import advertise_connections


async def play_floor(path: str, rate: float) -> None:
    """Advertise, wait for a subscriber, play ``path`` at ``rate`` by sleep and sendfile alone."""
    reader = open_reader(path)
    node = AsyncNode("play_floor", anonymous=True)
    await node.start()
    publisher = next(iter((await advertise_connections(node, reader.summary().connections)).values()))
    while not publisher.impl.links:
        await asyncio.sleep(0.05)
    await asyncio.sleep(0.3)  # as `bag play -d 0.3`
    sock_fd = publisher.impl.links[0].conn.transport.get_extra_info("socket").fileno()
    places = []
    for _conn, t, frame in merged_framed_messages([reader]):
        if not isinstance(frame, FileRegion):
            sys.exit(f"{path}: not an uncompressed bag")
        places.append((t, frame.fd, frame.offset, frame.length))
    lower_timer_slack()
    clock, sleep, sendfile = time.perf_counter, time.sleep, os.sendfile
    cpu = time.process_time()
    start_wall, start_bag = clock(), places[0][0]
    for t, fd, offset, length in places:
        left = start_wall + (t - start_bag) / 1e9 / rate - clock()
        if left > 0:
            sleep(left)
        if sendfile(sock_fd, fd, offset, length) != length:
            sys.exit("the subscriber's socket was full: this floor does not queue")
    print(f"sent={len(places)} loop_cpu_s={time.process_time() - cpu:.3f}", flush=True)
    await asyncio.sleep(0.5)  # the subscriber reads the last messages
    os._exit(0)  # as a player's exit, without a node's shutdown


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    asyncio.run(play_floor(sys.argv[1], float(sys.argv[2]) if len(sys.argv) == 3 else 4.0))
