#!/usr/bin/env python3
"""What each part of a bag player's path costs a message, with warm caches: no master, no subscriber, no sleep.

    .venv/bin/python bench/bag_play_parts.py BAG [REPEATS]

The real Transport, Player, Publication and OutgoingLink play an uncompressed
``.bag`` with every message due at once (a rate of 1e9) into one end of a
socket pair whose other end ``cat`` drains. Printed, in µs a message (the best
of REPEATS): ``sendfile`` alone of every message's region, the publish chain
(the transport's sender of each connection down to ``sendfile``), the stream (time order, each
record's head read, its frame made) and the whole play. In a real play each
part runs after a wake-up, with cold caches, and costs more (bench/README.md,
"Bag play CPU", eighth pass).
"""

from __future__ import annotations

import asyncio
import os
import socket
import subprocess
import sys
import threading
import time
import types
from collections.abc import Callable

from rostui.core.bag.files import open_reader
from rostui.core.bag.frames import merged_framed_messages
from rostui.core.file_region import FileRegion
from rostui.core.node.topics import OutgoingLink, Publication
from rostui.tools.bag.player import Player, PlayOptions


def best(repeats: int, run: Callable[[], int]) -> float:
    """The least CPU a message over ``repeats`` runs of ``run`` (which returns its messages)."""
    costs = []
    for _ in range(repeats):
        start = time.process_time()
        count = run()
        costs.append((time.process_time() - start) / count * 1e6)
    return min(costs)


def main(path: str, repeats: int) -> None:
    """Print each part's µs a message for the bag at ``path``."""
    ours, theirs = socket.socketpair()
    drain = subprocess.Popen(["cat"], stdin=theirs.fileno(), stdout=subprocess.DEVNULL)
    theirs.close()
    transport = types.SimpleNamespace(is_closing=lambda: False, get_write_buffer_size=lambda: 0,
                                      get_extra_info=lambda key: ours if key == "socket" else None)
    conn = types.SimpleNamespace(transport=transport, write=ours.sendall)
    loop = asyncio.new_event_loop()
    node = types.SimpleNamespace(loop_thread_id=threading.get_ident(), namespace="/", name="/play", loop=loop,
                                 next_connection_id=lambda: 1)
    reader = open_reader(path)
    items = list(merged_framed_messages([reader]))
    if not all(isinstance(frame, FileRegion) for _c, _t, frame in items):
        sys.exit(f"{path}: not an uncompressed bag")

    def player() -> Player:
        made = Player(node, PlayOptions(files=[path], rate=1e9), [reader])
        for c in reader.summary().connections:
            pub = Publication(node, c.topic, None, queue_size=100, latch=False, tcp_nodelay=True)  # type: ignore[arg-type]
            pub.links = (OutgoingLink(pub, conn, {"callerid": "/drain"}),)  # type: ignore[arg-type]
            made.publishers[(c.topic, c.md5sum)] = types.SimpleNamespace(impl=pub)
        return made

    def sendfile_alone() -> int:
        fd = ours.fileno()
        for _c, _t, region in items:
            os.sendfile(fd, region.fd, region.offset, region.length)  # type: ignore[union-attr]
        return len(items)

    def chain() -> int:
        made = player()  # quiet, as the benchmark plays: the transport calls each connection's frame sender
        senders = {id(c): made._frame_sender(c) for c, _t, _frame in items}
        for c, _t, frame in items:
            senders[id(c)](frame)
        return len(items)

    def stream() -> int:
        return sum(1 for _ in merged_framed_messages([reader]))

    def whole() -> int:
        return loop.run_until_complete(player().transport.run())

    print(f"µs a message, best of {repeats}: sendfile alone {best(repeats, sendfile_alone):.2f}, "
          f"publish chain {best(repeats, chain):.2f}, stream {best(repeats, stream):.2f}, "
          f"whole play {best(repeats, whole):.2f}", flush=True)
    drain.kill()  # the links hold copies of the socket: cat would never see its end
    drain.wait()


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) == 3 else 5)
