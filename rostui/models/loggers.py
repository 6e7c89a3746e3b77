"""Logger levels of running nodes, read and set as rqt_logger_level does (no UI here).

Every roscpp, rospy and rostui node serves ``<node>/get_loggers`` and
``<node>/set_logger_level`` (roscpp/GetLoggers, roscpp/SetLoggerLevel).
:class:`LoggerLevels` finds those nodes in the master's service list and calls
the services from an unannounced node on the caller's event loop, with a
timeout on every call.  Each failure is one line naming what went wrong: the
master (:class:`~rostui.core.master_errors.MasterUnreachableError`, as
everywhere in rostui), the node or the service (a :class:`LoggerToolError`);
:data:`LOGGER_ERRORS` holds both.

Nodes spell levels differently: roscpp and rostui answer ``info``, rospy
``INFO``.  Levels are shown upper case; requests send upper case names,
which all three accept (their ``set_logger_level`` is case-insensitive).
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from typing import Any, Iterable, Sequence

from rostui.core.log import Level
from rostui.core.master_errors import MasterUnreachableError
from rostui.models.calling_node import CallingNode

__all__ = [
    "LEVEL_NAMES",
    "GET_LOGGERS",
    "SET_LOGGER_LEVEL",
    "DEFAULT_TIMEOUT",
    "LoggerNode",
    "LoggerLevel",
    "LOGGER_ERRORS",
    "LoggerToolError",
    "NodeGoneError",
    "ServiceFailedError",
    "ServiceTimeoutError",
    "display_level",
    "request_level",
    "logger_nodes",
    "preferred_logger",
    "LoggerLevels",
    "resolve_node_name",
    "fetch_loggers",
    "change_level",
    "format_loggers",
]

#: The levels a logger can be set to, lowest first.
LEVEL_NAMES: tuple[str, ...] = tuple(level.name for level in Level)

#: The services every node offers under its own name.
GET_LOGGERS = "get_loggers"
SET_LOGGER_LEVEL = "set_logger_level"

#: Seconds a master query or a service call may take before it counts as failed.
DEFAULT_TIMEOUT = 3.0


@dataclass(frozen=True)
class LoggerNode:
    """A node that serves ``get_loggers``; ``can_set`` when it also serves ``set_logger_level``."""

    name: str
    can_set: bool = True


@dataclass(frozen=True)
class LoggerLevel:
    """One logger of a node: its name, its level as shown (``DEBUG``...) and as the node spelled it."""

    name: str
    level: str
    raw: str


class LoggerToolError(Exception):
    """A one-line, user-facing reason a logger query or change failed."""


class NodeGoneError(LoggerToolError):
    """The node no longer serves its logger services or does not accept connections."""


class ServiceFailedError(LoggerToolError):
    """The node answered the call with an error, or dropped the connection."""


class ServiceTimeoutError(LoggerToolError):
    """The node did not answer within the timeout."""


#: Everything a logger query or change raises for the user to read: the master, the node, the service.
LOGGER_ERRORS: tuple[type[Exception], ...] = (LoggerToolError, MasterUnreachableError)


def display_level(text: str) -> str:
    """A level as shown to the user: ``DEBUG``...``FATAL``; anything else upper-cased as sent."""
    try:
        return Level.parse(text).name
    except ValueError:
        return str(text).strip().upper()


def request_level(level: str | Level) -> str:
    """The level name to send in a SetLoggerLevel request (``DEBUG``...); ValueError if unknown."""
    return Level.parse(level).name


def logger_nodes(services: Iterable[Sequence[Any]]) -> list[LoggerNode]:
    """Nodes serving ``<node>/get_loggers``, sorted, from getSystemState's ``[service, providers]`` list."""
    names = {str(entry[0]) for entry in services}
    suffix = "/" + GET_LOGGERS
    found = []
    for service in names:
        if service.endswith(suffix) and len(service) > len(suffix):
            node = service[: -len(suffix)]
            found.append(LoggerNode(node, can_set=f"{node}/{SET_LOGGER_LEVEL}" in names))
    return sorted(found, key=lambda n: n.name)


