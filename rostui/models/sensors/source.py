"""ViewSource: `rostui view`'s node and the master's topic types, read every second.

One anonymous node ``/rostui_view_<pid>_<ms>`` kept registered by a
:class:`~rostui.models.master_link.MasterLink`; the panels subscribe on it.
"""

from __future__ import annotations

import asyncio
from typing import Callable

from rostui.core.node import AsyncNode
from rostui.models.master_link import CALL_TIMEOUT, LinkedSource, MasterLink, SourceState

__all__ = ["ViewSource", "NODE_NAME"]

#: The view's node name (made anonymous).
NODE_NAME = "rostui_view"


class ViewSource(LinkedSource):
    """The master at ``master_uri``: its topic types every ``period`` seconds; call :meth:`run` as a task."""

    def __init__(self, master_uri: str, *, period: float = 1.0,
                 on_state: Callable[[SourceState], None] | None = None) -> None:
        self.master_uri = master_uri
        self.period = period
        self.types: dict[str, str] = {}
        self.link = MasterLink(NODE_NAME, master_uri, on_connect=self._poll, session=self._serve,
                               on_state=on_state, check_period=period)

    def type_of(self, topic: str) -> str | None:
        """The type the master lists for ``topic`` (None when it lists none)."""
        return self.types.get(topic)

    async def run(self) -> None:
        """Stay registered; poll the topic types."""
        await self.link.run()

    async def stop(self) -> None:
        """Unsubscribe everything and leave the master."""
        await self.link.stop()

    async def _serve(self, node: AsyncNode) -> None:
        while True:
            await asyncio.sleep(self.period)
            await self._poll(node)

    async def _poll(self, node: AsyncNode) -> None:
        answer = await asyncio.wait_for(node.master_call("getTopicTypes"), CALL_TIMEOUT)
        self.types = {str(name): str(kind) for name, kind in answer}
