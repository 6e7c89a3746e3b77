"""LiveSource: /rosout_agg for the console, surviving a master that goes away and comes back.

A node ``/rostui_console_<pid>_<ms>`` subscribes to /rosout_agg on the
caller's loop and appends each message, converted to a
:class:`~rostui.core.log.rosout_read.RosoutEntry`, to an inbox the app empties
in batches.  Once a second it asks the master for its pid: no answer means
the master is gone (the node is dropped and the source waits for one to
answer); a different pid means a new master (the node registers again, so a
restarted roscore's rosout finds us).
"""

from __future__ import annotations

import asyncio
import sys
from typing import Any, Callable

from rostui.core.log.rosout_read import RosoutEntry
from rostui.core.msg import get_message_class
from rostui.core.node.node import AsyncNode
from rostui.models.master_link import SourceState

__all__ = ["LiveSource", "SourceState", "entry_from_message"]

#: Seconds between two master checks.
CHECK_PERIOD = 1.0

#: Seconds a master call may take before the master counts as gone.
CALL_TIMEOUT = 3.0

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


class LiveSource:
    """Subscribes to /rosout_agg and keeps doing so across master restarts.

    ``on_state`` is called with a :class:`SourceState` whenever the connection
    state changes; messages collect in :attr:`inbox` until :meth:`take`.
    """

    def __init__(self, master_uri: str, on_state: Callable[[SourceState], None]) -> None:
        self.master_uri = master_uri
        self.on_state = on_state
        self.inbox: list[RosoutEntry] = []
        self.node: AsyncNode | None = None
        self.subscriptions = 0
        self._log_class = get_message_class("rosgraph_msgs/Log")
        self._stopped = False
        self.state = SourceState("waiting", master_uri)

    def take(self) -> list[RosoutEntry]:
        """The messages received since the last call."""
        batch, self.inbox = self.inbox, []
        return batch

    def _receive(self, msg: Any) -> None:
        self.inbox.append(entry_from_message(msg))

    def _set_state(self, status: str, detail: str = "") -> None:
        state = SourceState(status, self.master_uri, detail)
        if state != self.state:
            self.state = state
            self.on_state(state)

    async def _connect(self) -> int:
        """Start a node and subscribe; returns the master's pid."""
        node = AsyncNode(NODE_NAME, anonymous=True, master_uri=self.master_uri)
        node.log.console = None  # library warnings must not write over the screen
        self.node = node
        await node.start(publish_rosout=False)
        pid = await asyncio.wait_for(node.master_call("getPid"), CALL_TIMEOUT)
        await node.subscribe("/rosout_agg", self._log_class, self._receive)
        self.subscriptions += 1
        return int(pid)

    async def _drop_node(self) -> None:
        node, self.node = self.node, None
        if node is not None:
            try:
                await asyncio.wait_for(node.shutdown("rostui console: master changed"), CALL_TIMEOUT)
            except Exception:  # the master is gone; closing our own sockets is all that matters
                pass

    async def _master_pid(self) -> int | None:
        assert self.node is not None
        try:
            return int(await asyncio.wait_for(self.node.master_call("getPid"), CALL_TIMEOUT))
        except Exception:  # no answer, or not one a master gives: either way not the master we registered with
            return None

    async def run(self) -> None:
        """Connect, watch the master, reconnect; runs until :meth:`stop`."""
        had_master = False
        while not self._stopped:
            try:
                pid = await self._connect()
            except Exception as exc:  # any failure to register is said on screen, then retried
                await self._drop_node()
                self._set_state("lost" if had_master else "waiting", "" if had_master else _reason(exc))
                await asyncio.sleep(CHECK_PERIOD)
                continue
            had_master = True
            self._set_state("connected")
            while not self._stopped:
                await asyncio.sleep(CHECK_PERIOD)
                now = await self._master_pid()
                if now != pid:
                    break
            await self._drop_node()
            if not self._stopped:
                self._set_state("lost")

    async def stop(self) -> None:
        """Unsubscribe and shut the node down."""
        self._stopped = True
        await self._drop_node()


def _reason(exc: BaseException) -> str:
    text = str(exc)
    if "Unable to communicate" in text or isinstance(exc, (OSError, asyncio.TimeoutError)):
        return "no answer"
    return text.splitlines()[0] if text else type(exc).__name__