def preferred_logger(names: Sequence[str]) -> str | None:
    """The logger a user most likely wants to change on a node (the book: "almost certainly ros.<package>").

    rospy's user messages go through ``rosout``; roscpp's and rostui's through
    ``ros.<package>``, next to roscpp's internal ``ros.roscpp*`` loggers.  Falls
    back to the root ``ros``, then to the first name.
    """
    if "rosout" in names and any(name == "rospy" or name.startswith("rospy.") for name in names):
        return "rosout"
    for name in names:
        parts = name.split(".")
        if len(parts) == 2 and parts[0] == "ros" and parts[1] != "roscpp":
            return name
    if "ros" in names:
        return "ros"
    return names[0] if names else None


class LoggerLevels(CallingNode):
    """Lists logger nodes and reads and sets their levels, on the running event loop.

    The node used for the calls registers nothing with the master, so it does
    not appear in node lists.  Call :meth:`start` before use and :meth:`close`
    when done.
    """

    def __init__(self, master_uri: str | None = None, *, timeout: float = DEFAULT_TIMEOUT) -> None:
        super().__init__("rostui_loggers", master_uri, "rostui loggers done")
        self.timeout = timeout

    async def nodes(self) -> list[LoggerNode]:
        """Nodes that serve ``get_loggers`` now, sorted by name."""
        from rostui.core.master_errors import MasterError

        try:
            _, _, services = await asyncio.wait_for(self.node.master_call("getSystemState"), self.timeout)
        except asyncio.TimeoutError:
            raise MasterUnreachableError(self.master_uri, f"no answer within {self.timeout:g} s") from None
        except MasterError:
            raise MasterUnreachableError(self.master_uri) from None
        return logger_nodes(services)

    async def ping(self, node: str) -> int:
        """The pid of ``node``, asked through its slave API (``rosnode ping``), without touching its loggers.

        NodeGoneError when the master no longer knows it or it does not answer;
        ServiceTimeoutError when it accepts but does not answer in time.
        """
        from rostui.core.master_errors import MasterRefusedError
        from rostui.core.xmlrpc import RosApiError, XmlRpcClient, XmlRpcConnectionError, XmlRpcError, ros_result

        try:
            uri = await asyncio.wait_for(self.node.master_call("lookupNode", node), self.timeout)
        except asyncio.TimeoutError:
            raise MasterUnreachableError(self.master_uri, f"no answer within {self.timeout:g} s") from None
        except MasterUnreachableError:
            raise MasterUnreachableError(self.master_uri) from None
        except MasterRefusedError:
            raise _unlisted(node) from None
        client = XmlRpcClient(str(uri), timeout=self.timeout + 1.0)  # wait_for below decides the timeout
        try:
            return int(ros_result(await asyncio.wait_for(client.call("getPid", self.node.name), self.timeout)))
        except asyncio.TimeoutError:
            raise ServiceTimeoutError(f"node {node} did not answer within {self.timeout:g} s") from None
        except XmlRpcConnectionError as exc:
            raise await self._gone_or_dead(node, exc.reason) from None
        except (XmlRpcError, RosApiError, ValueError, TypeError) as exc:
            raise ServiceFailedError(f"node {node} answered getPid wrongly: {exc}") from None
        finally:
            await client.close()

    async def loggers(self, node: str) -> list[LoggerLevel]:
        """The loggers of ``node`` with their levels, sorted by name."""
        response = await self._call(node, GET_LOGGERS, "roscpp/GetLoggers")
        items = [LoggerLevel(item.name, display_level(item.level), item.level) for item in response.loggers]
        return sorted(items, key=lambda item: item.name)

    async def set_level(self, node: str, logger: str, level: str | Level) -> str:
        """Set ``logger`` of ``node`` to ``level``; returns the level name sent.

        ValueError (before any call) for a level that is not DEBUG, INFO, WARN, ERROR or FATAL.
        """
        name = request_level(level)
        await self._call(node, SET_LOGGER_LEVEL, "roscpp/SetLoggerLevel", logger=logger, level=name)
        return name

    async def _call(self, node: str, service: str, type_name: str, **fields: Any) -> Any:
        from rostui.core.msg import get_service_class
        from rostui.core.master_errors import MasterRefusedError
        from rostui.core.node.services import ServiceException

        name = f"{node.rstrip('/')}/{service}"
        proxy = self.node.service_proxy(name, get_service_class(type_name))
        try:
            return await asyncio.wait_for(proxy.call(**fields), self.timeout)
        except asyncio.TimeoutError:
            raise ServiceTimeoutError(f"{name} did not answer within {self.timeout:g} s") from None
        except ServiceException as exc:
            cause = exc.__cause__
            if isinstance(cause, MasterUnreachableError):
                raise MasterUnreachableError(self.master_uri) from None
            if isinstance(cause, MasterRefusedError):
                raise NodeGoneError(f"{name} is not registered with the master: node {node} is not running") \
                    from None
            if isinstance(cause, OSError):
                raise await self._gone_or_dead(node, _reason(cause)) from None
            raise ServiceFailedError(f"{name} failed: {exc}") from None

    async def _gone_or_dead(self, node: str, reason: str) -> NodeGoneError:
        """Why ``node`` could not be reached (``reason``): shut down (the master no longer lists it: a node that
        shut down between our look-up and our call) or, while the master still lists it, probably died."""
        from rostui.core.master_errors import MasterError, MasterRefusedError

        try:
            await asyncio.wait_for(self.node.master_call("lookupNode", node), self.timeout)
        except MasterRefusedError:
            return _unlisted(node)
        except (asyncio.TimeoutError, MasterError):
            pass
        return NodeGoneError(f"node {node} does not answer ({reason}): it has probably died")


