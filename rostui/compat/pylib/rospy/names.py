"""rospy.names: this process's node name, namespace and name resolution (before and after ``init_node``)."""

from __future__ import annotations

import os
import sys

from rostui.core import names as _names
from rostui.core.node import sync as _sync

__all__ = ["get_name", "get_namespace", "get_caller_id", "resolve_name", "remap_name", "get_mappings",
           "get_resolved_mappings", "canonicalize_name", "ns_join", "is_global", "is_private", "namespace",
           "get_ros_namespace", "is_initialized", "make_global_ns", "SEP", "GLOBALNS", "PRIV_NAME"]

SEP = "/"
"""The separator of graph names."""
GLOBALNS = "/"
"""The global namespace."""
PRIV_NAME = "~"
"""The prefix of private names."""
_UNNAMED = "/unnamed"

canonicalize_name = _names.canonicalize_name
is_global = _names.is_global
is_private = _names.is_private
make_global_ns = _names.make_global_ns


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
    """The command line's ``from:=to`` remappings and ``__key:=value`` specials, as written, in order."""
    found: dict[str, str] = {}
    for arg in sys.argv[1:]:
        source, sep, target = arg.partition(":=")
        if sep and source and not (source.startswith("_") and not source.startswith("__")):
            found[source] = target
    return found


def get_resolved_mappings() -> dict[str, str]:
    """The command line's remappings with both sides resolved in this node's namespace."""
    remaps = {k: v for k, v in get_mappings().items() if not k.startswith("__")}
    return _names.resolve_remappings(remaps, get_namespace(), get_name())


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """*name* resolved to a global name (remappings applied), for this node or for *caller_id*."""
    if caller_id is None:
        if is_initialized():
            return _sync.resolve_name(name)
        return _names.resolve_name(name, get_namespace(), _UNNAMED, get_resolved_mappings())
    return _names.resolve_for_caller(name, caller_id) if name else _names.namespace_of(caller_id)


def remap_name(name: str, caller_id: str | None = None, resolved: bool = True) -> str:
    """*name*'s remapping as written on the command line, resolved for *caller_id* (default this node).

    A name the command line does not remap is returned as it is. *resolved* is accepted, as rospy does.
    """
    mapped = get_mappings().get(name)
    if mapped is None:
        return name
    return _names.resolve_for_caller(mapped, caller_id or get_name())


def ns_join(ns: str, name: str) -> str:
    """*name* inside namespace *ns* (a global or private *name* is returned as it is)."""
    if _names.is_global(name) or _names.is_private(name) or not ns:
        return name
    return ns + name if ns.endswith(SEP) else ns + SEP + name


def namespace(name: str) -> str:
    """The namespace *name* lives in, with trailing slash."""
    return _names.namespace_of(name)
