"""LiveSource: /rosout_agg for the console, surviving a master that goes away and comes back.

A node ``/rostui_console_<pid>_<ms>``, kept registered by a
:class:`~rostui.models.master_link.MasterLink`, subscribes to /rosout_agg on
the caller's loop and appends each message, converted to a
:class:`~rostui.core.log.rosout_read.RosoutEntry`, to an inbox the app empties
in batches.  Each time the link registers with a master (a restarted roscore
included) the node subscribes again, so that master's rosout finds us.
"""

from __future__ import annotations

import sys
from typing import Any, Callable

from rostui.core.log.rosout_read import RosoutEntry
from rostui.core.msg import get_message_class
from rostui.core.node.node import AsyncNode
from rostui.models.master_link import LinkedSource, MasterLink, SourceState

__all__ = ["LiveSource", "NODE_NAME", "entry_from_message"]

#: The console's node name (made anonymous, as rqt_console's is).
NODE_NAME = "rostui_console"


def entry_from_message(msg: Any) -> RosoutEntry:
    """A rosgraph_msgs/Log message as a :class:`RosoutEntry`."""
    stamp = msg.header.stamp
    return RosoutEntry(
        stamp=stamp.secs * 1_000_000_000 + stamp.nsecs,
        level=msg.level,
        node=sys.intern(msg.name),
        message=msg.msg,
        file=sys.intern(msg.file),
        line=msg.line,
        function=sys.intern(msg.function),
        topics=tuple(msg.topics),
    )


class LiveSource(LinkedSource):
    """Subscribes to /rosout_agg and keeps doing so across master restarts.

    ``on_state`` is called with a :class:`SourceState` whenever the connection
    state changes; messages collect in :attr:`inbox` until :meth:`take`.
    """

    def __init__(self, master_uri: str, on_state: Callable[[SourceState], None]) -> None:
        self.master_uri = master_uri
        self.inbox: list[RosoutEntry] = []
        self.subscriptions = 0
        self._log_class = get_message_class("rosgraph_msgs/Log")
        self.link = MasterLink(NODE_NAME, master_uri, on_connect=self._subscribe, on_state=on_state)

    def take(self) -> list[RosoutEntry]:
        """The messages received since the last call."""
        batch, self.inbox = self.inbox, []
        return batch

    def _receive(self, msg: Any) -> None:
        self.inbox.append(entry_from_message(msg))

    async def _subscribe(self, node: AsyncNode) -> None:
        """After each registration with a master: subscribed once (the node registers it again itself)."""
        if "/rosout_agg" not in node.subscriptions:
            await node.subscribe("/rosout_agg", self._log_class, self._receive)
        self.subscriptions += 1

    async def run(self) -> None:
        """Stay subscribed across master restarts; runs until :meth:`stop`."""
        await self.link.run()

    async def stop(self) -> None:
        """Unsubscribe and shut the node down."""
        await self.link.stop()
