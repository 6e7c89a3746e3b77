"""Service calls before ``init_node``: rospy lets a script that is no node call services, so does this.

The calls run on a private engine under rospy's caller id ``/unnamed`` and
ask the master named by ``ROS_MASTER_URI`` (``__master:=`` on the command line wins).
"""

from __future__ import annotations

import asyncio
import sys
import threading
import time
from typing import Any

from rostui.core import names as _names
from rostui.core.localhost import connect_host
from rostui.core.masteruri import master_uri_from_env
from rostui.core.node.engine import Engine
from rostui.core.node.services import ServiceException, parse_rosrpc_uri, probe_header
from rostui.core.tcpros import encode_header
from rostui.core.node.services import ServiceProxy as _AsyncProxy
from rostui.core.node.sync import DetachedCaller

__all__ = ["Caller", "caller"]


class Caller(DetachedCaller):
    """The part of a node a service proxy needs: a caller id, the master, and an engine to run on."""

    def __init__(self) -> None:
        super().__init__("/unnamed", master_uri_from_env(_names.parse_argv(sys.argv[1:]).master))
        self.engine = Engine()

    def proxy(self, resolved: str, service_class: Any, persistent: bool,
              headers: dict[str, str] | None) -> _AsyncProxy:
        """An asynchronous proxy of *resolved* that runs on this caller's engine."""
        host: Any = self
        return _AsyncProxy(host, resolved, service_class, persistent=persistent, headers=headers)

    def wait_for_service(self, resolved: str, timeout: float | None) -> bool:
        """Block until *resolved* is registered and accepts connections; False when *timeout* passes first."""
        deadline = None if timeout is None else time.monotonic() + timeout

        async def reachable() -> bool:
            try:
                uri = await self.lookup_service(resolved)
                host, port = parse_rosrpc_uri(uri)
                _, writer = await asyncio.wait_for(asyncio.open_connection(connect_host(host), port), 1.0)
                writer.write(encode_header(probe_header(self.name, resolved)))
                writer.close()
                return True
            except (ServiceException, OSError, ValueError, asyncio.TimeoutError):
                return False

        while not self.engine.run(reachable()):
            if deadline is not None and time.monotonic() >= deadline:
                return False
            time.sleep(0.1)
        return True


_lock = threading.Lock()
_caller: list[Caller] = []


def caller() -> Caller:
    """This process's one nodeless caller, started on first use."""
    with _lock:
        if not _caller:
            _caller.append(Caller())
        return _caller[0]
