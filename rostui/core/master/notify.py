"""Asynchronous master -> node notifications (publisherUpdate, paramUpdate, shutdown).

Each target node URI gets its own queue, drained in order by one task over one
persistent connection, so the API call that caused a notification never waits
for it, and a slow node only delays itself.  A pending publisherUpdate for a
topic (or paramUpdate for a key) that has not been sent yet is replaced by a
newer one, since only the latest state matters.  When a target cannot be
reached, what is queued for it is dropped and logged at debug level.
"""

from __future__ import annotations

import asyncio
import collections
import logging
from typing import Any, Callable

from ..xmlrpc import XmlRpcClient, XmlRpcError

_log = logging.getLogger("rostui.master.notify")

MASTER_CALLER_ID = "/master"

ResultCallback = Callable[[Any], None]


class _Item:
    __slots__ = ("key", "method", "args", "on_result")

    def __init__(self, key: tuple[str, str] | None, method: str, args: tuple[Any, ...],
                 on_result: ResultCallback | None) -> None:
        self.key = key
        self.method = method
        self.args = args
        self.on_result = on_result


class _Target:
    __slots__ = ("api", "queue", "pending", "task")

    def __init__(self, api: str) -> None:
        self.api = api
        self.queue: collections.deque[_Item] = collections.deque()
        self.pending: dict[tuple[str, str], _Item] = {}
        self.task: asyncio.Task[None] | None = None


class Notifier:
    """Queues XML-RPC notifications to nodes and sends them in the background."""

    def __init__(self, timeout: float = 10.0) -> None:
        self.timeout = timeout
        self._targets: dict[str, _Target] = {}
        self._closed = False

    def publisher_update(self, api: str, topic: str, publishers: list[str]) -> None:
        """Tell the node at ``api`` the current publisher URIs of ``topic``."""
        self._enqueue(api, ("pub", topic), "publisherUpdate", (MASTER_CALLER_ID, topic, publishers))

    def param_update(self, api: str, key: str, value: Any,
                     on_result: ResultCallback | None = None) -> None:
        """Tell the node at ``api`` that parameter ``key`` is now ``value``."""
        self._enqueue(api, ("param", key), "paramUpdate", (MASTER_CALLER_ID, key, value), on_result)

    def shutdown_node(self, api: str, reason: str) -> None:
        """Ask the node at ``api`` to shut down."""
        self._enqueue(api, None, "shutdown", (MASTER_CALLER_ID, reason))

    def _enqueue(self, api: str, key: tuple[str, str] | None, method: str,
                 args: tuple[Any, ...], on_result: ResultCallback | None = None) -> None:
        if self._closed or not api.startswith("http"):
            return
        target = self._targets.get(api)
        if target is None:
            target = self._targets[api] = _Target(api)
        if key is not None:
            pending = target.pending.get(key)
            if pending is not None:
                pending.args = args
                pending.on_result = on_result
                return
        item = _Item(key, method, args, on_result)
        if key is not None:
            target.pending[key] = item
        target.queue.append(item)
        if target.task is None:
            target.task = asyncio.get_running_loop().create_task(self._drain(target))

    async def _drain(self, target: _Target) -> None:
        client = XmlRpcClient(target.api, timeout=self.timeout)
        try:
            while target.queue:
                item = target.queue.popleft()
                if item.key is not None and target.pending.get(item.key) is item:
                    del target.pending[item.key]
                try:
                    result = await client.call(item.method, *item.args)
                except XmlRpcError as exc:
                    dropped = len(target.queue)
                    target.queue.clear()
                    target.pending.clear()
                    _log.debug("%s to %s failed (%s); dropped %d more queued",
                               item.method, target.api, exc, dropped)
                    continue
                except Exception:  # a bug in a callback must not kill the drain loop
                    _log.debug("%s to %s failed", item.method, target.api, exc_info=True)
                    continue
                if item.on_result is not None:
                    try:
                        item.on_result(result)
                    except Exception:
                        _log.debug("notification callback failed", exc_info=True)
        finally:
            if self._targets.get(target.api) is target:
                del self._targets[target.api]
            target.task = None
            await client.close()

    async def flush(self, timeout: float | None = None) -> None:
        """Wait until everything queued so far has been sent (or dropped)."""
        tasks = [t.task for t in self._targets.values() if t.task is not None]
        if tasks:
            await asyncio.wait(tasks, timeout=timeout)

    async def close(self) -> None:
        """Cancel every pending notification."""
        self._closed = True
        tasks = [t.task for t in self._targets.values() if t.task is not None]
        for task in tasks:
            task.cancel()
        if tasks:
            await asyncio.gather(*tasks, return_exceptions=True)
        self._targets.clear()
