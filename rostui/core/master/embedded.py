"""An in-process master for one-command tools: start one when none answers, reuse one that does.

``rostui turtlesim`` on a fresh machine must work without a separate
``rostui core``: :func:`ensure_master` probes ROS_MASTER_URI and, when nothing
answers and the URI names this machine, serves a :class:`Master` plus the
``/rosout`` aggregator on the caller's event loop until :meth:`EmbeddedMaster.stop`.
"""

from __future__ import annotations

import errno
import socket
from dataclasses import dataclass
from urllib.parse import urlsplit

from rostui.core.master.master import Master
from rostui.core.network import is_loopback_host, master_uri_from_env, resolve_addressing
from rostui.core.rosout import RosoutNode

#: Seconds to wait for a master to answer the probe.
PROBE_TIMEOUT = 2.0


class MasterStartError(Exception):
    """No master answers and none can be started here (remote URI, port taken, ...)."""


@dataclass
class EmbeddedMaster:
    """A master and rosout that this process started; stop them with :meth:`stop`."""

    master: Master
    rosout: RosoutNode

    @property
    def uri(self) -> str:
        """The master's URI (``http://host:port/``)."""
        return self.master.uri

    async def stop(self) -> None:
        """Shut rosout down (unregistering it), then close the master's port."""
        await self.rosout.stop()
        await self.master.stop()


async def master_answers(master_uri: str, timeout: float = PROBE_TIMEOUT) -> bool:
    """True when a ROS master answers ``getPid`` at ``master_uri``."""
    from rostui.core.xmlrpc import XmlRpcClient, XmlRpcError

    client = XmlRpcClient(master_uri, timeout=timeout)
    try:
        reply = await client.call("getPid", "/rostui_probe")
    except (XmlRpcError, OSError):
        return False
    finally:
        await client.close()
    return isinstance(reply, list) and len(reply) == 3 and reply[0] == 1


def is_local_host(host: str) -> bool:
    """True when ``host`` is a loopback name or an address of one of this machine's interfaces."""
    if is_loopback_host(host):
        return True
    try:
        infos = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except OSError:
        return False
    for family, _, _, _, address in infos:
        with socket.socket(family, socket.SOCK_STREAM) as probe:
            try:
                probe.bind((address[0], 0))
            except OSError:
                continue
            return True
    return False


async def ensure_master(master_uri: str | None = None) -> EmbeddedMaster | None:
    """Make sure a master answers at ``master_uri`` (default: ROS_MASTER_URI).

    Returns None when one already answers (it is reused), or the
    :class:`EmbeddedMaster` started on the running loop when none did and the
    URI's host is this machine.  Raises :class:`MasterStartError`, with
    a one-line reason, when no master answers and none can be started.
    """
    uri = master_uri_from_env(master_uri)
    if await master_answers(uri):
        return None
    parts = urlsplit(uri)
    host = parts.hostname or ""
    try:
        port = parts.port
    except ValueError:
        port = None
    if parts.scheme != "http" or not host or port is None:
        raise MasterStartError(f"ROS_MASTER_URI {uri} is not an http://host:port/ address")
    if not is_local_host(host):
        raise MasterStartError(
            f"no master answers at {uri}, and {host} is not this machine, so none can be started here")
    addressing = resolve_addressing(uri)
    # A shutdown call must not terminate the program this master lives in; its owner may await
    # master.wait_for_shutdown_request().
    master = Master(addressing.bind_host, port, advertise_host=host, terminate_process=False)
    try:
        await master.start()
    except OSError as exc:
        if exc.errno == errno.EADDRINUSE and await master_answers(uri):
            return None  # another master won the race for the port
        reason = "the port is in use by something that is not a ROS master" \
            if exc.errno == errno.EADDRINUSE else (exc.strerror or str(exc))
        raise MasterStartError(f"cannot start a master at {uri}: {reason}") from None
    rosout = RosoutNode(master.uri, master.run_id)
    try:
        await rosout.start()
    except BaseException:
        await master.stop()
        raise
    return EmbeddedMaster(master, rosout)

