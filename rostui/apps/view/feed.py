"""TopicFeed: one topic's subscription that keeps only the newest message (frames are dropped, never queued)."""

from __future__ import annotations

import time
from collections import deque
from typing import Any, Callable

from rostui.core.node import AnyMsg, AsyncNode, Subscriber
from rostui.core.node.header_check import HeaderCheck

__all__ = ["TopicFeed", "Rate"]


class Rate:
    """Events per second over the last ``window`` seconds (received frames, drawn frames)."""

    def __init__(self, window: float = 2.0) -> None:
        self.window = window
        self.count = 0
        self._times: deque[float] = deque()

    def add(self, now: float) -> None:
        """Count one event at ``now``."""
        self.count += 1
        self._times.append(now)
        while self._times and self._times[0] < now - self.window:
            self._times.popleft()

    def per_second(self, now: float) -> float:
        """Events per second lately (0 once none came for ``window`` seconds)."""
        while self._times and self._times[0] < now - self.window:
            self._times.popleft()
        if len(self._times) < 2:
            return 0.0
        span = max(self._times[-1] - self._times[0], now - self._times[0], 1e-9)
        return (len(self._times) - 1) / span if span < self.window else len(self._times) / self.window


#: Most bytes of messages waiting for the screen with :attr:`TopicFeed.keep_every`.
KEEP_BYTES = 64 << 20


class TopicFeed:
    """``topic`` subscribed raw (AnyMsg) on a node; :meth:`take` hands over the newest message once.

    ``on_arrival()`` runs (on the node's loop) after each message; the owner
    then takes the newest when it is ready to draw, so a slow screen skips
    frames instead of falling behind.  With :attr:`check` set before
    :meth:`attach` (:mod:`rostui.core.node.header_check`), only the publishers
    it accepts are heard: a liar's frames never take an honest one's place.
    """

    def __init__(self, topic: str, on_arrival: Callable[[], None], clock: Callable[[], float] = time.time) -> None:
        self.topic = topic
        self.on_arrival = on_arrival
        self.clock = clock
        self.check: HeaderCheck | None = None
        """Which publishers are heard (None: every one); used by the next :meth:`attach`."""
        self.received = Rate()
        self.node: AsyncNode | None = None
        self._handle: Subscriber | None = None
        self._newest: AnyMsg | None = None
        self._arrived = 0.0
        self.dropped = 0
        """Messages replaced by a newer one before they were taken (never drawn)."""
        self.keep_every = 0
        """Above 0: up to this many messages (and :data:`KEEP_BYTES`) wait to be taken, in order (markers: each
        adds or deletes some); the oldest is dropped past it, and counted in :attr:`dropped`."""
        self._queue: deque[tuple[AnyMsg, float]] = deque()
        self._queue_bytes = 0

    @property
    def subscribed(self) -> bool:
        """True while subscribed."""
        return self._handle is not None

    async def attach(self, node: AsyncNode | None) -> None:
        """Be subscribed on ``node`` (None: on no node); a different node than before subscribes again."""
        if node is self.node and (node is None or self._handle is not None):
            return
        await self.detach()
        self.node = node
        if node is not None:
            self._handle = await node.subscribe(self.topic, AnyMsg, self._on_message, check=self.check)

    async def detach(self) -> None:
        """Unsubscribe (the node may be gone already)."""
        handle, self._handle = self._handle, None
        node, self.node = self.node, None
        if handle is not None and node is not None and not node.is_shutdown:
            try:
                await handle.unregister()
            except Exception:  # the master or the node went away meanwhile: nothing left to undo
                pass

    def _on_message(self, raw: Any) -> None:
        self._arrived = self.clock()
        self.received.add(self._arrived)
        if self.keep_every > 0:
            size = len(getattr(raw, "_buff", b""))
            while self._queue and (len(self._queue) >= self.keep_every or self._queue_bytes + size > KEEP_BYTES):
                old, _ = self._queue.popleft()
                self._queue_bytes -= len(getattr(old, "_buff", b""))
                self.dropped += 1
            self._queue.append((raw, self._arrived))
            self._queue_bytes += size
        else:
            if self._newest is not None:
                self.dropped += 1
            self._newest = raw
        self.on_arrival()

    @property
    def waiting(self) -> bool:
        """True when a message came that was not taken yet."""
        return self._newest is not None or bool(self._queue)

    def take(self) -> tuple[Any, float] | None:
        """The newest message not taken yet and its arrival time (wall seconds), or None (with
        :attr:`keep_every`: the oldest waiting)."""
        if self._queue:
            taken = self._queue.popleft()
            self._queue_bytes -= len(getattr(taken[0], "_buff", b""))
            return taken
        raw, self._newest = self._newest, None
        return (raw, self._arrived) if raw is not None else None
