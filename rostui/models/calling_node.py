"""CallingNode: an unannounced node a tool or an app calls the master and other nodes from.

It registers nothing of its own, so it does not appear in node lists (loggers, top and the action app ask from
one); :meth:`CallingNode.start` opens its servers and :meth:`CallingNode.close` shuts it down.
"""

from __future__ import annotations

from typing import TypeVar

from rostui.core.node.node import AsyncNode

__all__ = ["CallingNode"]

_Self = TypeVar("_Self", bound="CallingNode")


class CallingNode:
    """Holds :attr:`node`, ``/<name>_<pid>_<ms>`` on the master at ``master_uri``; ``done`` is the reason it gives
    when it shuts down. With ``quiet`` its library warnings stay off the screen."""

    def __init__(self, name: str, master_uri: str | None, done: str, *, quiet: bool = False) -> None:
        self.node = AsyncNode(name, anonymous=True, argv=[], master_uri=master_uri)
        if quiet:
            self.node.log.console = None
        self._done = done
        self._started = False

    @property
    def master_uri(self) -> str:
        """The master asked."""
        return self.node.master_uri

    async def start(self: _Self) -> _Self:
        """Open the node's servers (no master needed yet)."""
        if not self._started:
            await self.node.start(announce=False)
            self._started = True
        return self

    async def close(self) -> None:
        """Shut the node down."""
        if self._started:
            self._started = False
            await self.node.shutdown(self._done)
