"""rosgraph.masterapi: the ROS master's XML-RPC API as methods that return the value or raise.

``Master(caller_id)`` calls the master at ``ROS_MASTER_URI`` (or the URI given) with the caller id resolved
in this process's namespace. A reply with code 1 gives its value; code -1 raises ``MasterError``, any other
``MasterFailure``. A master that cannot be reached raises the socket's own error (``ConnectionRefusedError``),
as Python's XML-RPC client does: scripts catch ``socket.error`` for that.
"""

from __future__ import annotations

import xmlrpc.client
from typing import Any
from urllib.parse import urlsplit

from .names import make_caller_id
from .rosenv import get_master_uri

__all__ = ["Error", "Failure", "Master", "MasterError", "MasterException", "MasterFailure", "ROSMasterException",
           "is_online"]


class MasterException(Exception):
    """The base of the master's errors."""


class MasterFailure(MasterException):
    """The master failed to do what it was asked (code 0): it may be in a bad state."""


class MasterError(MasterException):
    """The master refused the call's arguments (code -1)."""


ROSMasterException = MasterException
Error = MasterError
Failure = MasterFailure


def _check_uri(master_uri: str | None) -> str:
    if master_uri is None:
        raise ValueError("ROS master URI is not set")
    try:
        parts = urlsplit(master_uri)
        valid = bool(parts.scheme) and bool(parts.hostname)
        parts.port  # noqa: B018 (a port that is no number is a ValueError)
    except ValueError:
        valid = False
    if not valid:
        raise ValueError(f"invalid master URI: {master_uri}")
    return master_uri


class Master:
    """The master's API for the program *caller_id* (relative names are resolved in ``ROS_NAMESPACE``)."""

    def __init__(self, caller_id: str, master_uri: str | None = None) -> None:
        self._reinit(master_uri if master_uri is not None else get_master_uri())
        self.caller_id = make_caller_id(caller_id)
        if self.caller_id.endswith("/"):
            self.caller_id = self.caller_id[:-1]

    def _reinit(self, master_uri: str | None) -> None:
        self.master_uri = _check_uri(master_uri)
        self.handle = xmlrpc.client.ServerProxy(self.master_uri)

    def is_online(self) -> bool:
        """Whether the master answers ``getPid``."""
        try:
            self.getPid()
        except Exception:
            return False
        return True

    @staticmethod
    def _succeed(args: Any) -> Any:
        code, msg, val = args
        if code == 1:
            return val
        if code == -1:
            raise MasterError(msg)
        raise MasterFailure(msg)

    def _call(self, method: str, *args: Any) -> Any:
        return self._succeed(getattr(self.handle, method)(self.caller_id, *args))

    def deleteParam(self, key: str) -> Any:  # noqa: N802 (the master API's names)
        """Delete a parameter (or a namespace of them)."""
        return self._call("deleteParam", key)

    def setParam(self, key: str, value: Any) -> Any:  # noqa: N802
        """Set a parameter; a dict replaces the whole namespace *key*."""
        return self._call("setParam", key, value)

    def getParam(self, key: str) -> Any:  # noqa: N802
        """A parameter's value (a dict for a namespace); MasterError when it is not set."""
        return self._call("getParam", key)

    def searchParam(self, key: str) -> Any:  # noqa: N802
        """The closest parameter named *key* up from the caller's namespace."""
        return self._call("searchParam", key)

    def subscribeParam(self, caller_api: str, key: str) -> Any:  # noqa: N802
        """A parameter's value, and paramUpdate calls to *caller_api* when it changes."""
        return self._call("subscribeParam", caller_api, key)

    def unsubscribeParam(self, caller_api: str, key: str) -> Any:  # noqa: N802
        """Stop the paramUpdate calls for *key*."""
        return self._call("unsubscribeParam", caller_api, key)

    def hasParam(self, key: str) -> Any:  # noqa: N802
        """Whether a parameter is set."""
        return self._call("hasParam", key)

    def getParamNames(self) -> Any:  # noqa: N802
        """Every parameter name on the server."""
        return self._call("getParamNames")

    def getPid(self) -> Any:  # noqa: N802
        """The master's process id."""
        return self._call("getPid")

    def getUri(self) -> Any:  # noqa: N802
        """The master's URI."""
        return self._call("getUri")

    def registerService(self, service: str, service_api: str, caller_api: str) -> Any:  # noqa: N802
        """Register the caller as the provider of *service*."""
        return self._call("registerService", service, service_api, caller_api)

    def lookupService(self, service: str) -> Any:  # noqa: N802
        """The rosrpc URI of *service*'s provider."""
        return self._call("lookupService", service)

    def unregisterService(self, service: str, service_api: str) -> Any:  # noqa: N802
        """Unregister the caller as *service*'s provider."""
        return self._call("unregisterService", service, service_api)

    def registerSubscriber(self, topic: str, topic_type: str, caller_api: str) -> Any:  # noqa: N802
        """Subscribe the caller to *topic*; the publishers' URIs."""
        return self._call("registerSubscriber", topic, topic_type, caller_api)

    def unregisterSubscriber(self, topic: str, caller_api: str) -> Any:  # noqa: N802
        """Unsubscribe the caller from *topic*."""
        return self._call("unregisterSubscriber", topic, caller_api)

    def registerPublisher(self, topic: str, topic_type: str, caller_api: str) -> Any:  # noqa: N802
        """Register the caller as a publisher of *topic*; the subscribers' URIs."""
        return self._call("registerPublisher", topic, topic_type, caller_api)

    def unregisterPublisher(self, topic: str, caller_api: str) -> Any:  # noqa: N802
        """Unregister the caller as a publisher of *topic*."""
        return self._call("unregisterPublisher", topic, caller_api)

    def lookupNode(self, node_name: str) -> Any:  # noqa: N802
        """The XML-RPC URI of the node *node_name*."""
        return self._call("lookupNode", node_name)

    def getPublishedTopics(self, subgraph: str) -> Any:  # noqa: N802
        """[[topic, type], ...] of the published topics under *subgraph* ('' for all)."""
        return self._call("getPublishedTopics", subgraph)

    def getTopicTypes(self) -> Any:  # noqa: N802
        """[[topic, type], ...] of every topic the master knows."""
        return self._call("getTopicTypes")

    def getSystemState(self) -> Any:  # noqa: N802
        """[publishers, subscribers, services], each [[name, [node, ...]], ...]."""
        return self._call("getSystemState")


def is_online(master_uri: str | None = None) -> bool:
    """Whether the master (``ROS_MASTER_URI`` by default) answers."""
    return Master("rosgraph", master_uri=master_uri).is_online()
