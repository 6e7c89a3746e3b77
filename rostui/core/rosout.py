"""The rosout node: subscribes to /rosout and relays every message to /rosout_agg."""

from __future__ import annotations

from typing import Any

from rostui.core.msg import get_message_class
from rostui.core.node.node import AsyncNode, Publisher


class RosoutNode:
    """The ``/rosout`` aggregator, run on the caller's loop (inside ``rostui core``)."""

    def __init__(self, master_uri: str) -> None:
        self.node = AsyncNode("rosout", argv=[], master_uri=master_uri)
        self._agg: Publisher | None = None
        self.relayed = 0

    async def start(self) -> None:
        """Register /rosout_agg (publisher) and /rosout (subscriber)."""
        log_class = get_message_class("rosgraph_msgs/Log")
        await self.node.start()
        self._agg = await self.node.advertise("/rosout_agg", log_class, queue_size=0)
        await self.node.subscribe("/rosout", log_class, self._relay, queue_size=0)

    def _relay(self, msg: Any) -> None:
        assert self._agg is not None
        self._agg.publish(msg)
        self.relayed += 1

    async def stop(self) -> None:
        """Unregister and close."""
        await self.node.shutdown("rostui core stopping")
