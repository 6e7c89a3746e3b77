"""What `rostui node` does, as plain functions: rosnode's listing, info, ping, kill and cleanup.

Master calls go through ``call(method, *args)`` (the CLI binds the caller id
and turns an absent master into one error line); calls to nodes use the
blocking XML-RPC helper with a short timeout.  Text is formatted exactly as
rosnode prints it.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Collection, Iterable, Mapping, Sequence

from rostui.core import names

__all__ = [
    "SystemState",
    "quick_master_call",
    "system_state",
    "filter_namespace",
    "format_list",
    "NodeInfo",
    "node_info",
    "format_info",
    "ping_node",
    "PingError",
    "kill_nodes",
    "unreachable_nodes",
    "cleanup_nodes",
]

Call = Callable[..., Any]

#: How long to wait for a node's XML-RPC answer when pinging (rosnode's default).
PING_TIMEOUT = 3.0


def quick_master_call(caller_id: str, method: str, *args: Any, timeout: float = 0.5) -> Any:
    """One master call for shell completion: None on any failure, never an exception or output."""
    try:
        from rostui.core.network import master_uri_from_env
        from rostui.core.xmlrpc import call_sync, ros_result

        return ros_result(call_sync(master_uri_from_env(), method, caller_id, *args, timeout=timeout))
    except Exception:
        return None


class Registrations:
    """What one node holds, for anything with ``publishers``, ``subscribers`` and ``services`` maps (name -> nodes):
    the master's state here and the graph view's model (:class:`rostui.models.graph.model.RosGraph`)."""

    publishers: Mapping[str, Collection[str]]
    subscribers: Mapping[str, Collection[str]]
    services: Mapping[str, Collection[str]]

    def publications_of(self, node: str) -> list[str]:
        """Topics ``node`` publishes, sorted."""
        return sorted(t for t, nodes in self.publishers.items() if node in nodes)

    def subscriptions_of(self, node: str) -> list[str]:
        """Topics ``node`` subscribes to, sorted."""
        return sorted(t for t, nodes in self.subscribers.items() if node in nodes)

    def services_of(self, node: str) -> list[str]:
        """Services ``node`` provides, sorted."""
        return sorted(s for s, nodes in self.services.items() if node in nodes)


@dataclass
class SystemState(Registrations):
    """``getSystemState`` as three maps: topic/service name -> node names."""

    publishers: dict[str, list[str]] = field(default_factory=dict)
    subscribers: dict[str, list[str]] = field(default_factory=dict)
    services: dict[str, list[str]] = field(default_factory=dict)

    @classmethod
    def from_wire(cls, value: Sequence[Any]) -> "SystemState":
        """Build from the ``[publishers, subscribers, services]`` lists the master returns."""
        pubs, subs, srvs = (list(part) for part in value)
        return cls({t: list(n) for t, n in pubs}, {t: list(n) for t, n in subs}, {s: list(n) for s, n in srvs})

    def nodes(self) -> list[str]:
        """Every node that holds a registration, sorted."""
        found: set[str] = set()
        for part in (self.publishers, self.subscribers, self.services):
            for nodes in part.values():
                found.update(nodes)
        return sorted(found)



def system_state(call: Call) -> SystemState:
    """The master's current registrations."""
    return SystemState.from_wire(call("getSystemState"))


def script_resolve(name: str) -> str:
    """A node or namespace name typed on the command line, resolved in ROS_NAMESPACE."""
    import os

    return names.resolve_name(name, os.environ.get("ROS_NAMESPACE") or "/")


def filter_namespace(nodes: Iterable[str], namespace: str | None) -> list[str]:
    """``rosnode list NS``: nodes in ``namespace`` (or the node named exactly so)."""
    if not namespace:
        return list(nodes)
    prefix = names.make_global_ns(namespace)
    return [n for n in nodes if n == namespace or n.startswith(prefix)]


def lookup_uris(call: Call, nodes: Iterable[str]) -> dict[str, str | None]:
    """Each node's XML-RPC URI (None when the master no longer knows it)."""
    from rostui.core.xmlrpc import RosApiError

    uris: dict[str, str | None] = {}
    for node in nodes:
        try:
            uris[node] = call("lookupNode", node)
        except RosApiError:
            uris[node] = None
    return uris


