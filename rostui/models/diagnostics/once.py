"""One look at the robot's diagnostics for a script: ``rostui diagnostics --once``.

With an aggregator on the master (a publisher of /diagnostics_agg) its next message is the whole tree. Without
one, the flat topic's publishers each speak about once a second, so what came within :data:`FLAT_SETTLE`
seconds of the first message is the picture.
"""

from __future__ import annotations

import asyncio
import time

from rostui.models.master_link import MASTER_ERRORS

from .source import DiagnosticsSource
from .store import AGGREGATED, FLAT

__all__ = ["read_once", "FLAT_SETTLE", "NothingHeard"]

#: Seconds the flat topic is listened to after its first message.
FLAT_SETTLE = 1.5


class NothingHeard(Exception):
    """No diagnostics came within the wait; the message says which topic was awaited."""


def _publishes(system_state: list, topic: str) -> bool:
    publishers = system_state[0] if system_state else []
    return any(name == topic and nodes for name, nodes in publishers)


async def read_once(source: DiagnosticsSource, wait: float) -> str:
    """Run ``source`` until one picture is complete; the topic it came from (:data:`AGGREGATED` or :data:`FLAT`,
    or the one topic the source listens to).

    :class:`NothingHeard` when nothing came within ``wait`` seconds.
    """
    if len(source.topics) == 1:
        return await _one_topic(source, source.topics[0], wait)
    task = asyncio.create_task(source.run())
    try:
        deadline = time.monotonic() + wait
        first_flat: float | None = None
        aggregator = False
        asked_at = 0.0
        while time.monotonic() < deadline:
            if task.done():
                task.result()
            if source.store.has_aggregator:
                return AGGREGATED
            node = source.node
            if node is not None and time.monotonic() - asked_at > 0.5:
                asked_at = time.monotonic()
                try:
                    aggregator = _publishes(await asyncio.wait_for(node.master_call("getSystemState"), 3.0),
                                            AGGREGATED)
                except MASTER_ERRORS:  # the link judges the master; ask again later
                    aggregator = False
            if source.store.flat.messages and first_flat is None:
                first_flat = time.monotonic()
            if first_flat is not None and not aggregator and time.monotonic() - first_flat >= FLAT_SETTLE:
                return FLAT
            await asyncio.sleep(0.02)
        if source.store.flat.messages:
            return FLAT
        awaited = AGGREGATED if aggregator else f"{AGGREGATED} or {FLAT}"
        raise NothingHeard(f"no diagnostics on {awaited} within {wait:g} s")
    finally:
        await _end(source, task)


async def _one_topic(source: DiagnosticsSource, topic: str, wait: float) -> str:
    """The first message of ``topic`` (/diagnostics: what came within :data:`FLAT_SETTLE` s of it)."""
    task = asyncio.create_task(source.run())
    table = source.store.table(topic)
    try:
        deadline = time.monotonic() + wait
        while time.monotonic() < deadline and not table.messages:
            if task.done():
                task.result()
            await asyncio.sleep(0.02)
        if not table.messages:
            raise NothingHeard(f"no diagnostics on {topic} within {wait:g} s")
        if topic == FLAT:
            await asyncio.sleep(FLAT_SETTLE)
        return topic
    finally:
        await _end(source, task)


async def _end(source: DiagnosticsSource, task: asyncio.Task[None]) -> None:
    await source.stop()
    task.cancel()
    try:
        await task
    except (asyncio.CancelledError, Exception):  # the source's own end; the picture is taken
        pass