def resolve_node_name(name: str) -> str:
    """A node name typed by the user, made global in ``ROS_NAMESPACE`` (as rosnode does)."""
    import os

    from rostui.core import names

    return names.resolve_name(name.rstrip("/") or "/", os.environ.get("ROS_NAMESPACE") or "/")


def fetch_loggers(node: str, *, master_uri: str | None = None,
                  timeout: float = DEFAULT_TIMEOUT) -> list[LoggerLevel]:
    """The loggers of ``node`` (blocking; runs its own event loop)."""
    async def run() -> list[LoggerLevel]:
        client = await LoggerLevels(master_uri, timeout=timeout).start()
        try:
            return await client.loggers(node)
        finally:
            await client.close()

    return asyncio.run(run())


def change_level(node: str, logger: str, level: str, *, master_uri: str | None = None,
                 timeout: float = DEFAULT_TIMEOUT) -> str:
    """Set one logger's level (blocking); returns the level name sent.  ValueError for an unknown level."""
    name = request_level(level)

    async def run() -> str:
        client = await LoggerLevels(master_uri, timeout=timeout).start()
        try:
            return await client.set_level(node, logger, name)
        finally:
            await client.close()

    return asyncio.run(run())


def format_loggers(items: Sequence[LoggerLevel]) -> str:
    """One ``logger  LEVEL`` line per logger, levels aligned in a column."""
    width = max((len(item.name) for item in items), default=0)
    return "".join(f"{item.name.ljust(width)}  {item.level}\n" for item in items)


def _unlisted(node: str) -> NodeGoneError:
    """``node`` is gone: the master no longer lists it (it shut down)."""
    return NodeGoneError(f"node {node} is gone: the master no longer lists it")


def _reason(error: OSError) -> str:
    """``connection refused`` and the like, from an OSError."""
    for kind, text in ((ConnectionRefusedError, "connection refused"), (ConnectionResetError, "connection reset"),
                       (TimeoutError, "connection timed out")):
        if isinstance(error, kind):
            return text
    text = error.strerror or str(error) or type(error).__name__
    return text[:1].lower() + text[1:]
