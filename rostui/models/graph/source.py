"""Where the graph app gets its facts: the master's registrations, ``node info``, a topic's rate.

All of it is async and never blocks the caller's loop: master polls go
through an :class:`~rostui.core.xmlrpc.XmlRpcClient`, ``node info`` reuses
:func:`rostui.tools.node.node_info` in a thread, and a rate is measured
by a short-lived anonymous node (``/rostui_graph_<pid>_<ms>``) that
subscribes, counts arrivals with rostopic hz's statistics and leaves.
"""

from __future__ import annotations

import asyncio
import time
from dataclasses import dataclass
from typing import Any

from rostui.models.graph.model import RosGraph
from rostui.tools.node import NodeInfo

__all__ = ["GraphSource", "SourceError", "RateReport", "CALLER_ID", "NODE_NAME"]

#: Caller id of the master polls.
CALLER_ID = "/rostui_graph"
#: Base name of the anonymous node that measures rates.
NODE_NAME = "rostui_graph"
#: Seconds a master or node call may take before the source gives up on it.
CALL_TIMEOUT = 3.0


class SourceError(Exception):
    """The master (or a node) could not be asked; the message is one line for the status bar."""


@dataclass(frozen=True)
class RateReport:
    """A topic's measured rate: messages seen in ``seconds``, and rostopic hz's statistics when there were two."""

    topic: str
    seconds: float
    messages: int
    rate: float | None = None
    min_delta: float | None = None
    max_delta: float | None = None
    std_dev: float | None = None

    def text(self) -> str:
        """One line: ``average rate: 2.000 Hz (min 0.499 s, max 0.501 s, 7 msgs in 3.0 s)`` or why not."""
        if self.rate is None:
            return f"no messages in {self.seconds:.1f} s" if self.messages == 0 else \
                f"1 message in {self.seconds:.1f} s"
        return (f"average rate: {self.rate:.3f} Hz (min {self.min_delta:.3f} s, max {self.max_delta:.3f} s, "
                f"{self.messages} msgs in {self.seconds:.1f} s)")


class GraphSource:
    """The master at ``master_uri`` seen by the graph app."""

    def __init__(self, master_uri: str) -> None:
        self.master_uri = master_uri
        self._client: Any = None

    async def fetch(self) -> RosGraph:
        """The current registrations (SourceError when the master does not answer)."""
        from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcError, ros_result

        if self._client is None:
            self._client = XmlRpcClient(self.master_uri, timeout=CALL_TIMEOUT)
        try:
            state = ros_result(await self._client.call("getSystemState", CALLER_ID))
            types = ros_result(await self._client.call("getTopicTypes", CALLER_ID))
        except (XmlRpcError, RosApiError, OSError) as exc:
            await self._reset()
            raise SourceError(f"master unreachable at {self.master_uri}: {_reason(exc)}") from None
        try:
            return RosGraph.from_wire(state, types)
        except (TypeError, ValueError) as exc:
            raise SourceError(f"master at {self.master_uri} sent a malformed system state: {exc}") from None

    async def node_info(self, node: str) -> NodeInfo:
        """``rosnode info`` data for ``node`` (its ``error`` says when the node or master cannot be reached)."""
        from rostui.core.xmlrpc import XmlRpcError, call_sync, ros_result
        from rostui.tools.node import node_info

        def call(method: str, *args: Any) -> Any:
            return ros_result(call_sync(self.master_uri, method, CALLER_ID, *args, timeout=CALL_TIMEOUT))

        try:
            return await asyncio.to_thread(node_info, call, node, timeout=CALL_TIMEOUT)
        except XmlRpcError as exc:
            return NodeInfo(node, [], [], [], error=f"master unreachable at {self.master_uri}: {_reason(exc)}")

    async def measure_rate(self, topic: str, seconds: float = 3.0) -> RateReport:
        """Subscribe to ``topic`` for ``seconds`` and report its rate (SourceError when that cannot be done)."""
        from rostui.core.node import AnyMsg, AsyncNode
        from rostui.models.master_link import MASTER_ERRORS
        from rostui.tools.topic.rates import HzStats

        stats = HzStats()
        node = AsyncNode(NODE_NAME, anonymous=True, argv=[], master_uri=self.master_uri)
        try:
            await node.start(announce=False)
            await node.subscribe(topic, AnyMsg, lambda _msg: stats.add(time.time()))
            await asyncio.sleep(seconds)
        except MASTER_ERRORS + (ValueError,) as exc:  # ValueError: a topic name that does not resolve
            raise SourceError(f"cannot measure {topic}: {_reason(exc)}") from None
        finally:
            try:
                await asyncio.wait_for(node.shutdown("rate measured"), CALL_TIMEOUT)
            except MASTER_ERRORS:  # the master is gone; closing our own sockets is all that matters
                pass
        count = len(stats.times)
        numbers = stats.stats()
        if numbers is None:
            return RateReport(topic, seconds, count)
        rate, lo, hi, sd, _ = numbers
        return RateReport(topic, seconds, count, rate, lo, hi, sd)

    async def close(self) -> None:
        """Close the connection to the master."""
        await self._reset()

    async def _reset(self) -> None:
        client, self._client = self._client, None
        if client is not None:
            await client.close()


def _reason(exc: BaseException) -> str:
    """The useful part of an exception, on one line."""
    reason = getattr(exc, "reason", None) or str(exc) or type(exc).__name__
    return " ".join(str(reason).split())
