"""Helpers for the bag view and bag play key tests: a counts bag and a subscriber process that prints what it gets.

The subscriber is a separate process (a real node over TCPROS, like any
user's), started with ``rostui.client``; it prints ``connected TOPIC`` once a
publisher connects on each topic, then ``TOPIC VALUE`` per message.
"""

from __future__ import annotations

import asyncio
import subprocess
import sys
from pathlib import Path
from typing import Any, Awaitable, Callable

from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection
from rostui.core.msg import get_message_class

from conftest import REPO, stop_process, until, wait_until

Int32 = get_message_class("std_msgs/Int32")

#: A pilot scenario: what a test does with the running app.
Scenario = Callable[[Any, Any], Awaitable[None]]
T0 = 1_700_000_000_000_000_000
STEP_NS = 10_000_000

COUNTER = r'''
import sys, time
from rostui import client as ros
ros.init_node("bag_counter", anonymous=True)
Int32 = ros.msg("std_msgs/Int32")

def printer(topic):
    def show(m):
        print(topic, m.data, flush=True)
    return show

subs = [(t, ros.Subscriber(t, Int32, printer(t), queue_size=1000)) for t in sys.argv[1:]]
print("ready", flush=True)
connected = set()
while not ros.is_shutdown():
    for topic, sub in subs:
        if topic not in connected and sub.get_num_connections() > 0:
            connected.add(topic)
            print("connected", topic, flush=True)
    time.sleep(0.02)
'''


def write_counts(path: Path, count: int = 100, flush_every: int = 0, compression: str = "none") -> Path:
    """``/count`` 0..count-1 and ``/odd`` (the odd ones), 10 ms apart, from T0; with ``flush_every`` a chunk
    ends after every that many counts (as the recorder's timer leaves them)."""
    writer = open_writer(str(path), compression)
    writer.add_connection(Connection(0, "/count", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/c"))
    writer.add_connection(Connection(1, "/odd", "std_msgs/Int32", Int32._md5sum, Int32._full_text, "/o"))
    for i in range(count):
        writer.write(0, T0 + i * STEP_NS, Int32(data=i).serialize())
        if i % 2:
            writer.write(1, T0 + i * STEP_NS, Int32(data=i).serialize())
        if flush_every and i % flush_every == flush_every - 1:
            writer.flush()
    writer.close()
    return path


class Counter:
    """A subscriber process on ``topics`` (std_msgs/Int32) printing each message it receives."""

    def __init__(self, env: dict[str, str], tmp: Path, *topics: str) -> None:
        script = tmp / "bag_counter.py"
        script.write_text(COUNTER)
        self.out = tmp / "bag_counter.out"
        self.topics = topics
        with self.out.open("w") as out:
            self.proc = subprocess.Popen([sys.executable, str(script), *topics], env=env, cwd=REPO,
                                         stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT)
        wait_until(lambda: "ready" in self.lines(), "the counter node to subscribe")

    def lines(self) -> list[str]:
        """What it printed so far."""
        return self.out.read_text(errors="replace").splitlines()

    def connected(self) -> bool:
        """True once a publisher is connected on every topic."""
        lines = self.lines()
        return all(f"connected {t}" in lines for t in self.topics)

    def received(self) -> list[tuple[str, int]]:
        """``(topic, value)`` of every message, in arrival order."""
        got = []
        for line in self.lines():
            topic, _, value = line.partition(" ")
            if topic in self.topics and value.lstrip("-").isdigit():
                got.append((topic, int(value)))
        return got

    def values(self, topic: str) -> list[int]:
        """Values received on ``topic``."""
        return [v for t, v in self.received() if t == topic]

    def close(self) -> None:
        """Stop the process."""
        stop_process(self.proc)


def run_pilot(app: Any, scenario: Scenario, size: tuple[int, int] = (120, 30)) -> None:
    """Run ``app`` headless and play ``scenario``; then quit as q does."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            await scenario(pilot, app)
            await app.action_quit()

    asyncio.run(main())


async def inspector_open(app: Any, pilot: Any) -> None:
    """Wait for bag view to have read its bags, then show its inspector (i) if it is hidden."""
    await until(lambda: app.index is not None and app.transport is not None, "the bag read")
    if not app.inspector.display:
        await pilot.press("i")
