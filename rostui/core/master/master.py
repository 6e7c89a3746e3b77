"""The :class:`Master`: a Master/Parameter Server API handler served over XML-RPC."""

from __future__ import annotations

import asyncio
import logging
import os
import signal
import socket
import uuid

from typing import Any

from ..xmlrpc import EncodedResponse, XmlRpcServer
from .handler import MasterHandler
from .notify import Notifier

_log = logging.getLogger("rostui.master")

#: Defaults for the parameters roslaunch sets when it starts a core.
DEFAULT_ROSDISTRO = "noetic\n"
DEFAULT_ROSVERSION = "1.16.0\n"

#: Seconds between answering a ``shutdown`` call and acting on it, for the reply to reach the caller.
_REPLY_GRACE = 0.05


def _terminate_this_process(reason: str) -> None:
    """Stop this process as ``kill`` would, if it handles SIGTERM; otherwise only log the request."""
    handler = signal.getsignal(signal.SIGTERM)
    if handler in (signal.SIG_DFL, signal.SIG_IGN, None):
        _log.warning("shutdown requested (%s), but this process does not handle SIGTERM: still running", reason)
        return
    _log.info("shutdown requested: %s", reason)
    os.kill(os.getpid(), signal.SIGTERM)


class _WireHandler:
    """What the XML-RPC server sees: the handler, plus a cached encoding of getSystemState.

    getSystemState is the one large answer tools poll (rqt_graph, rosnode);
    while the registrations do not change its serialised form is reused.
    """

    def __init__(self, handler: MasterHandler) -> None:
        self._handler = handler
        self._state_key: list[Any] | None = None
        self._state_encoded: EncodedResponse | None = None

    def __getattr__(self, name: str) -> Any:
        return getattr(self._handler, name)

    def getSystemState(self, *args: Any) -> Any:
        """getSystemState, answered from cache while nothing changed."""
        result = self._handler.getSystemState(*args)
        if result[0] != 1:
            return result
        state = result[2]
        key = self._state_key
        if key is None or any(a is not b for a, b in zip(key, state)):
            self._state_key = list(state)
            self._state_encoded = EncodedResponse(result)
        return self._state_encoded


class Master:
    """A ROS 1 master (Master API + Parameter Server) on ``host:port``.

    ``host`` is the interface to bind; ``advertise_host`` is the host name put
    in :attr:`uri` (default: ``host``, or this machine's name when ``host`` is a
    wildcard address).  On :meth:`start` the parameters ``/run_id`` (a UUID1
    string, ``run_id`` if given), ``/rosdistro`` and ``/rosversion`` are set.

    A ``shutdown`` call is answered ``[1, "shutdown", 0]``, as rosmaster does,
    and then ends the master: an owner awaiting :meth:`wait_for_shutdown_request`
    stops it; when none is, ``terminate_process`` (the default) sends this
    process SIGTERM if the process handles SIGTERM (a command such as
    ``rostui core`` that stops cleanly on ``kill``), so it exits as rosmaster
    does.  ``terminate_process=False`` (a master inside a bigger program)
    leaves the request to :meth:`wait_for_shutdown_request`.
    """

    def __init__(self, host: str, port: int, *, advertise_host: str | None = None,
                 run_id: str | None = None, rosdistro: str = DEFAULT_ROSDISTRO,
                 rosversion: str = DEFAULT_ROSVERSION, notify_timeout: float = 10.0,
                 terminate_process: bool = True) -> None:
        if advertise_host is None:
            advertise_host = socket.gethostname() if host in ("", "0.0.0.0", "::") else host
        self.host = host
        self.advertise_host = advertise_host
        self._run_id = run_id or str(uuid.uuid1())
        self._rosdistro = rosdistro
        self._rosversion = rosversion
        self._shutdown_reason: asyncio.Future[str] | None = None
        self._shutdown_waiters = 0
        self._terminate_process = terminate_process
        self.handler = MasterHandler(Notifier(timeout=notify_timeout), on_shutdown=self._shutdown_requested)
        self._server = XmlRpcServer(_WireHandler(self.handler), host, port, advertise_host=advertise_host)

    @property
    def run_id(self) -> str:
        """The UUID stored in ``/run_id``."""
        return self._run_id

    @property
    def uri(self) -> str:
        """``http://<advertise_host>:<port>/`` (valid after :meth:`start`)."""
        return self._server.uri

    @property
    def port(self) -> int:
        """The TCP port the master listens on (valid after :meth:`start`)."""
        return self._server.port

    async def start(self) -> None:
        """Bind the port, then set ``/run_id``, ``/rosdistro`` and ``/rosversion``.

        Raises ``OSError`` when the port cannot be bound.
        """
        self._shutdown_reason = asyncio.get_running_loop().create_future()
        await self._server.start()
        self.handler.uri = self._server.uri
        params = self.handler.params
        params.set("/run_id", self._run_id)
        params.set("/rosdistro", self._rosdistro)
        params.set("/rosversion", self._rosversion)
        _log.info("master started at %s, run_id %s", self.uri, self._run_id)

    async def stop(self) -> None:
        """Stop serving and cancel pending notifications."""
        await self._server.close()
        await self.handler.notifier.close()

    def _shutdown_requested(self, reason: str) -> None:
        fut = self._shutdown_reason
        if fut is None or fut.done():
            return
        fut.set_result(reason)
        if self._shutdown_waiters == 0 and self._terminate_process:
            # After the reply has gone out: the handler returns it once this callback is done.
            fut.get_loop().call_later(_REPLY_GRACE, _terminate_this_process, reason)

    async def wait_for_shutdown_request(self) -> str:
        """Return (with its message) once a client calls the ``shutdown`` API.

        While a caller waits here, the master does not terminate its process
        on a shutdown call: the caller decides what stopping means.
        """
        if self._shutdown_reason is None:
            raise RuntimeError("Master not started")
        self._shutdown_waiters += 1
        try:
            return await asyncio.shield(self._shutdown_reason)
        finally:
            self._shutdown_waiters -= 1
