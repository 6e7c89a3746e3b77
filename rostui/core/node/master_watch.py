"""Whether a node's master answers and which master it is: rostui's one judge of the master.

About every second (:data:`CHECK_PERIOD`) the watch asks the master at the node's URI its pid and
``/run_id`` (one ``system.multicall``, or two calls to a master without it) on a connection of its
own, beside the node's traffic.  A master that answers after none did, or whose pid or ``/run_id``
differs from the last answer's, is a new master: the node registers again everything it has
(publishers, subscribers, services, parameter subscriptions), the watch runs its ``on_connect``
hooks, and only then is the node connected.  A master that stops answering leaves the node lost
(waiting, while none has answered yet).  Listeners hear every change of :class:`MasterState`.

ROS 1 nodes have no such thing: they outlive a restarted master without it knowing them.
"""

from __future__ import annotations

import asyncio
import enum
import logging
from typing import Any, Awaitable, Callable, Protocol

from rostui.core.master_errors import MasterUnreachableError
from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcConnectionError, XmlRpcError, XmlRpcFault, ros_result

__all__ = ["CHECK_PERIOD", "CHECK_TIMEOUT", "MasterHost", "MasterState", "MasterWatch", "failure_reason"]

log = logging.getLogger("rostui.node")

#: Seconds between two checks of who the master is.
CHECK_PERIOD = 1.0

#: Seconds a check may wait for the master's answer before the master counts as not answering.
CHECK_TIMEOUT = 3.0


class MasterState(str, enum.Enum):
    """Where a node stands with its master; each equals its lower-case name as a string."""

    WAITING = "waiting"
    """No master has answered yet."""
    CONNECTED = "connected"
    """Registered with a master that answers."""
    LOST = "lost"
    """A master answered once and does not now (or another took its place and the node is registering again)."""


class MasterHost(Protocol):
    """What the watch needs of its node."""

    name: str
    master_uri: str

    @property
    def is_shutdown(self) -> bool:
        """True once the node began shutting down."""
        ...

    def has_registrations(self) -> bool:
        """Whether the node has anything registered with the master."""
        ...

    async def register_again(self) -> None:
        """Register everything the node has with the master again."""
        ...


def failure_reason(exc: BaseException) -> str:
    """An error in a few words: ``no answer`` when the master (or a peer) did not answer, else its first line."""
    if isinstance(exc, (MasterUnreachableError, XmlRpcConnectionError, OSError, asyncio.TimeoutError)):
        return "no answer"
    text = str(exc)
    return text.splitlines()[0] if text else type(exc).__name__


def _multicall_value(answer: Any) -> Any:
    """The value of one ROS API call inside a ``system.multicall`` answer, or None (a fault, a failure code)."""
    if isinstance(answer, list) and len(answer) == 1:
        try:
            return ros_result(answer[0])
        except (RosApiError, XmlRpcError):
            return None
    return None


