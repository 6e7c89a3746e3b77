"""Helpers for the monitor tests: steady publishers as real processes, and the master's view of subscriptions.

Publishers are the real `rostui topic pub -r RATE` command (one process per
topic), so messages reach the monitor over TCPROS as from any other node.
"""

from __future__ import annotations

import asyncio
import subprocess
import sys
import xmlrpc.client
from pathlib import Path
from typing import Awaitable, Callable, Iterator, Sequence

from textual.pilot import Pilot

from rostui.apps.monitor.app import MonitorApp

from conftest import rostui_cmd, stop_process

__all__ = ["Publisher", "ManyTopics", "start_publishers", "stop_all", "subscribers_on_master", "master_subscriptions"]


class Publisher:
    """`rostui topic pub -r RATE TOPIC TYPE YAML` running as a process (output to a file)."""

    def __init__(self, env: dict[str, str], tmp_path: Path, topic: str, type_name: str, yaml_text: str,
                 rate: float) -> None:
        self.topic = topic
        log = tmp_path / f"pub{topic.replace('/', '_')}.log"
        self._out = log.open("w")
        self.proc = subprocess.Popen(rostui_cmd("topic", "pub", "-r", f"{rate:g}", topic, type_name, yaml_text),
                                     env=env, stdout=self._out, stderr=subprocess.STDOUT)

    def stop(self) -> None:
        """SIGINT the publisher (it unregisters) and wait for it."""
        stop_process(self.proc)
        self._out.close()

    def kill(self) -> None:
        """SIGKILL the publisher: it dies without unregistering from the master."""
        self.proc.kill()
        self.proc.wait()
        self._out.close()


def start_publishers(env: dict[str, str], tmp_path: Path, specs: Sequence[tuple[str, str, str, float]]) \
        -> list[Publisher]:
    """One publisher process per ``(topic, type, yaml, rate)``."""
    return [Publisher(env, tmp_path, *spec) for spec in specs]


def stop_all(publishers: Iterator[Publisher] | Sequence[Publisher]) -> None:
    """Stop every publisher still running."""
    for pub in publishers:
        if pub.proc.poll() is None:
            pub.stop()


def master_subscriptions(env: dict[str, str], node_prefix: str = "/rostui_monitor") -> set[str]:
    """Topics the master lists a subscriber ``node_prefix...`` for (getSystemState, as any ROS tool sees it)."""
    master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
    code, _, (_, subs, _) = master.getSystemState("/monitor_test")
    assert code == 1
    return {topic for topic, nodes in subs if any(n.startswith(node_prefix) for n in nodes)}


def subscribers_on_master(env: dict[str, str]) -> dict[str, list[str]]:
    """Every topic's subscriber nodes as the master lists them."""
    master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
    _, _, (_, subs, _) = master.getSystemState("/monitor_test")
    return {topic: list(nodes) for topic, nodes in subs}


class ManyTopics:
    """One process publishing std_msgs/String on ``PREFIX/t000`` ... at ``rate`` Hz each (this module as a script)."""

    def __init__(self, env: dict[str, str], tmp_path: Path, prefix: str, count: int, rate: float) -> None:
        self.names = [f"{prefix}/t{i:03d}" for i in range(count)]
        self._out = (tmp_path / f"many{prefix.replace('/', '_')}.log").open("w")
        self.proc = subprocess.Popen([sys.executable, str(Path(__file__)), prefix, str(count), f"{rate:g}"], env=env,
                                     stdout=self._out, stderr=subprocess.STDOUT)

    def stop(self) -> None:
        """SIGINT the process (it unregisters) and wait for it."""
        stop_process(self.proc)
        self._out.close()


async def _publish_many(prefix: str, count: int, rate: float) -> None:
    import asyncio
    import signal

    from rostui.core.msg import get_message_class
    from rostui.core.node import AsyncNode

    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    node = await AsyncNode("many_topics", anonymous=True, argv=[]).start()
    string = get_message_class("std_msgs/String")
    pubs = [await node.advertise(f"{prefix}/t{i:03d}", string, queue_size=10) for i in range(count)]
    msgs = [string(data=f"t{i:03d}") for i in range(count)]
    print("advertised", flush=True)
    period = 1.0 / rate
    due = loop.time()
    while not stop.is_set():
        for pub, msg in zip(pubs, msgs):
            pub.publish(msg)
        due += period
        try:
            await asyncio.wait_for(stop.wait(), max(0.0, due - loop.time()))
        except asyncio.TimeoutError:
            pass
    await node.shutdown("done")


if __name__ == "__main__":
    import asyncio

    asyncio.run(_publish_many(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))


#: A pilot scenario played against a running monitor.
Scenario = Callable[[Pilot, MonitorApp], Awaitable[None]]


def run_monitor(app: MonitorApp, scenario: Scenario, size: tuple[int, int] = (120, 32)) -> None:
    """Run ``app`` headless and play ``scenario``; the app quits with q at the end."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            await scenario(pilot, app)
            await pilot.press("q")

    asyncio.run(main())