def format_list(nodes: Sequence[str], uris: dict[str, str | None] | None, *, show_uri: bool,
                show_all: bool) -> str:
    """The lines ``rosnode list [-u] [-a]`` prints (the caller adds the final newline)."""
    if show_all:
        return "\n".join(f"{uris.get(n) if uris else None} \t{n}" for n in nodes)
    if show_uri:
        return "\n".join(str(uris.get(n) if uris else None) for n in nodes)
    return "\n".join(nodes)


# --------------------------------------------------------------------------- info


@dataclass
class NodeInfo:
    """What ``rosnode info`` reports about one node."""

    name: str
    publications: list[tuple[str, str]]
    subscriptions: list[tuple[str, str]]
    services: list[str]
    uri: str | None = None
    pid: int | None = None
    connections: list[dict[str, Any]] = field(default_factory=list)
    error: str | None = None

    def to_json(self) -> dict[str, Any]:
        """A machine-readable view (``--json``)."""
        return {
            "node": self.name,
            "uri": self.uri,
            "pid": self.pid,
            "publications": [{"topic": t, "type": ty} for t, ty in self.publications],
            "subscriptions": [{"topic": t, "type": ty} for t, ty in self.subscriptions],
            "services": list(self.services),
            "connections": self.connections,
            "error": self.error,
        }


_CPP_TRANSPORT = re.compile(r"^TCPROS connection on port (\d+) to \[(\S+) on socket (\d+)\]$")


def _peer_label(dest: str, topic: str, state: SystemState, uris: dict[str, str | None]) -> str:
    """``/node (http://...)`` for a peer given by URI, the name itself otherwise."""
    if not dest.startswith("http://"):
        return dest
    for node in state.publishers.get(topic, []) + state.subscribers.get(topic, []):
        if uris.get(node) == dest:
            return f"{node} ({dest})"
    for node, uri in uris.items():
        if uri == dest:
            return f"{node} ({dest})"
    return f"unknown ({dest})"


def node_info(call: Call, node: str, *, quiet: bool = False, timeout: float = PING_TIMEOUT) -> NodeInfo:
    """Collect ``rosnode info`` data: registrations, then (unless quiet) pid and connections."""
    from rostui.core.xmlrpc import RosApiError, XmlRpcError, call_sync, ros_result

    state = system_state(call)
    types = dict(call("getTopicTypes"))
    info = NodeInfo(
        node,
        [(t, types.get(t, "unknown type")) for t in state.publications_of(node)],
        [(t, types.get(t, "unknown type")) for t in state.subscriptions_of(node)],
        state.services_of(node),
    )
    try:
        info.uri = call("lookupNode", node)
    except RosApiError:
        info.error = f"cannot contact [{node}]: unknown node"
        return info
    if quiet:
        return info
    try:
        info.pid = ros_result(call_sync(info.uri, "getPid", "/rosnode", timeout=timeout))
        bus = ros_result(call_sync(info.uri, "getBusInfo", "/rosnode", timeout=timeout))
    except (XmlRpcError, RosApiError):
        info.error = f"ERROR: Communication with node[{info.uri}] failed!"
        return info
    uris = lookup_uris(call, state.nodes())
    for entry in bus:
        if len(entry) > 5 and not entry[5]:
            continue
        dest, direction, transport, topic = entry[1], entry[2], entry[3], entry[4]
        detail = entry[6] if len(entry) > 6 else ""
        info.connections.append({
            "topic": topic,
            "to": _peer_label(str(dest), topic, state, uris),
            "direction": {"i": "inbound", "o": "outbound", "b": "both"}.get(direction, "unknown"),
            "transport": transport,
            "detail": str(detail),
        })
    return info


def _section(title: str, items: list[str]) -> str:
    if not items:
        return f"{title}: None\n\n"
    return f"{title}: \n" + "".join(f" * {item}\n" for item in items) + "\n"


