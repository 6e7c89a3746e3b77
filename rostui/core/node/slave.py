"""The slave (node) XML-RPC API that the master and other nodes call."""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, Protocol

from rostui.core.network import Addressing
from rostui.core.node.params import ParamCache
from rostui.core.node.services import ServiceServer
from rostui.core.node.topics import Publication, Subscription

Result = list[Any]


class SlaveHost(Protocol):
    """What the slave API reads and calls on its node (an AsyncNode is one)."""

    @property
    def master_uri(self) -> str:
        """The master the node registered with."""

    @property
    def addressing(self) -> Addressing:
        """How the node's servers are reached (``advertise_host``)."""

    @property
    def tcpros_port(self) -> int:
        """The port of the node's TCPROS server."""

    @property
    def publications(self) -> Mapping[str, Publication]:
        """The node's publications by topic."""

    @property
    def subscriptions(self) -> Mapping[str, Subscription]:
        """The node's subscriptions by topic."""

    @property
    def services(self) -> Mapping[str, ServiceServer]:
        """The node's services by name."""

    @property
    def params(self) -> ParamCache:
        """The node's cache of subscribed parameters."""

    def next_connection_id(self) -> int:
        """A fresh id for a connection (getBusInfo)."""

    def request_shutdown(self, reason: str) -> None:
        """Begin shutting the node down."""


class SlaveApi:
    """XML-RPC methods every ROS node serves; each returns ``[code, msg, value]``."""

    def __init__(self, node: SlaveHost) -> None:
        self._node = node

    def getBusStats(self, caller_id: str) -> Result:
        """Per-connection byte and message counters."""
        node = self._node
        pubs = [[p.topic, p.messages_published,
                 [[link.id, link.bytes_sent, link.messages_sent, True] for link in p.links]]
                for p in node.publications.values()]
        subs = [[s.topic, [[i, c.bytes_received, 0, True]
                           for i, c in enumerate(s.connections.values()) if c is not None]]
                for s in node.subscriptions.values()]
        calls = sum(s.calls for s in node.services.values())
        return [1, "", [pubs, subs, [calls, 0, 0]]]

    def getBusInfo(self, caller_id: str) -> Result:
        """Every connection: id, peer, direction, transport, topic, connected."""
        node = self._node
        info: list[list[Any]] = []
        for pub in node.publications.values():
            for link in pub.links:
                info.append([link.id, link.callerid, "o", "TCPROS", pub.topic, True,
                             f"TCPROS connection on port {node.tcpros_port} to [{link.callerid}]"])
            for sub in pub.local:
                info.append([node.next_connection_id(), sub.node.name, "o", "INTRAPROCESS", pub.topic, True, ""])
        for sub in node.subscriptions.values():
            for uri, conn in sub.connections.items():
                if conn is not None and conn.header is not None:
                    info.append([node.next_connection_id(), uri, "i", "TCPROS", sub.topic, True,
                                 f"TCPROS connection to [{conn.header.get('callerid', uri)}]"])
            for uri in sub.local_pubs:
                info.append([node.next_connection_id(), uri, "i", "INTRAPROCESS", sub.topic, True, ""])
        return [1, "bus info", info]

    def getMasterUri(self, caller_id: str) -> Result:
        """The master this node registered with."""
        return [1, "", self._node.master_uri]

    def shutdown(self, caller_id: str, msg: str = "") -> Result:
        """Ask the node to shut down (e.g. a new node took its name)."""
        self._node.request_shutdown(msg or f"shutdown request from {caller_id}")
        return [1, "shutdown", 0]

    def getPid(self, caller_id: str) -> Result:
        """The node's process id."""
        return [1, "", os.getpid()]

    def getSubscriptions(self, caller_id: str) -> Result:
        """``[[topic, type], ...]`` this node subscribes to."""
        return [1, "subscriptions", [[s.topic, s.type_name] for s in self._node.subscriptions.values()]]

    def getPublications(self, caller_id: str) -> Result:
        """``[[topic, type], ...]`` this node publishes."""
        return [1, "publications", [[p.topic, p.topic_type.type] for p in self._node.publications.values()]]

    def paramUpdate(self, caller_id: str, key: str, value: Any) -> Result:
        """A subscribed parameter changed."""
        self._node.params.update(key, value)
        return [1, "", 0]

    def publisherUpdate(self, caller_id: str, topic: str, publishers: list[str]) -> Result:
        """The master's list of publishers of a topic we subscribe to."""
        sub = self._node.subscriptions.get(topic)
        if sub is not None:
            sub.update_publishers(list(publishers))
        return [1, "", 0]

    def requestTopic(self, caller_id: str, topic: str, protocols: list[Any]) -> Result:
        """Offer a TCPROS endpoint for a topic we publish."""
        if topic not in self._node.publications:
            return [-1, f"Not a publisher of [{topic}]", []]
        for proto in protocols:
            if isinstance(proto, list) and proto and proto[0] == "TCPROS":
                host = self._node.addressing.advertise_host
                return [1, f"ready on {host}:{self._node.tcpros_port}", ["TCPROS", host, self._node.tcpros_port]]
        return [0, "no supported protocol implementations", []]
