"""Shared by the console tests: a deterministic rosout.log and small pilot helpers.

The sample log is what the book's chapter 4 shows: ``count_and_log``
counting with messages at every level (DEBUG each count, INFO every 3rd,
WARN every 5th, ERROR every 10th, FATAL every 20th), plus turtlesim's start
and a wall warning, and a two-line message from a listener.  Stamps are
fixed, so screens drawn from it are the same on every run (with TZ=UTC).
"""

from __future__ import annotations

import asyncio
from pathlib import Path

from rostui.apps.console.app import ConsoleApp
from rostui.core.log import RosoutLogWriter
from rostui.core.node.node import AsyncNode

DEADLINE = 30.0

#: Seconds of the first sample message (2023-11-14 22:13:20 UTC).
T0 = 1_700_000_000

COUNT_TOPICS = ["/rosout"]
TURTLESIM_TOPICS = ["/rosout", "/turtle1/color_sensor", "/turtle1/pose"]


def write_sample_log(path: Path, count: int = 20) -> Path:
    """Write the sample rosout.log (``count`` counts of count_and_log) to ``path``."""
    writer = RosoutLogWriter(path, clock=lambda: T0 * 1_000_000_000)
    ms = 0

    def log(level: int, node: str, file: str, function: str, line: int, topics: list[str], text: str) -> None:
        nonlocal ms
        ms += 137
        writer.write(T0 + ms // 1000, (ms % 1000) * 1_000_000, level, node, file, line, function, topics, text)

    log(2, "/turtlesim", "turtle_frame.cpp", "TurtleFrame::TurtleFrame", 66, TURTLESIM_TOPICS,
        "Starting turtlesim with node name /turtlesim")
    log(2, "/turtlesim", "turtle_frame.cpp", "TurtleFrame::spawnTurtle", 162, TURTLESIM_TOPICS,
        "Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]")
    for i in range(1, count + 1):
        log(1, "/count_and_log", "count.cpp", "main", 14, COUNT_TOPICS, f"Counted to {i}")
        if i % 3 == 0:
            log(2, "/count_and_log", "count.cpp", "main", 16, COUNT_TOPICS, f"{i} is divisible by 3.")
        if i % 5 == 0:
            log(4, "/count_and_log", "count.cpp", "main", 19, COUNT_TOPICS, f"{i} is divisible by 5.")
        if i % 10 == 0:
            log(8, "/count_and_log", "count.cpp", "main", 22, COUNT_TOPICS, f"{i} is divisible by 10.")
        if i % 20 == 0:
            log(16, "/count_and_log", "count.cpp", "main", 25, COUNT_TOPICS, f"{i} is divisible by 20.")
        if i == 7:
            log(4, "/turtlesim", "turtle.cpp", "Turtle::update", 201, TURTLESIM_TOPICS,
                "Oh no! I hit the wall! (Clamping from [x=11.112, y=5.544])")
        if i == 12:
            log(8, "/listener", "listener.py", "callback", 9, ["/chatter", "/rosout"],
                "lost the talker\nlast heard 3.2 s ago")
    writer.close()
    return path


async def log_until_seen(app: ConsoleApp, node: AsyncNode, text: str) -> None:
    """Log ``text`` at INFO until the app shows it (rosout connects to a new node asynchronously)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + DEADLINE
    while not any(e.message == text for _, e in app.model.shown()):
        assert loop.time() < deadline, f"{text!r} never arrived"
        node.log.info(text)
        await asyncio.sleep(0.2)
