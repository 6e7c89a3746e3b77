"""The Master API and Parameter Server API, as XML-RPC methods.

:class:`MasterHandler` answers every call rosmaster answers, with the same
status codes, messages and value shapes.  It is meant to be served by
:class:`rostui.core.xmlrpc.XmlRpcServer` on an asyncio loop; notifications
are queued on a :class:`~rostui.core.master.notify.Notifier` and never awaited.

Values returned by query methods may share structure with the master's own
tables: serialise them, do not mutate them.
"""

from __future__ import annotations

import asyncio
import logging
import os
from typing import Any, Callable

from rostui.core.names import SEP
from rostui.core.names import canonicalize_name as canonicalize
from rostui.core.names import resolve_for_caller as resolve
from .notify import Notifier
from .params import ParamTree, Update, compute_updates
from .registrations import PUBLICATIONS, NodeRef, RegistrationManager
from .validate import (
    ANYTYPE, api, empty_or_valid_name, is_api, is_graph_resource, non_empty_str, not_none,
    valid_name, valid_type_name,
)

_log = logging.getLogger("rostui.master")

ApiReturn = tuple[int, str, Any]

REPLACED_REASON = "new node registered with same name"

SETTLE_SECONDS = 2.0
"""How long after a registerSubscriber a publisher change is sent to the subscriber a second time.

A node may handle a publisherUpdate before the registerSubscriber reply that was computed earlier: rospy
then keeps the reply's older list as the newest and never connects (roscpp drops the connection). The
master cannot see when the node handled its reply, so it repeats the current list once, later."""


