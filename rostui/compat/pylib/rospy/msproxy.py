"""rospy.msproxy: ``MasterProxy``, the master's XML-RPC API with this node's caller id and names filled in.

``master.getParam("~gain")`` sends ``getParam(caller_id, resolved name)`` and
returns the master's ``[code, statusMessage, value]`` as it is; the
parameter server also reads and writes like a dict (``master["/p"] = 1``).
"""

from __future__ import annotations

import sys
import threading
import xmlrpc.client
from typing import Any, Callable, Iterator

from rostui.core import names as _names
from rostui.core.masteruri import master_uri_from_env
from rostui.core.node import sync as _sync
from rostui.core.xmlrpc import XmlRpcConnectionError, XmlRpcFault, call_sync

from . import names
from .exceptions import ROSException

__all__ = ["MasterProxy", "get_master"]

#: Master methods whose first argument after the caller id is a graph name, resolved before the call.
_NAME_FIRST = frozenset({
    "deleteParam", "setParam", "getParam", "searchParam", "subscribeParam", "unsubscribeParam", "hasParam",
    "registerService", "lookupService", "unregisterService", "registerSubscriber", "unregisterSubscriber",
    "registerPublisher", "unregisterPublisher", "lookupNode", "getPublishedTopics",
})


class MasterProxy:
    """The ROS master at *uri*: its API methods as attributes, the parameter server as a mapping."""

    def __init__(self, uri: str) -> None:
        self.uri = uri
        self._lock = threading.Lock()

    def _call(self, method: str, *args: Any) -> Any:
        """Call *method* with the caller id first; errors as Python's XML-RPC client raises them."""
        try:
            with self._lock:
                return call_sync(self.uri, method, names.get_caller_id(), *args)
        except XmlRpcFault as exc:
            raise xmlrpc.client.Fault(exc.code, exc.string) from None
        except XmlRpcConnectionError as exc:
            raise ConnectionError(exc.reason) from None

    def __getattr__(self, method: str) -> Callable[..., Any]:
        if method.startswith("_"):
            raise AttributeError(method)

        def forward(*args: Any) -> Any:
            values = list(args)
            if method in _NAME_FIRST and values:
                values[0] = names.resolve_name(values[0])
            return self._call(method, *values)
        return forward

    def __getitem__(self, key: str) -> Any:
        """The parameter *key*; KeyError when it is not set."""
        code, _, value = self._call("getParam", names.resolve_name(key))
        if code != 1:
            raise KeyError(key)
        return value

    def __setitem__(self, key: str, value: Any) -> None:
        """Set the parameter *key*."""
        self._call("setParam", names.resolve_name(key), value)

    def __delitem__(self, key: str) -> None:
        """Delete the parameter *key*; KeyError when it is not set."""
        code, msg, _ = self._call("deleteParam", names.resolve_name(key))
        if code == -1:
            raise KeyError(key)
        if code != 1:
            raise ROSException(f"cannot delete parameter: {msg}")

    def __contains__(self, key: object) -> bool:
        """True when the parameter *key* is set."""
        code, msg, value = self._call("hasParam", names.resolve_name(str(key)))
        if code != 1:
            raise ROSException(f"cannot check parameter on server: {msg}")
        return bool(value)

    def __iter__(self) -> Iterator[str]:
        """Every parameter name on the server."""
        code, msg, value = self._call("getParamNames")
        if code != 1:
            raise ROSException(f"cannot retrieve parameter names: {msg}")
        return iter(value)

    def search_param(self, key: str) -> str | None:
        """The nearest parameter called *key* up this node's namespace, or None."""
        key = names.get_mappings().get(key, key)
        code, msg, value = self._call("searchParam", key)
        if code == 1:
            return str(value)
        if code == -1:
            return None
        raise ROSException(f"cannot search for parameter: {msg}")

    def get_param_cached(self, key: str) -> Any:
        """The parameter *key*, subscribed once and then read from the node's cache; KeyError when not set."""
        value = _sync.get_param_cached(key, _MISSING)
        if value is _MISSING or value == {}:
            raise KeyError(key)
        return value


_MISSING: Any = object()
_proxy: list[MasterProxy] = []
_proxy_lock = threading.Lock()


def get_master() -> MasterProxy:
    """This process's :class:`MasterProxy`, of ``ROS_MASTER_URI`` (``__master:=`` wins); no node needed."""
    with _proxy_lock:
        if not _proxy:
            _proxy.append(MasterProxy(master_uri_from_env(_names.parse_argv(sys.argv[1:]).master)))
        return _proxy[0]
