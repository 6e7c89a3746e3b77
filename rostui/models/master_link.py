"""The one link to the master that live views share, and how their status line says it.

:class:`MasterLink` keeps an anonymous node for as long as it runs.  Whether
the master answers, and whether it is a new one, is the node's own judgement
(:class:`~rostui.core.node.master_watch.MasterWatch`, every ``check_period``
seconds): after a restart the node registers again what it has, then the
link's owner sets it up in ``on_connect`` (a first poll, a subscription it
does not have yet) and may run a ``session`` beside it while it stays
connected.  The link only says what the apps show: waiting, connected or
lost.  The console's, monitor's, view's and tf tree's sources share it; the
graph and logger views register nothing, so they only poll.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import Awaitable, Callable

from rostui.core.node.master_watch import CHECK_PERIOD, MasterState, failure_reason
from rostui.core.node.node import AsyncNode, MasterError
from rostui.core.xmlrpc import XmlRpcError

__all__ = ["CALL_TIMEOUT", "CHECK_PERIOD", "MASTER_ERRORS", "LinkedSource", "MasterLink", "MasterState", "SourceState",
           "failure_reason"]

#: Seconds a master call may take before the master counts as gone.
CALL_TIMEOUT = 3.0

#: What a master that is down, unreachable, slow or not a master raises at a node talking to it.
MASTER_ERRORS: tuple[type[Exception], ...] = (MasterError, XmlRpcError, OSError, asyncio.TimeoutError)


@dataclass(frozen=True)
class SourceState:
    """Where a link stands with its master (:class:`MasterState`), the master's URI and why it is still waiting."""

    status: MasterState
    master_uri: str
    detail: str = ""

    def text(self, marks: bool = False) -> str:
        """One line for a status bar; with ``marks`` a leading ●, ✖ or … and, once connected, no URI."""
        if self.status is MasterState.CONNECTED:
            return "● master" if marks else f"master {self.master_uri}"
        if self.status is MasterState.LOST:
            return ("✖ " if marks else "") + f"master {self.master_uri} gone: waiting for it to come back"
        return (("… " if marks else "") + f"waiting for master {self.master_uri}"
                + (f" ({self.detail})" if self.detail else ""))


