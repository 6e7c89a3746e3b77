"""rosgraph.names: ROS graph names, as rosgraph.names treats them (see http://wiki.ros.org/Names).

Each function keeps rosgraph's own rules, which differ in places from a node's resolution: ``namespace``
of a name ending in ``/``, ``resolve_name`` with a node name as its namespace, ``load_mappings`` leaving
out ``_param:=value`` assignments.
"""

from __future__ import annotations

import os
import random
import re
import socket
import sys
from collections.abc import Mapping, Sequence
from typing import Any

from rostui.core import names as _core_names

from .rosenv import ROS_NAMESPACE

__all__ = [
    "ANYTYPE", "GLOBALNS", "MSG_EXT", "PRIV_NAME", "REMAP", "SEP", "SRV_EXT", "anonymous_name", "canonicalize_name",
    "get_ros_namespace", "is_global", "is_legal_base_name", "is_legal_name", "is_legal_remap", "is_private",
    "isstring", "load_mappings", "make_caller_id", "make_global_ns", "namespace", "ns_join", "resolve_name",
    "script_resolve_name",
]

MSG_EXT = ".msg"
SRV_EXT = ".srv"
SEP = "/"
GLOBALNS = "/"
PRIV_NAME = "~"
REMAP = ":="
ANYTYPE = "*"
_NS_ARG = "__ns:="
# \w without re.ASCII, as rosgraph has it: a non-ASCII letter is legal here (rostui.core.names is stricter).
_LEGAL_NAME = re.compile(r"[~/A-Za-z][\w/]*")
_LEGAL_BASE_NAME = re.compile(r"[A-Za-z]\w*")
_LEGAL_REMAP = re.compile(r"(?:[~/A-Za-z]|_|__)[\w/]*" + REMAP + r".*", re.S)


def isstring(s: Any) -> bool:
    """Whether *s* is a str."""
    return isinstance(s, str)


def is_global(name: str) -> Any:
    """Whether *name* starts with ``/`` (an empty or None name is returned as it is, as rosgraph does)."""
    return name[0] == SEP if name else name


def is_private(name: str) -> Any:
    """Whether *name* starts with ``~`` (an empty or None name is returned as it is)."""
    return name[0] == PRIV_NAME if name else name


def make_global_ns(name: str) -> str:
    """*name* as a global namespace with leading and trailing ``/``; ValueError for a ``~name``."""
    if is_private(name):
        raise ValueError(f"cannot turn [{name}] into a global name")
    name = name if is_global(name) else SEP + name
    return name if name.endswith(SEP) else name + SEP


def get_ros_namespace(env: Mapping[str, str] | None = None, argv: Sequence[str] | None = None) -> str:
    """``__ns:=`` from *argv* (``sys.argv``), else ``ROS_NAMESPACE``, else ``/``; global, with a trailing ``/``."""
    for arg in sys.argv if argv is None else argv:
        if arg.startswith(_NS_ARG):
            return make_global_ns(arg[len(_NS_ARG):])
    return make_global_ns((os.environ if env is None else env).get(ROS_NAMESPACE, GLOBALNS))


def ns_join(ns: str, name: str) -> str:
    """*name* inside *ns* (a ``~`` or ``/`` name is returned as it is; an empty *ns* gives *name*)."""
    return _core_names.join_names(ns, name)


def make_caller_id(name: str) -> str:
    """The caller id of a program called *name* in this process's namespace (with a trailing ``/``)."""
    return make_global_ns(ns_join(get_ros_namespace(), name))


def namespace(name: str) -> str:
    """The namespace of *name* with a trailing ``/`` (``/wg/node1`` gives ``/wg/``; ``''`` gives ``/``)."""
    if name is None:
        raise ValueError("name")
    if not isinstance(name, str):
        raise TypeError("name")
    if not name:
        return SEP
    if name.endswith(SEP):
        name = name[:-1]
    return name[: name.rfind(SEP) + 1] or SEP


def canonicalize_name(name: str) -> str:
    """*name* without repeated or trailing ``/`` (an empty name and ``/`` stay as they are)."""
    return _core_names.canonicalize_name(name)


def is_legal_name(name: str | None) -> bool:
    """Whether *name* is a legal graph name (letters, digits, ``_`` and single ``/``; may start with ``~``)."""
    if name is None:
        return False
    return name == "" or (_LEGAL_NAME.fullmatch(name) is not None and "//" not in name)


def is_legal_base_name(name: str | None) -> bool:
    """Whether *name* is a legal name without namespace (a letter, then letters, digits and ``_``)."""
    return name is not None and _LEGAL_BASE_NAME.fullmatch(name) is not None


def is_legal_remap(arg: str | None) -> bool:
    """Whether *arg* reads as a remapping argument ``from:=to``."""
    return arg is not None and _LEGAL_REMAP.fullmatch(arg) is not None


def load_mappings(argv: Sequence[str]) -> dict[str, str]:
    """The name remappings in *argv* (``from:=to``), without the ``_param:=value`` assignments."""
    mappings: dict[str, str] = {}
    for arg in argv:
        if not is_legal_remap(arg):
            continue
        parts = [part.strip() for part in arg.split(REMAP)]
        if len(parts) != 2:
            sys.stderr.write(f"ERROR: Invalid remapping argument '{arg}'\n")
            continue
        source, target = parts
        if source and target and not (len(source) > 1 and source[0] == "_" and source[1] != "_"):
            mappings[source] = target
    return mappings


def resolve_name(name: str, namespace_: str, remappings: Mapping[str, str] | None = None) -> str:
    """*name* resolved against the node name *namespace_* (``~x`` under the node, ``x`` beside it), then remapped."""
    if not name:
        return namespace(namespace_)
    return _core_names.resolve_name(name, namespace(namespace_), node_name=namespace_, remappings=remappings)


def script_resolve_name(script_name: str, name: str) -> str:
    """*name* resolved for a script named *script_name* in ``ROS_NAMESPACE`` (no remapping)."""
    if not name:
        return get_ros_namespace()
    if is_global(name):
        return name
    if is_private(name):
        return ns_join(make_caller_id(script_name), name[1:])
    return get_ros_namespace() + name


def anonymous_name(id: str) -> str:
    """A name unlikely to be taken: *id*, the host, the process id and a random number, joined by ``_``."""
    name = f"{id}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, sys.maxsize)}"
    return name.replace(".", "_").replace("-", "_").replace(":", "_")
