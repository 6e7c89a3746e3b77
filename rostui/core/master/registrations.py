"""The master's registration tables: publishers, subscribers, services, param subscribers.

Semantics follow rosmaster (ordering, return codes and messages), but every
table is a dict of insertion-ordered dicts so registering, unregistering and
node replacement cost O(1) per registration instead of list scans.
"""

from __future__ import annotations

from typing import Any, Callable

PUBLICATIONS = "pub"
SUBSCRIPTIONS = "sub"
SERVICES = "srv"
PARAM_SUBSCRIPTIONS = "param"

Provider = tuple[str, str]  # (caller_id, caller_api)
ApiResult = tuple[int, str, int]


class NodeRef:
    """One registered node: its XML-RPC URI and the keys it registered, per kind."""

    __slots__ = ("id", "api", "keys")

    def __init__(self, node_id: str, api: str) -> None:
        self.id = node_id
        self.api = api
        self.keys: dict[str, dict[str, None]] = {
            PUBLICATIONS: {}, SUBSCRIPTIONS: {}, SERVICES: {}, PARAM_SUBSCRIPTIONS: {},
        }

    def is_empty(self) -> bool:
        """True when the node holds no registration at all."""
        k = self.keys
        return not (k[PUBLICATIONS] or k[SUBSCRIPTIONS] or k[SERVICES] or k[PARAM_SUBSCRIPTIONS])


class Registrations:
    """A multimap ``key -> ordered set of (caller_id, caller_api)``; services also map to a URI."""

    __slots__ = ("kind", "map", "service_api_map", "_state")

    def __init__(self, kind: str) -> None:
        self.kind = kind
        self.map: dict[str, dict[Provider, None]] = {}
        self.service_api_map: dict[str, tuple[str, str]] | None = None
        self._state: list[list[Any]] | None = None

    def __bool__(self) -> bool:
        return bool(self.map)

    def __contains__(self, key: str) -> bool:
        return key in self.map

    def keys(self) -> Any:
        """The registered keys, in registration order."""
        return self.map.keys()

    def providers(self, key: str) -> list[Provider]:
        """``[(caller_id, caller_api), ...]`` registered for ``key``."""
        entry = self.map.get(key)
        return list(entry) if entry else []

    def get_apis(self, key: str) -> list[str]:
        """The caller APIs registered for ``key`` (empty when none)."""
        entry = self.map.get(key)
        return [api for _, api in entry] if entry else []

    def get_service_api(self, service: str) -> str | None:
        """The rosrpc URI of ``service``, or None."""
        if self.service_api_map:
            found = self.service_api_map.get(service)
            if found is not None:
                return found[1]
        return None

    def get_state(self) -> list[list[Any]]:
        """``[[key, [caller_id, ...]], ...]`` as getSystemState returns it (cached; do not mutate)."""
        state = self._state
        if state is None:
            state = self._state = [[k, [cid for cid, _ in v]] for k, v in self.map.items()]
        return state

    def register(self, key: str, caller_id: str, caller_api: str, service_api: str | None = None) -> None:
        """Add a provider; a service registration replaces the previous provider."""
        self._state = None
        if service_api:
            self.map[key] = {(caller_id, caller_api): None}
            if self.service_api_map is None:
                self.service_api_map = {}
            self.service_api_map[key] = (caller_id, service_api)
            return
        entry = self.map.get(key)
        if entry is None:
            self.map[key] = {(caller_id, caller_api): None}
        else:
            entry[(caller_id, caller_api)] = None

    def unregister_keys(self, keys: Any, caller_id: str) -> list[str]:
        """Remove every registration of ``caller_id`` under ``keys``; return the keys changed."""
        changed: list[str] = []
        for key in keys:
            entry = self.map.get(key)
            if entry:
                dead = [p for p in entry if p[0] == caller_id]
                if dead:
                    for p in dead:
                        del entry[p]
                    changed.append(key)
                    if not entry:
                        del self.map[key]
            if self.service_api_map:
                svc = self.service_api_map.get(key)
                if svc is not None and svc[0] == caller_id:
                    del self.service_api_map[key]
        if changed:
            self._state = None
        return changed

    def unregister(self, key: str, caller_id: str, caller_api: str | None,
                   service_api: str | None = None) -> ApiResult:
        """Remove one registration; return rosmaster's ``(1, message, 0 or 1)``."""
        if service_api:
            if self.service_api_map is None:
                return 1, f"[{caller_id}] is not a provider of [{key}]", 0
            if self.service_api_map.get(key) != (caller_id, service_api):
                return 1, f"[{service_api}] is no longer the current service api handle for [{key}]", 0
            del self.service_api_map[key]
            self.map.pop(key, None)
            self._state = None
            return 1, f"Unregistered [{caller_id}] as provider of [{key}]", 1
        entry = self.map.get(key)
        provider = (caller_id, caller_api)
        if entry is not None and provider in entry:
            del entry[provider]
            if not entry:
                del self.map[key]
            self._state = None
            return 1, f"Unregistered [{caller_id}] as provider of [{key}]", 1
        return 1, f"[{caller_id}] is not a known provider of [{key}]", 0


