"""A node's cache of parameters it subscribed to with subscribeParam."""

from __future__ import annotations

import threading
from typing import Any

_MISSING = object()


def _canonical_key(key: str) -> str:
    return key.rstrip("/") or "/"


class ParamCache:
    """Values of subscribed parameters, kept current by paramUpdate calls.

    Thread-safe: the engine thread writes, any thread reads.
    """

    def __init__(self) -> None:
        self._values: dict[str, Any] = {}
        self._lock = threading.Lock()

    def subscribed(self, key: str) -> bool:
        """True if the key (or a namespace holding it) is cached."""
        return self.get(key, _MISSING) is not _MISSING

    def get(self, key: str, default: Any = None) -> Any:
        """The cached value of a key, looked up through cached namespaces."""
        key = _canonical_key(key)
        with self._lock:
            if key in self._values:
                return self._values[key]
            for ns, value in self._values.items():
                prefix = ns if ns.endswith("/") else ns + "/"
                if key.startswith(prefix) and isinstance(value, dict):
                    node: Any = value
                    for part in key[len(prefix):].split("/"):
                        if not isinstance(node, dict) or part not in node:
                            node = _MISSING
                            break
                        node = node[part]
                    if node is not _MISSING:
                        return node
        return default

    def set(self, key: str, value: Any) -> None:
        """Store a value fetched from the master."""
        with self._lock:
            self._values[_canonical_key(key)] = value

    def update(self, key: str, value: Any) -> None:
        """Apply a paramUpdate: replace the key and forget stale values beneath it."""
        key = _canonical_key(key)
        prefix = key if key.endswith("/") else key + "/"
        with self._lock:
            for cached in [k for k in self._values if k.startswith(prefix)]:
                del self._values[cached]
            self._values[key] = value

    def keys(self) -> list[str]:
        """Keys subscribed so far."""
        with self._lock:
            return list(self._values)

    def forget(self, key: str) -> None:
        """Drop a key (after unsubscribeParam)."""
        with self._lock:
            self._values.pop(_canonical_key(key), None)
