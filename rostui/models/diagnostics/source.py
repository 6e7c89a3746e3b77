"""DiagnosticsSource: /diagnostics_agg and /diagnostics into a :class:`DiagnosticsStore`, across master restarts.

A node ``/rostui_diagnostics_<pid>_<ms>``, kept registered by a :class:`~rostui.models.master_link.MasterLink`,
subscribes to both topics as diagnostic_msgs/DiagnosticArray (a publisher of another type or md5sum is refused,
as ROS refuses it) and files each message under its topic. Which one a screen shows is its choice: the
aggregator's tree once it has spoken, the flat topic before.
"""

from __future__ import annotations

import time
from typing import Any, Callable

from rostui.core.msg import get_message_class
from rostui.core.node.node import AsyncNode
from rostui.models.master_link import LinkedSource, MasterLink, SourceState

from .store import AGGREGATED, FLAT, DiagnosticsStore

__all__ = ["DiagnosticsSource", "NODE_NAME", "ARRAY_TYPE"]

#: The node's name (made anonymous).
NODE_NAME = "rostui_diagnostics"
ARRAY_TYPE = "diagnostic_msgs/DiagnosticArray"


class DiagnosticsSource(LinkedSource):
    """Both diagnostics topics of the master at ``master_uri`` in :attr:`store`; run :meth:`run` as a task.

    ``topics`` are those listened to (default both). ``on_change()`` runs after each message is filed (on the caller's loop); ``clock`` stamps arrivals (wall
    seconds; tests pass their own).
    """

    def __init__(self, master_uri: str, *, topics: tuple[str, ...] | None = None, store: DiagnosticsStore | None = None,
                 on_change: Callable[[], None] | None = None,
                 on_state: Callable[[SourceState], None] | None = None,
                 clock: Callable[[], float] = time.time) -> None:
        self.topics = topics or (AGGREGATED, FLAT)
        self.store = store if store is not None else DiagnosticsStore()
        self.clock = clock
        self.on_change = on_change or (lambda: None)
        self.link = MasterLink(NODE_NAME, master_uri, on_connect=self._subscribe, on_state=on_state)

    async def _subscribe(self, node: AsyncNode) -> None:
        """After each registration with a master: subscribed once (the node registers them again itself)."""
        array = get_message_class(ARRAY_TYPE)
        for topic in self.topics:
            if topic not in node.subscriptions:
                await node.subscribe(topic, array, self._receive, callback_args=topic)

    def _receive(self, msg: Any, topic: str) -> None:
        self.store.take(topic, msg.status, self.clock(), msg.header.stamp.to_sec())
        self.on_change()

    async def run(self) -> None:
        """Stay subscribed across master restarts; runs until :meth:`stop`."""
        await self.link.run()

    async def stop(self) -> None:
        """Unsubscribe and shut the node down."""
        await self.link.stop()