def format_info(info: NodeInfo, *, quiet: bool = False) -> tuple[str, str | None]:
    """(stdout text, stderr line or None) of ``rosnode info`` for one node."""
    out = "-" * 80 + "\n" + f"Node [{info.name}]\n"
    out += _section("Publications", [f"{t} [{ty}]" for t, ty in info.publications])
    out += _section("Subscriptions", [f"{t} [{ty}]" for t, ty in info.subscriptions])
    out += _section("Services", info.services)
    if info.uri is None or quiet:
        return out, info.error
    out += f"\ncontacting node {info.uri} ...\n"
    if info.pid is None:
        return out, info.error
    out += f"Pid: {info.pid}\n"
    if info.connections:
        out += "Connections:\n"
        for conn in info.connections:
            direction = conn["direction"]
            match = _CPP_TRANSPORT.match(conn["detail"])
            if match:
                direction += f" ({match.group(1)} - {match.group(2)}) [{match.group(3)}]"
            out += (f" * topic: {conn['topic']}\n    * to: {conn['to']}\n    * direction: {direction}\n"
                    f"    * transport: {conn['transport']}\n")
    out += "\n"
    return out, info.error


# --------------------------------------------------------------------------- ping


class PingError(Exception):
    """A node did not answer a ping; the message is rosnode's error line."""


def ping_node(uri: str, timeout: float = PING_TIMEOUT) -> float:
    """One XML-RPC round trip (``getPid``) to ``uri``; milliseconds, or PingError."""
    from rostui.core.xmlrpc import XmlRpcConnectionError, XmlRpcError, call_sync

    start = time.perf_counter()
    try:
        call_sync(uri, "getPid", "/rosnode", timeout=timeout)
    except XmlRpcConnectionError as exc:
        if "refused" in exc.reason:
            raise PingError(f"ERROR: connection refused to [{uri}]") from None
        if "within" in exc.reason:
            raise PingError(f"ERROR: connection to [{uri}] timed out") from None
        raise PingError(f"ERROR: connection to [{uri}] failed: {exc.reason}") from None
    except XmlRpcError as exc:
        raise PingError(f"ERROR: bad reply from [{uri}]: {exc}") from None
    return (time.perf_counter() - start) * 1000.0


# --------------------------------------------------------------------------- kill / cleanup


def kill_nodes(call: Call, nodes: Sequence[str], *, caller: str = "/rosnode") -> tuple[list[str], list[str]]:
    """Ask each node to shut down; return (killed, unknown)."""
    from rostui.core.xmlrpc import XmlRpcError, call_sync

    uris = lookup_uris(call, nodes)
    unknown = [n for n in nodes if uris.get(n) is None]
    killed: list[str] = []
    for node in nodes:
        uri = uris.get(node)
        if uri is None:
            continue
        try:
            call_sync(uri, "shutdown", caller, "user request", timeout=PING_TIMEOUT)
        except XmlRpcError:
            pass
        killed.append(node)
    return killed, unknown


def unreachable_nodes(call: Call, nodes: Iterable[str], *, timeout: float = PING_TIMEOUT,
                      on_error: Callable[[str], None] | None = None) -> list[str]:
    """Registered nodes whose slave API does not answer (sorted)."""
    uris = lookup_uris(call, nodes)
    dead: list[str] = []
    for node, uri in sorted(uris.items()):
        if uri is None:
            continue
        try:
            ping_node(uri, timeout)
        except PingError as exc:
            if on_error is not None:
                on_error(str(exc))
            dead.append(node)
    return dead


def cleanup_nodes(call: Call, dead: Iterable[str]) -> None:
    """Remove every registration of ``dead`` nodes from the master (like ``rosnode cleanup``)."""
    from rostui.core.xmlrpc import RosApiError

    state = system_state(call)
    for node in dead:
        try:
            uri = call("lookupNode", node)
        except RosApiError:
            continue
        for topic in state.publications_of(node):
            _as(node, "unregisterPublisher", topic, uri)
        for topic in state.subscriptions_of(node):
            _as(node, "unregisterSubscriber", topic, uri)
        for service in state.services_of(node):
            try:
                service_uri = call("lookupService", service)
            except RosApiError:
                continue
            _as(node, "unregisterService", service, service_uri)


def _as(node: str, method: str, *args: Any) -> None:
    """A master call made in the dead node's name (the master only honours its own caller id)."""
    from rostui.core.network import master_uri_from_env
    from rostui.core.xmlrpc import XmlRpcError, call_sync

    try:
        call_sync(master_uri_from_env(), method, node, *args, timeout=10.0)
    except XmlRpcError:
        pass
