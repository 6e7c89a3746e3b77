"""The rosout node: relays /rosout to /rosout_agg and writes the run's rosout.log."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rostui.core.log import RosoutLogWriter, run_log_dir, update_latest_link
from rostui.core.msg import get_message_class
from rostui.core.node.node import AsyncNode, Publisher


class RosoutNode:
    """The ``/rosout`` aggregator, run on the caller's loop (inside ``rostui core``).

    Every rosgraph_msgs/Log received on /rosout is republished on /rosout_agg
    and appended to ``<log dir>/<run_id>/rosout.log``; ``<log dir>/latest``
    points at that run.
    """

    def __init__(self, master_uri: str, run_id: str) -> None:
        self.node = AsyncNode("rosout", argv=[], master_uri=master_uri)
        self.run_dir: Path = run_log_dir(run_id)
        self.writer = RosoutLogWriter(self.run_dir / "rosout.log")
        self._agg: Publisher | None = None
        self.relayed = 0

    async def start(self) -> None:
        """Open rosout.log, register /rosout_agg (publisher) and /rosout (subscriber)."""
        update_latest_link(self.run_dir)
        self.writer.open()
        log_class = get_message_class("rosgraph_msgs/Log")
        await self.node.start(publish_rosout=False)
        self._agg = await self.node.advertise("/rosout_agg", log_class, queue_size=0)
        await self.node.subscribe("/rosout", log_class, self._relay, queue_size=0)

    def _relay(self, msg: Any) -> None:
        assert self._agg is not None
        self._agg.publish(msg)
        self.writer.write_message(msg)
        self.relayed += 1

    async def stop(self) -> None:
        """Unregister, close the node and the file."""
        await self.node.shutdown("rostui core stopping")
        self.writer.close()