class MasterLink:
    """One anonymous node ``/<node_name>_<pid>_<ms>`` kept with the master at ``master_uri``.

    Call :meth:`run` as a task and :meth:`stop` to end.  ``on_connect(node)``
    runs after each registration with a master (the first, and again after a
    new master; it must do only what the node does not have yet);
    ``session(node)``, when given, runs beside the node while it stays
    connected and starts again when it is connected again.  A master error in
    either is the master's failure (the node judges it at its next check);
    any other error ends :meth:`run`.  ``on_drop()`` runs before the node is
    shut down, and ``on_state`` gets each new :class:`SourceState`.
    """

    def __init__(self, node_name: str, master_uri: str, *,
                 on_connect: Callable[[AsyncNode], Awaitable[None]] | None = None,
                 session: Callable[[AsyncNode], Awaitable[None]] | None = None,
                 on_drop: Callable[[], None] | None = None,
                 on_state: Callable[[SourceState], None] | None = None,
                 check_period: float = CHECK_PERIOD, call_timeout: float = CALL_TIMEOUT) -> None:
        self.node_name = node_name
        self.master_uri = master_uri
        self.check_period = check_period
        self.call_timeout = call_timeout
        self.state = SourceState(MasterState.WAITING, master_uri)
        self._node: AsyncNode | None = None
        self._on_connect = on_connect
        self._session = session
        self._on_drop = on_drop
        self._on_state = on_state
        self._stopping = asyncio.Event()
        self._changed = asyncio.Event()
        self._changes = 0
        self._failure: BaseException | None = None

    @property
    def node(self) -> AsyncNode | None:
        """The link's node while it is connected to a master."""
        return self._node if self.state.status is MasterState.CONNECTED else None

    async def run(self) -> None:
        """Start the node and keep the session going while it is connected; until :meth:`stop`."""
        node = AsyncNode(self.node_name, anonymous=True, argv=[], master_uri=self.master_uri,
                         master_check_period=self.check_period)
        node.log.console = None  # library warnings must not write over the screen
        watch = node.master_watch
        assert watch is not None
        watch.on_connect.append(lambda: self._connected(node))
        watch.listeners.append(lambda _state: self._judged(node))
        self._node = node
        try:
            await node.start(announce=False)
            while not self._stopping.is_set():
                if self.state.status is MasterState.CONNECTED and self._session is not None:
                    await self._keep_session(node)
                else:
                    await self._next_change(self._changes)
            if self._failure is not None:
                raise self._failure
        finally:
            await self._drop()

    async def stop(self) -> None:
        """End :meth:`run` and shut the node down."""
        self._stopping.set()
        self._changed.set()
        await self._drop()

    async def _connected(self, node: AsyncNode) -> None:
        """The node's hook after each registration with a master: its logger services once, then the owner's set-up."""
        await asyncio.wait_for(node.announce(publish_rosout=False), self.call_timeout)
        if self._on_connect is None:
            return
        try:
            await self._on_connect(node)
        except MASTER_ERRORS:
            raise
        except Exception as exc:  # a bug, not the master: end run() with it
            self._failure = exc
            self._stopping.set()
            self._changed.set()

    def _judged(self, node: AsyncNode) -> None:
        watch = node.master_watch
        assert watch is not None
        detail = watch.detail if watch.state is MasterState.WAITING else ""
        self._set_state(SourceState(watch.state, self.master_uri, detail))

    async def _keep_session(self, node: AsyncNode) -> None:
        """Run the session until the node is not connected any more, the link stops or the session fails."""
        assert self._session is not None
        seen = self._changes
        change = asyncio.ensure_future(self._next_change(seen))
        session = asyncio.ensure_future(self._session(node))
        try:
            await asyncio.wait({session, change}, return_when=asyncio.FIRST_COMPLETED)
        finally:
            for task in (session, change):
                task.cancel()
            await asyncio.gather(session, change, return_exceptions=True)
        if session.cancelled() or not session.done():
            return
        error = session.exception()
        if error is None:  # the session is over while connected: nothing more to run until the state changes
            await self._next_change(seen)
        elif isinstance(error, MASTER_ERRORS):  # the master failed it: the node's next check says whether it is gone
            await self._pause(self.check_period)
        else:
            raise error

    async def _next_change(self, seen: int) -> None:
        """Wait until the link's state changed since it had made ``seen`` changes, or it stops."""
        while self._changes == seen and not self._stopping.is_set():
            self._changed.clear()
            await self._changed.wait()

    async def _pause(self, seconds: float) -> bool:
        """Wait ``seconds`` or until :meth:`stop`; True when stopping."""
        try:
            await asyncio.wait_for(self._stopping.wait(), seconds)
        except asyncio.TimeoutError:
            pass
        return self._stopping.is_set()

    async def _drop(self) -> None:
        node, self._node = self._node, None
        if node is None:
            return
        if self._on_drop is not None:
            self._on_drop()
        try:
            await asyncio.wait_for(node.shutdown(f"{self.node_name}: master link closed"), self.call_timeout)
        except MASTER_ERRORS:  # the master is gone; closing our own sockets is all that matters
            pass

    def _set_state(self, state: SourceState) -> None:
        if state != self.state:
            self.state = state
            self._changes += 1
            self._changed.set()
            if self._on_state is not None:
                self._on_state(state)


class LinkedSource:
    """A live source that keeps its node through a :class:`MasterLink` (set ``self.link`` in ``__init__``)."""

    link: MasterLink

    @property
    def state(self) -> SourceState:
        """The link's state: waiting, connected or lost."""
        return self.link.state

    @property
    def node(self) -> AsyncNode | None:
        """The source's node while registered with a master."""
        return self.link.node
