"""rospy.names: this process's node name, namespace and name resolution (before and after ``init_node``)."""

from __future__ import annotations

import os
import sys

from rostui.core import names as _names
from rostui.core.node import sync as _sync

__all__ = ["get_name", "get_namespace", "get_caller_id", "resolve_name", "remap_name", "get_mappings",
           "get_resolved_mappings", "canonicalize_name", "ns_join", "is_global", "is_private", "namespace",
           "get_ros_namespace", "is_initialized", "SEP", "PRIV_NAME"]

SEP = "/"
"""The separator of graph names."""
PRIV_NAME = "~"
"""The prefix of private names."""
_UNNAMED = "/unnamed"

canonicalize_name = _names.canonicalize_name
is_global = _names.is_global
is_private = _names.is_private


def is_initialized() -> bool:
    """True once ``init_node`` has run in this process."""
    try:
        _sync.get_name()
    except _sync.ROSException:
        return False
    return True


def get_name() -> str:
    """This node's global name; ``/unnamed`` before ``init_node``, as in rospy."""
    return _sync.get_name() if is_initialized() else _UNNAMED


get_caller_id = get_name


def get_ros_namespace(argv: list[str] | None = None) -> str:
    """The namespace from ``__ns:=`` in *argv* (default ``sys.argv``) or ``ROS_NAMESPACE``.

    It is global, with a trailing slash.
    """
    args = _names.parse_argv(list(sys.argv if argv is None else argv)[1:])
    return _names.node_namespace(args, os.environ)


def get_namespace() -> str:
    """This node's namespace, with leading and trailing slash."""
    return _sync.get_namespace() if is_initialized() else get_ros_namespace()


def get_mappings() -> dict[str, str]:
    """The remappings given on the command line (``from:=to``), as written."""
    return dict(_names.parse_argv(sys.argv[1:]).remaps)


def get_resolved_mappings() -> dict[str, str]:
    """The command line's remappings with both sides resolved in this node's namespace."""
    return _names.resolve_remappings(get_mappings(), get_namespace(), get_name())


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """*name* resolved to a global name (remappings applied), for this node or for *caller_id*."""
    if caller_id is None:
        if is_initialized():
            return _sync.resolve_name(name)
        return _names.resolve_name(name, get_namespace(), _UNNAMED, get_resolved_mappings())
    return _names.resolve_for_caller(name, caller_id) if name else _names.namespace_of(caller_id)


def remap_name(name: str, caller_id: str | None = None, resolved: bool = True) -> str:
    """*name* after this node's remappings, or *name* itself when none applies.

    With *resolved* false, *name* is resolved first (for *caller_id*, default this node).
    """
    key = name if resolved else resolve_name(name, caller_id)
    return get_resolved_mappings().get(key, key)


def ns_join(ns: str, name: str) -> str:
    """*name* inside namespace *ns* (a global or private *name* is returned as it is)."""
    if _names.is_global(name) or _names.is_private(name) or not ns:
        return name
    return ns + name if ns.endswith(SEP) else ns + SEP + name


def namespace(name: str) -> str:
    """The namespace *name* lives in, with trailing slash."""
    return _names.namespace_of(name)
