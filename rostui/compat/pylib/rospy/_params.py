"""rospy's parameter functions: the node's once ``init_node`` has run, the master's (as ``/unnamed``) before.

rospy lets a script read and set parameters before it is a node (``fake_time.py``
sets ``/use_sim_time`` first); these do the same through :func:`get_master`.
"""

from __future__ import annotations

from typing import Any

from rostui.core.node import sync as _sync

from .exceptions import ROSException
from .msproxy import get_master
from .names import is_initialized

__all__ = ["get_param", "set_param", "has_param", "delete_param", "search_param", "get_param_names"]

_MISSING: Any = object()


def get_param(param_name: str, default: Any = _MISSING) -> Any:
    """A parameter's value; *default* when it is not set, else KeyError."""
    if is_initialized():
        return _sync.get_param(param_name) if default is _MISSING else _sync.get_param(param_name, default)
    try:
        return get_master()[param_name]
    except KeyError:
        if default is _MISSING:
            raise
        return default


def set_param(param_name: str, param_value: Any) -> None:
    """Set a parameter (a dict replaces a whole namespace)."""
    if is_initialized():
        _sync.set_param(param_name, param_value)
    else:
        get_master()[param_name] = param_value


def has_param(param_name: str) -> bool:
    """True when the parameter is set."""
    return _sync.has_param(param_name) if is_initialized() else param_name in get_master()


def delete_param(param_name: str) -> None:
    """Delete a parameter; KeyError when it is not set."""
    if is_initialized():
        _sync.delete_param(param_name)
    else:
        del get_master()[param_name]


def search_param(param_name: str) -> str | None:
    """The nearest parameter called *param_name* up the caller's namespace, or None."""
    return _sync.search_param(param_name) if is_initialized() else get_master().search_param(param_name)


def get_param_names() -> list[str]:
    """Every parameter name on the server."""
    if is_initialized():
        return _sync.get_param_names()
    code, msg, value = get_master().getParamNames()
    if code != 1:
        raise ROSException(f"Unable to retrieve parameter names: {msg}")
    return list(value)