class RegistrationManager:
    """All registrations plus the node table, with rosmaster's node-replacement rule.

    ``on_replaced(old_ref)`` is called when a caller_id registers with a new
    caller_api: the old node must be shut down.  Its registrations are already
    gone by then; ``old_ref.keys`` tells which.
    """

    def __init__(self, on_replaced: Callable[[NodeRef, dict[str, list[str]]], None]) -> None:
        self.nodes: dict[str, NodeRef] = {}
        self.publishers = Registrations(PUBLICATIONS)
        self.subscribers = Registrations(SUBSCRIPTIONS)
        self.services = Registrations(SERVICES)
        self.param_subscribers = Registrations(PARAM_SUBSCRIPTIONS)
        self._tables = {
            PUBLICATIONS: self.publishers, SUBSCRIPTIONS: self.subscribers,
            SERVICES: self.services, PARAM_SUBSCRIPTIONS: self.param_subscribers,
        }
        self._on_replaced = on_replaced

    def get_node(self, caller_id: str) -> NodeRef | None:
        """The node registered as ``caller_id``, if any."""
        return self.nodes.get(caller_id)

    def _register(self, kind: str, key: str, caller_id: str, caller_api: str,
                  service_api: str | None = None) -> None:
        ref = self.nodes.get(caller_id)
        if ref is None or ref.api != caller_api:
            old = ref
            ref = self.nodes[caller_id] = NodeRef(caller_id, caller_api)
            if old is not None:
                removed = {k: table.unregister_keys(old.keys[k], caller_id)
                           for k, table in self._tables.items()}
                self._on_replaced(old, removed)
        ref.keys[kind][key] = None
        self._tables[kind].register(key, caller_id, caller_api, service_api)

    def _unregister(self, kind: str, key: str, caller_id: str, caller_api: str | None,
                    service_api: str | None = None) -> ApiResult:
        ref = self.nodes.get(caller_id)
        if ref is None:
            return 1, f"[{caller_id}] is not a registered node", 0
        result = self._tables[kind].unregister(key, caller_id, caller_api, service_api)
        if result[2] == 1:
            ref.keys[kind].pop(key, None)
        if ref.is_empty():
            del self.nodes[caller_id]
        return result

    def register_publisher(self, topic: str, caller_id: str, caller_api: str) -> None:
        """Record ``caller_id`` as a publisher of ``topic``."""
        self._register(PUBLICATIONS, topic, caller_id, caller_api)

    def register_subscriber(self, topic: str, caller_id: str, caller_api: str) -> None:
        """Record ``caller_id`` as a subscriber of ``topic``."""
        self._register(SUBSCRIPTIONS, topic, caller_id, caller_api)

    def register_service(self, service: str, caller_id: str, caller_api: str, service_api: str) -> None:
        """Record ``caller_id`` as the provider of ``service`` at ``service_api``."""
        self._register(SERVICES, service, caller_id, caller_api, service_api)

    def register_param_subscriber(self, key: str, caller_id: str, caller_api: str) -> None:
        """Record ``caller_id`` as a subscriber of parameter ``key``."""
        self._register(PARAM_SUBSCRIPTIONS, key, caller_id, caller_api)

    def unregister_publisher(self, topic: str, caller_id: str, caller_api: str) -> ApiResult:
        """Undo :meth:`register_publisher`."""
        return self._unregister(PUBLICATIONS, topic, caller_id, caller_api)

    def unregister_subscriber(self, topic: str, caller_id: str, caller_api: str) -> ApiResult:
        """Undo :meth:`register_subscriber`."""
        return self._unregister(SUBSCRIPTIONS, topic, caller_id, caller_api)

    def unregister_service(self, service: str, caller_id: str, service_api: str) -> ApiResult:
        """Undo :meth:`register_service` if ``service_api`` is still the current one."""
        return self._unregister(SERVICES, service, caller_id, None, service_api)

    def unregister_param_subscriber(self, key: str, caller_id: str, caller_api: str) -> ApiResult:
        """Undo :meth:`register_param_subscriber`."""
        return self._unregister(PARAM_SUBSCRIPTIONS, key, caller_id, caller_api)
