"""The :class:`Master`: a Master/Parameter Server API handler served over XML-RPC."""

from __future__ import annotations

import asyncio
import logging
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
    """

    def __init__(self, host: str, port: int, *, advertise_host: str | None = None,
                 run_id: str | None = None, rosdistro: str = DEFAULT_ROSDISTRO,
                 rosversion: str = DEFAULT_ROSVERSION, notify_timeout: float = 10.0) -> None:
        if advertise_host is None:
            advertise_host = socket.gethostname() if host in ("", "0.0.0.0", "::") else host
        self.host = host
        self.advertise_host = advertise_host
        self._run_id = run_id or str(uuid.uuid1())
        self._rosdistro = rosdistro
        self._rosversion = rosversion
        self._shutdown_reason: asyncio.Future[str] | None = None
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
        if fut is not None and not fut.done():
            fut.set_result(reason)

    async def wait_for_shutdown_request(self) -> str:
        """Return (with its message) once a client calls the ``shutdown`` API."""
        if self._shutdown_reason is None:
            raise RuntimeError("Master not started")
        return await asyncio.shield(self._shutdown_reason)