class MasterHandler:
    """The XML-RPC methods of a ROS 1 master (graph registrations + parameter server)."""

    def __init__(self, notifier: Notifier | None = None,
                 on_shutdown: Callable[[str], None] | None = None) -> None:
        self.uri = ""
        self.notifier = notifier or Notifier()
        self.reg = RegistrationManager(self._node_replaced)
        self.params = ParamTree()
        self.topic_types: dict[str, str] = {}
        self._on_shutdown = on_shutdown
        self._settling: dict[tuple[str, str], bool] = {}

    # -- internal ----------------------------------------------------------

    def _node_replaced(self, old: NodeRef, removed: dict[str, list[str]]) -> None:
        _log.info("node %s re-registered from a new URI; shutting down %s", old.id, old.api)
        self.notifier.shutdown_node(old.api, f"[{old.id}] Reason: {REPLACED_REASON}")
        for topic in removed.get(PUBLICATIONS, ()):
            self._notify_subscribers(topic)

    def _notify_subscribers(self, topic: str) -> list[str]:
        """Send *topic*'s publishers to each of its subscribers; the subscribers' URIs."""
        subs = self.reg.subscribers.get_apis(topic)
        if subs:
            pubs = self.reg.publishers.get_apis(topic)
            for sub_api in subs:
                self.notifier.publisher_update(sub_api, topic, pubs)
                if (sub_api, topic) in self._settling:
                    self._settling[(sub_api, topic)] = True
        return subs

    def _settle(self, sub_api: str, topic: str) -> None:
        """Repeat *topic*'s publishers to a subscriber registered :data:`SETTLE_SECONDS` ago, if they changed since."""
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            return  # called outside a served master (a unit test of the handler): nothing to repeat later
        key = (sub_api, topic)
        self._settling[key] = False

        def repeat() -> None:
            if self._settling.pop(key, False) and sub_api in self.reg.subscribers.get_apis(topic):
                self.notifier.publisher_update(sub_api, topic, self.reg.publishers.get_apis(topic))

        loop.call_later(SETTLE_SECONDS, repeat)

    def _notify_params(self, updates: list[Update]) -> None:
        for subscribers, key, value in updates:
            for caller_id, caller_api in subscribers:
                self.notifier.param_update(
                    caller_api, key, value, self._param_result_handler(caller_id, caller_api, key))

    def _param_result_handler(self, caller_id: str, caller_api: str, key: str) -> Callable[[Any], None]:
        def on_result(result: Any) -> None:
            # A node answering -1 no longer wants this parameter.
            if isinstance(result, (list, tuple)) and result and result[0] == -1:
                self.reg.unregister_param_subscriber(key, caller_id, caller_api)
        return on_result

    # -- node-level API ----------------------------------------------------

    @api(0, (None,))
    def shutdown(self, caller_id: str, msg: str) -> ApiReturn:
        """Ask the master to stop (it stops once its owner reacts)."""
        _log.info("shutdown request from %s: %s", caller_id, msg)
        if self._on_shutdown is not None:
            self._on_shutdown(str(msg))
        return 1, "shutdown", 0

    @api("")
    def getUri(self, caller_id: str) -> ApiReturn:
        """The master's XML-RPC URI."""
        return 1, "", self.uri

    @api(-1)
    def getPid(self, caller_id: str) -> ApiReturn:
        """The master's process id."""
        return 1, "", os.getpid()

    # -- parameter server --------------------------------------------------

    @api(0, (non_empty_str("key"),))
    def deleteParam(self, caller_id: str, key: str) -> ApiReturn:
        """Delete a parameter (or a whole namespace)."""
        key = resolve(key, caller_id)
        try:
            self.params.delete(key)
        except KeyError:
            return -1, f"parameter [{key}] is not set", 0
        if self.reg.param_subscribers:
            self._notify_params(compute_updates(self.reg.param_subscribers, key, {}))
        return 1, f"parameter {key} deleted", 0

    @api(0, (non_empty_str("key"), not_none("value")))
    def setParam(self, caller_id: str, key: str, value: Any) -> ApiReturn:
        """Set a parameter; a dict value replaces the namespace ``key``."""
        key = resolve(key, caller_id)
        self.params.set(key, value)
        if self.reg.param_subscribers:
            self._notify_params(compute_updates(self.reg.param_subscribers, key, value, caller_id))
        return 1, f"parameter {key} set", 0

    @api(0, (non_empty_str("key"),))
    def getParam(self, caller_id: str, key: str) -> ApiReturn:
        """A parameter's value; a namespace returns a dict of everything under it."""
        key = resolve(key, caller_id)
        try:
            return 1, f"Parameter [{key}]", self.params.get(key)
        except KeyError:
            return -1, f"Parameter [{key}] is not set", 0

    @api(0, (non_empty_str("key"),))
    def searchParam(self, caller_id: str, key: str) -> ApiReturn:
        """Find ``key`` from the caller's namespace upwards (rosmaster's algorithm)."""
        found = self.params.search(caller_id, key)
        if found:
            return 1, f"Found [{found}]", found
        return -1, f"Cannot find parameter [{key}] in an upwards search", ""

    @api(0, (is_api("caller_api"), non_empty_str("key")))
    def subscribeParam(self, caller_id: str, caller_api: str, key: str) -> ApiReturn:
        """Return a parameter's value ({} if unset) and send paramUpdate on changes."""
        key = resolve(key, caller_id)
        sub_key = key if key == SEP else canonicalize(key) + SEP
        try:
            value = self.params.get(sub_key)
        except KeyError:
            value = {}
        self.reg.register_param_subscriber(sub_key, caller_id, caller_api)
        return 1, f"Subscribed to parameter [{key}]", value

    @api(0, (is_api("caller_api"), non_empty_str("key")))
    def unsubscribeParam(self, caller_id: str, caller_api: str, key: str) -> ApiReturn:
        """Stop paramUpdate notifications for ``key``."""
        key = resolve(key, caller_id)
        sub_key = key if key == SEP else canonicalize(key) + SEP
        self.reg.unregister_param_subscriber(sub_key, caller_id, caller_api)
        return 1, f"Unsubscribe to parameter [{key}]", 1

    @api(False, (non_empty_str("key"),))
    def hasParam(self, caller_id: str, key: str) -> ApiReturn:
        """Whether ``key`` is set."""
        key = resolve(key, caller_id)
        return 1, key, self.params.has(key)

    @api([])
    def getParamNames(self, caller_id: str) -> ApiReturn:
        """Every parameter name on the server."""
        return 1, "Parameter names", self.params.names()

    # -- services ----------------------------------------------------------

    @api(0, (is_graph_resource("service"), is_api("service_api"), is_api("caller_api")))
    def registerService(self, caller_id: str, service: str, service_api: str,
                        caller_api: str) -> ApiReturn:
        """Register the caller as the provider of ``service``."""
        self.reg.register_service(service, caller_id, caller_api, service_api)
        return 1, f"Registered [{caller_id}] as provider of [{service}]", 1

    @api("", (is_graph_resource("service"),))
    def lookupService(self, caller_id: str, service: str) -> ApiReturn:
        """The rosrpc:// URI of ``service``'s provider."""
        url = self.reg.services.get_service_api(service)
        if url:
            return 1, f"rosrpc URI: [{url}]", url
        return -1, "no provider", ""

    @api(0, (is_graph_resource("service"), is_api("service_api")))
    def unregisterService(self, caller_id: str, service: str, service_api: str) -> ApiReturn:
        """Unregister the caller as provider of ``service`` (if still current)."""
        return self.reg.unregister_service(service, caller_id, service_api)

    # -- topics ------------------------------------------------------------

    @api([], (is_graph_resource("topic"), valid_type_name("topic_type"), is_api("caller_api")))
    def registerSubscriber(self, caller_id: str, topic: str, topic_type: str,
                           caller_api: str) -> ApiReturn:
        """Subscribe the caller to ``topic``; returns the current publisher URIs."""
        self.reg.register_subscriber(topic, caller_id, caller_api)
        if topic_type != ANYTYPE and topic not in self.topic_types:
            self.topic_types[topic] = topic_type
        self._settle(caller_api, topic)
        return 1, f"Subscribed to [{topic}]", self.reg.publishers.get_apis(topic)

    @api(0, (is_graph_resource("topic"), is_api("caller_api")))
    def unregisterSubscriber(self, caller_id: str, topic: str, caller_api: str) -> ApiReturn:
        """Unregister the caller as a subscriber of ``topic``."""
        return self.reg.unregister_subscriber(topic, caller_id, caller_api)

    @api([], (is_graph_resource("topic"), valid_type_name("topic_type"), is_api("caller_api")))
    def registerPublisher(self, caller_id: str, topic: str, topic_type: str,
                          caller_api: str) -> ApiReturn:
        """Register the caller as a publisher of ``topic``; returns the subscriber URIs."""
        self.reg.register_publisher(topic, caller_id, caller_api)
        if topic_type != ANYTYPE or topic not in self.topic_types:
            self.topic_types[topic] = topic_type
        subs = self._notify_subscribers(topic)
        return 1, f"Registered [{caller_id}] as publisher of [{topic}]", subs

    @api(0, (is_graph_resource("topic"), is_api("caller_api")))
    def unregisterPublisher(self, caller_id: str, topic: str, caller_api: str) -> ApiReturn:
        """Unregister the caller as a publisher of ``topic``; subscribers are told."""
        result = self.reg.unregister_publisher(topic, caller_id, caller_api)
        if result[2]:
            self._notify_subscribers(topic)
        return result

    # -- graph state -------------------------------------------------------

    @api("", (valid_name("node"),))
    def lookupNode(self, caller_id: str, node_name: str) -> ApiReturn:
        """The XML-RPC URI of the node ``node_name``."""
        node = self.reg.get_node(node_name)
        if node is not None:
            return 1, "node api", node.api
        return -1, f"unknown node [{node_name}]", ""

    @api(0, (empty_or_valid_name("subgraph"),))
    def getPublishedTopics(self, caller_id: str, subgraph: str) -> ApiReturn:
        """``[[topic, type], ...]`` for topics with publishers, under ``subgraph``."""
        if subgraph and subgraph[-1] != SEP:
            subgraph += SEP
        types = self.topic_types
        return 1, "current topics", [
            [t, types[t]] for t in self.reg.publishers.keys() if t.startswith(subgraph)]

    @api([])
    def getTopicTypes(self, caller_id: str) -> ApiReturn:
        """``[[topic, type], ...]`` for every topic ever registered with a type."""
        return 1, "current system state", [[t, ty] for t, ty in self.topic_types.items()]

    @api([[], [], []])
    def getSystemState(self, caller_id: str) -> ApiReturn:
        """``[publishers, subscribers, services]``, each ``[[name, [node, ...]], ...]``."""
        reg = self.reg
        return 1, "current system state", [
            reg.publishers.get_state(), reg.subscribers.get_state(), reg.services.get_state()]
