"""The parameter tree and the computation of ``paramUpdate`` notifications.

Behaviour follows rosmaster's parameter server: namespaces are dicts, setting
a dict replaces the whole namespace, a non-dict on the way to a key is
silently turned into a namespace, and subscribers are told about changes
under (and deletions of) the keys they subscribed to.
"""

from __future__ import annotations

from typing import Any

from rostui.core.names import SEP
from rostui.core.names import canonicalize_name as canonicalize
from rostui.core.names import join_names as ns_join
from .registrations import Provider, Registrations

#: One notification batch: (subscribers, key sent, value sent).
Update = tuple[list[Provider], str, Any]


def _copy_tree(value: Any) -> Any:
    """Copy the dict structure of ``value`` (leaves are shared; they are immutable in practice)."""
    if type(value) is dict:
        return {k: _copy_tree(v) for k, v in value.items()}
    return value


def _segments(key: str) -> list[str]:
    return [x for x in key.split(SEP) if x]


class ParamTree:
    """The parameter server's storage: a tree of dicts rooted at ``/``."""

    def __init__(self) -> None:
        self.root: dict[str, Any] = {}

    def get(self, key: str) -> Any:
        """The value at global ``key`` (a dict for a namespace); ``KeyError`` if unset."""
        val: Any = self.root
        if key != SEP:
            for seg in _segments(key):
                if type(val) is not dict:
                    raise KeyError(key)
                val = val[seg]
        return val

    def has(self, key: str) -> bool:
        """True when ``key`` is set (as a value or a namespace)."""
        try:
            self.get(key)
            return True
        except KeyError:
            return False

    def set(self, key: str, value: Any) -> None:
        """Store ``value`` at global ``key``; a dict replaces the whole namespace."""
        value = _copy_tree(value)
        if key == SEP:
            if type(value) is not dict:
                raise TypeError("cannot set root of parameter tree to non-dictionary")
            self.root = value
            return
        segs = _segments(key)
        d = self.root
        for seg in segs[:-1]:
            child = d.get(seg)
            if type(child) is not dict:
                child = d[seg] = {}
            d = child
        d[segs[-1]] = value

    def delete(self, key: str) -> None:
        """Remove ``key`` (and everything under it); ``KeyError`` if unset."""
        if key == SEP:
            raise KeyError("cannot delete root of parameter tree")
        segs = _segments(key)
        d: Any = self.root
        for seg in segs[:-1]:
            if type(d) is not dict or seg not in d:
                raise KeyError(key)
            d = d[seg]
        # Like rosmaster, a non-dict here answers with its own ``in``/``del``
        # semantics (TypeError for numbers -> "invalid arguments").
        if segs[-1] not in d:
            raise KeyError(key)
        del d[segs[-1]]

    def names(self) -> list[str]:
        """Every leaf parameter name (empty namespaces are not listed)."""
        out: list[str] = []

        def walk(prefix: str, d: dict[str, Any]) -> None:
            for k, v in d.items():
                name = ns_join(prefix, k)
                if type(v) is dict:
                    walk(name, v)
                else:
                    out.append(name)
        walk(SEP, self.root)
        return out

    def search(self, ns: str, key: str) -> str | None:
        """rosmaster's searchParam: look for ``key`` from ``ns`` upwards to the root.

        Only the first segment of ``key`` has to exist for a namespace to
        match; the full key under that namespace is returned.
        """
        if not key or key[0] == "~":
            raise ValueError("invalid key")
        if not ns.startswith(SEP):
            raise ValueError("namespace must be global")
        if key[0] == SEP:
            return key if self.has(key) else None
        key_ns = _segments(key)[0]
        if self.has(ns_join(ns, key_ns)):
            return ns_join(ns, key)
        parts = _segments(ns)
        for i in range(1, len(parts) + 1):
            prefix = parts[:-i]
            if self.has(SEP + SEP.join(prefix + [key_ns])):
                return SEP + SEP.join(prefix + [key])
        return None


def _all_keys(param_key: str, value: dict[str, Any], out: list[str]) -> list[str]:
    for k, v in value.items():
        new_key = ns_join(param_key, k) + SEP
        out.append(new_key)
        if type(v) is dict:
            _all_keys(new_key, v, out)
    return out


def compute_updates(subscribers: Registrations, key: str, value: Any,
                    ignore_caller: str | None = None) -> list[Update]:
    """Which param subscribers hear about ``key`` becoming ``value`` ({} = deleted).

    Mirrors rosmaster: a subscriber of a namespace containing ``key`` gets the
    new value (the setter itself excluded); a subscriber of a key inside a
    namespace replaced by a dict gets its new value, or ``{}`` if it vanished.
    Keys sent carry a trailing slash, as rosmaster sends them.
    """
    if not subscribers:
        return []
    param_key = key if key == SEP else canonicalize(key) + SEP
    all_keys = _all_keys(param_key, value, []) if type(value) is dict else None
    all_set = set(all_keys) if all_keys else set()
    updates: list[Update] = []
    for sub_key in subscribers.keys():
        ns_key = sub_key if sub_key.endswith(SEP) else sub_key + SEP
        if param_key.startswith(ns_key):
            apis = subscribers.providers(sub_key)
            if ignore_caller is not None:
                apis = [p for p in apis if p[0] != ignore_caller]
            updates.append((apis, param_key, value))
        elif all_keys is not None and ns_key.startswith(param_key) and sub_key not in all_set:
            updates.append((subscribers.providers(sub_key), sub_key, {}))
    if all_keys:
        for k in all_keys:
            if k in subscribers:
                val: Any = value
                for seg in _segments(k[len(param_key):]):
                    val = val[seg]
                updates.append((subscribers.providers(k), k, val))
    return updates

