"""The one link to the master that live views share, and how their status line says it.

:class:`MasterLink` keeps an anonymous node registered with the master at a
URI for as long as it runs.  Every ``check_period`` seconds (one by default)
it asks the master for its pid: no answer means the master is gone (the node
is dropped and the link waits for a master to answer); a different pid means
a new master (the node registers again, so a restarted master knows it).  Its
owner sets each new node up in ``on_connect`` (subscriptions, a first poll)
and may run a ``session`` beside the pid check while the node stays registered.
The console's and the monitor's sources share it; the graph and logger views
register nothing, so they only poll.
"""

from __future__ import annotations

import asyncio
import enum
from dataclasses import dataclass
from typing import Awaitable, Callable

from rostui.core.node.node import AsyncNode, MasterError, MasterUnreachableError
from rostui.core.xmlrpc import XmlRpcError, XmlRpcProtocolError

__all__ = ["CALL_TIMEOUT", "CHECK_PERIOD", "MASTER_ERRORS", "LinkStatus", "LinkedSource", "MasterLink", "SourceState",
           "failure_reason"]

#: Seconds between two checks of the master's pid.
CHECK_PERIOD = 1.0

#: Seconds a master call may take before the master counts as gone.
CALL_TIMEOUT = 3.0

#: What a master that is down, unreachable, slow or not a master raises at a node talking to it.
MASTER_ERRORS: tuple[type[Exception], ...] = (MasterError, XmlRpcError, OSError, asyncio.TimeoutError)


class LinkStatus(str, enum.Enum):
    """Where a link to the master stands; each equals its lower-case name as a string."""

    WAITING = "waiting"
    """No master has answered yet."""
    CONNECTED = "connected"
    """Registered with a master that answers."""
    LOST = "lost"
    """The master answered once and is gone now."""


@dataclass(frozen=True)
class SourceState:
    """A link's :class:`LinkStatus`, the master's URI and a one-line detail (why it is still waiting)."""

    status: LinkStatus
    master_uri: str
    detail: str = ""

    def text(self, marks: bool = False) -> str:
        """One line for a status bar; with ``marks`` a leading ●, ✖ or … and, once connected, no URI."""
        if self.status is LinkStatus.CONNECTED:
            return "● master" if marks else f"master {self.master_uri}"
        if self.status is LinkStatus.LOST:
            return ("✖ " if marks else "") + f"master {self.master_uri} gone: waiting for it to come back"
        return (("… " if marks else "") + f"waiting for master {self.master_uri}"
                + (f" ({self.detail})" if self.detail else ""))


def failure_reason(exc: BaseException) -> str:
    """An error in a few words: ``no answer`` when the master (or a peer) did not answer, else its first line."""
    if isinstance(exc, (MasterUnreachableError, OSError, asyncio.TimeoutError)):
        return "no answer"
    text = str(exc)
    return text.splitlines()[0] if text else type(exc).__name__


class MasterLink:
    """One anonymous node ``/<node_name>_<pid>_<ms>`` kept registered with the master at ``master_uri``.

    Call :meth:`run` as a task and :meth:`stop` to end.  ``on_connect(node)``
    runs after each registration; ``session(node)``, when given, runs beside
    the pid check until the master goes or changes (then it is cancelled).
    Either raising one of :data:`MASTER_ERRORS` counts as losing the master;
    any other error ends :meth:`run`.  ``on_drop()`` runs before a node is
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
        self.node: AsyncNode | None = None
        self.state = SourceState(LinkStatus.WAITING, master_uri)
        self._on_connect = on_connect
        self._session = session
        self._on_drop = on_drop
        self._on_state = on_state
        self._stopping = asyncio.Event()

    async def run(self) -> None:
        """Register, watch the master, register again after it went or changed; until :meth:`stop`."""
        had_master = False
        while not self._stopping.is_set():
            try:
                node, pid = await self._register()
            except MASTER_ERRORS as exc:
                await self._drop()
                self._set_state(LinkStatus.LOST if had_master else LinkStatus.WAITING,
                                "" if had_master else failure_reason(exc))
                await self._pause(self.check_period)
                continue
            if self._stopping.is_set():
                break
            had_master = True
            self._set_state(LinkStatus.CONNECTED)
            await self._stay(node, pid)
            await self._drop()
            if not self._stopping.is_set():
                self._set_state(LinkStatus.LOST)
        await self._drop()

    async def stop(self) -> None:
        """End :meth:`run` and shut the node down."""
        self._stopping.set()
        await self._drop()

    async def _register(self) -> tuple[AsyncNode, int]:
        """Start a node with the master, set it up; returns it and the master's pid."""
        # the link watches the master itself (and starts a fresh node on a new one): the node's own watch off
        node = AsyncNode(self.node_name, anonymous=True, argv=[], master_uri=self.master_uri, watch_master=False)
        node.log.console = None  # library warnings must not write over the screen
        self.node = node
        await asyncio.wait_for(node.start(publish_rosout=False), self.call_timeout)
        pid = await self._master_pid(node)
        if self._on_connect is not None:
            await self._on_connect(node)
        return node, pid

    async def _master_pid(self, node: AsyncNode) -> int:
        answer = await asyncio.wait_for(node.master_call("getPid"), self.call_timeout)
        if not isinstance(answer, int):
            raise XmlRpcProtocolError(self.master_uri, f"getPid answered {answer!r:.80}, not a pid")
        return answer

    async def _stay(self, node: AsyncNode, pid: int) -> None:
        """Return when the link stops, the master goes or changes, or the session fails with a master error."""
        watch = asyncio.ensure_future(self._watch(node, pid))
        tasks: set[asyncio.Future[None]] = {watch}
        if self._session is not None:
            tasks.add(asyncio.ensure_future(self._session(node)))
        try:
            pending = set(tasks)
            while watch in pending:
                done, pending = await asyncio.wait(pending, return_when=asyncio.FIRST_COMPLETED)
                for task in done:
                    error = task.exception()
                    if error is None:
                        continue
                    if isinstance(error, MASTER_ERRORS):
                        return
                    raise error
        finally:
            for task in tasks:
                task.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)

    async def _watch(self, node: AsyncNode, pid: int) -> None:
        """Return when the link stops, or the master does not answer or answers with another pid."""
        while not await self._pause(self.check_period):
            try:
                if await self._master_pid(node) != pid:
                    return
            except MASTER_ERRORS:
                return

    async def _pause(self, seconds: float) -> bool:
        """Wait ``seconds`` or until :meth:`stop`; True when stopping."""
        try:
            await asyncio.wait_for(self._stopping.wait(), seconds)
        except asyncio.TimeoutError:
            pass
        return self._stopping.is_set()

    async def _drop(self) -> None:
        node, self.node = self.node, None
        if node is None:
            return
        if self._on_drop is not None:
            self._on_drop()
        try:
            await asyncio.wait_for(node.shutdown(f"{self.node_name}: master link closed"), self.call_timeout)
        except MASTER_ERRORS:  # the master is gone; closing our own sockets is all that matters
            pass

    def _set_state(self, status: LinkStatus, detail: str = "") -> None:
        state = SourceState(status, self.master_uri, detail)
        if state != self.state:
            self.state = state
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