class MasterWatch:
    """The checks of one node's master; :meth:`start` on the node's loop, :meth:`stop` at its shutdown.

    ``on_connect`` hooks run (in order) after each registration with a master, the first included;
    one that raises leaves the node lost, and the next check registers and runs them all again.
    ``listeners`` are called with each new :attr:`state` (and when only its :attr:`detail` changed).
    """

    def __init__(self, host: MasterHost, *, period: float = CHECK_PERIOD, timeout: float = CHECK_TIMEOUT) -> None:
        self.host = host
        self.period = period
        self.timeout = timeout
        self.state = MasterState.WAITING
        #: Why the master does not answer as one (``no answer``, ``getPid answered ...``); '' once it does.
        self.detail = ""
        #: How many times the node registered everything again with a new master.
        self.renewals = 0
        self.on_connect: list[Callable[[], Awaitable[None]]] = []
        self.listeners: list[Callable[[MasterState], None]] = []
        self._told: tuple[MasterState, str] = (self.state, self.detail)
        self._identity: tuple[Any, Any] | None = None
        self._answered = False
        self._connected_once = False
        self._missed = False
        self._multicall = True
        self._client: XmlRpcClient | None = None
        self._handle: asyncio.Handle | None = None
        self._task: asyncio.Task[None] | None = None

    def start(self) -> None:
        """Begin checking, now and then every :attr:`period` seconds (on the running loop)."""
        self._client = XmlRpcClient(self.host.master_uri, timeout=self.timeout)
        self._handle = asyncio.get_running_loop().call_soon(self._begin)

    async def stop(self) -> None:
        """No more checks; close the watch's connection."""
        if self._handle is not None:
            self._handle.cancel()
            self._handle = None
        task = self._task
        if task is not None and task is not asyncio.current_task():
            task.cancel()
            await asyncio.gather(task, return_exceptions=True)
        if self._client is not None:
            await self._client.close()

    def _begin(self) -> None:
        self._handle = None
        if not self.host.is_shutdown:
            self._task = asyncio.get_running_loop().create_task(self._run_check())

    async def _run_check(self) -> None:
        try:
            await self.check()
        except Exception as exc:  # a failed registration or hook is retried at the next check; it must not end them
            log.debug("master check failed: %s", exc)
            self.detail = failure_reason(exc)
            self._set_state(self._not_connected())
        finally:
            self._task = None
            if not self.host.is_shutdown:
                self._handle = asyncio.get_running_loop().call_later(self.period, self._begin)

    async def check(self) -> bool:
        """Check who the master is now; register again and run the hooks for a new one.

        Returns True when the node registered everything again.  The watch does this every
        :attr:`period` seconds by itself; call it to do it now.
        """
        identity = await self._identity_now()
        if identity is None:
            self._missed = self._missed or self._answered or self.host.has_registrations()
            self._set_state(self._not_connected())
            return False
        known, self._identity = self._identity, identity
        first = not self._answered
        self._answered = True
        renewing = self._missed or (known is not None and known != identity)
        if not renewing and not first:
            return False
        if self.state is MasterState.CONNECTED:  # another master took this one's place
            self._set_state(MasterState.LOST)
        self._missed = True  # until registered and set up: a failure below is retried at the next check
        if renewing:
            log.info("a new master answers at %s (pid %s, run_id %s): registering again", self.host.master_uri,
                     *identity)
            await self.host.register_again()
        for hook in list(self.on_connect):
            if self.host.is_shutdown:
                return renewing
            await hook()
        self._missed = False
        if renewing:
            self.renewals += 1
        self._connected_once = True
        self._set_state(MasterState.CONNECTED)
        return renewing

    async def _identity_now(self) -> tuple[Any, Any] | None:
        """The master's ``(pid, /run_id)``; None when it does not answer as a master (:attr:`detail` says why)."""
        client = self._client
        assert client is not None, "master watch not started"
        try:
            pid, run_id = await self._ask(client)
        except (XmlRpcError, OSError, asyncio.TimeoutError) as exc:
            self.detail = failure_reason(exc)
            return None
        if not isinstance(pid, int) or isinstance(pid, bool):
            self.detail = f"getPid answered {pid!r:.80}, not a pid"
            return None
        self.detail = ""
        return pid, run_id

    async def _ask(self, client: XmlRpcClient) -> tuple[Any, Any]:
        caller = self.host.name
        if self._multicall:
            try:
                answers = await client.call("system.multicall", [
                    {"methodName": "getPid", "params": [caller]},
                    {"methodName": "getParam", "params": [caller, "/run_id"]}])
                if isinstance(answers, list) and len(answers) == 2:
                    pid, run_id = (_multicall_value(answer) for answer in answers)
                    return pid, run_id
            except XmlRpcFault:
                pass
            self._multicall = False
        return await self._plain_value(client, "getPid"), await self._plain_value(client, "getParam", "/run_id")

    async def _plain_value(self, client: XmlRpcClient, method: str, *args: Any) -> Any:
        try:
            return ros_result(await client.call(method, self.host.name, *args))
        except (RosApiError, XmlRpcFault):
            return None

    def _not_connected(self) -> MasterState:
        return MasterState.LOST if self._connected_once else MasterState.WAITING

    def _set_state(self, state: MasterState) -> None:
        told = (state, self.detail)
        if told == self._told:
            return
        self.state = state
        self._told = told
        for listener in list(self.listeners):
            listener(state)
