"""ROS 1 graph resource names: validation, resolution, remapping and node arguments.

A graph resource name is one of

* global, ``/a/b`` -- needs no context;
* relative, ``b`` or ``a/b`` -- resolved in the node's namespace;
* private, ``~b`` -- resolved under the node's own global name;
* anonymous -- a node name with a unique suffix (``base_<pid>_<ms>``).

Remappings (``from:=to`` on the command line) have both sides resolved to global
names first; afterwards a resolved name is remapped by exact string comparison.

The command line of a ROS program also carries special keys (``__name:=``,
``__ns:=``, ``__log:=``, ``__ip:=``, ``__hostname:=``, ``__master:=``) and
private parameters (``_param:=value``, YAML-typed).  :func:`parse_argv` splits
them from the program's own arguments.

The results match Debian's ``rosgraph.names`` / ``rospy`` for legal input; the
few deliberate differences (stricter validation, ASCII-only names) are noted
on the functions concerned.
"""

from __future__ import annotations

import os
import re
import threading
import time
from typing import Any, Mapping, Sequence

from rostui.core.records import Record

__all__ = [
    "SEP",
    "PRIV",
    "GLOBAL_NS",
    "REMAP",
    "SPECIAL_KEYS",
    "InvalidNameError",
    "is_legal_name",
    "is_legal_base_name",
    "validate_name",
    "canonicalize_name",
    "namespace_of",
    "base_name",
    "join_names",
    "make_global_ns",
    "is_global",
    "is_private",
    "resolve_name",
    "anonymous_name",
    "NodeArgs",
    "parse_argv",
    "resolve_remappings",
    "node_namespace",
    "node_global_name",
]

SEP = "/"
"""Namespace separator."""

PRIV = "~"
"""Prefix of private names."""

GLOBAL_NS = "/"
"""The global (root) namespace."""

REMAP = ":="
"""Separator of command-line remappings, special keys and private parameters."""

SPECIAL_KEYS: tuple[str, ...] = ("__name", "__ns", "__log", "__ip", "__hostname", "__master")
"""The special command-line keys ROS 1 client libraries understand."""

ROS_NAMESPACE_ENV = "ROS_NAMESPACE"
"""Environment variable giving the default namespace when ``__ns:=`` is absent."""

# ASCII on purpose: roscpp accepts ASCII letters and digits only.
_LEGAL_NAME = re.compile(r"[A-Za-z/~][A-Za-z0-9_/]*", re.ASCII)
_LEGAL_BASE_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*", re.ASCII)
_SPECIAL_KEY = re.compile(r"__[A-Za-z0-9_/]*", re.ASCII)
_SLASHES = re.compile(r"/{2,}")


class InvalidNameError(ValueError):
    """A graph resource name (or a command-line remapping) breaks the ROS naming rules."""

    def __init__(self, name: str, reason: str, kind: str = "name") -> None:
        self.name = name
        self.reason = reason
        self.kind = kind
        super().__init__(f"invalid ROS {kind} {name!r}: {reason}")


# --------------------------------------------------------------------------- legality


def _illegal_reason(name: str) -> str | None:
    """Why ``name`` is not a legal graph resource name, or None when it is."""
    if not isinstance(name, str):
        return f"expected a string, got {type(name).__name__}"
    if name == "":
        return None
    first = name[0]
    if not (first.isascii() and (first.isalpha() or first in "/~")):
        return "must start with a letter, '/' or '~'"
    if not _LEGAL_NAME.fullmatch(name):
        bad = next(c for c in name[1:] if not (c.isascii() and (c.isalnum() or c in "_/")))
        return f"character {bad!r} is not allowed (only letters, digits, '_' and '/')"
    if "//" in name:
        return "contains '//'"
    return None


def is_legal_name(name: str) -> bool:
    """True when ``name`` is a legal graph resource name.

    Legal: empty (it resolves to the namespace), or a first character that is a
    letter, ``/`` or ``~``, followed by letters, digits, ``_`` and ``/``, with no
    ``//``.  Trailing slashes are tolerated (``/a/`` is ``/a``).
    """
    return _illegal_reason(name) is None


def is_legal_base_name(name: str) -> bool:
    """True when ``name`` is a legal base name: a letter, then letters, digits and ``_``."""
    return isinstance(name, str) and _LEGAL_BASE_NAME.fullmatch(name) is not None


def validate_name(name: str, kind: str = "name") -> str:
    """Return ``name`` unchanged when legal, else raise :class:`InvalidNameError`.

    ``kind`` ("topic", "node name", "namespace", ...) only words the message.
    """
    reason = _illegal_reason(name)
    if reason is not None:
        raise InvalidNameError(name, reason, kind)
    return name


def _validate_base_name(name: str, kind: str) -> str:
    """Return ``name`` when it is a legal base name, else raise InvalidNameError."""
    if is_legal_base_name(name):
        return name
    if not isinstance(name, str):
        raise InvalidNameError(str(name), f"expected a string, got {type(name).__name__}", kind)
    if name == "":
        raise InvalidNameError(name, "must not be empty", kind)
    if SEP in name or PRIV in name:
        raise InvalidNameError(name, "must be a base name without '/' or '~'", kind)
    if not (name[0].isascii() and name[0].isalpha()):
        raise InvalidNameError(name, "must start with a letter", kind)
    raise InvalidNameError(name, "only letters, digits and '_' are allowed", kind)


# --------------------------------------------------------------------------- structure


def canonicalize_name(name: str) -> str:
    """Collapse repeated slashes and drop a trailing slash (``/a//b/`` -> ``/a/b``).

    ``""`` stays ``""`` and ``/`` stays ``/``.
    """
    if not name or name == SEP:
        return name
    name = _SLASHES.sub(SEP, name)
    if len(name) > 1 and name.endswith(SEP):
        name = name[:-1]
    return name


def is_global(name: str) -> bool:
    """True when ``name`` starts with ``/``."""
    return bool(name) and name[0] == SEP


def is_private(name: str) -> bool:
    """True when ``name`` starts with ``~``."""
    return bool(name) and name[0] == PRIV


def namespace_of(name: str) -> str:
    """The namespace containing ``name``, with a trailing slash.

    ``/a/b`` -> ``/a/``, ``/a`` -> ``/``, ``a/b`` -> ``a/``; a name with no
    slash (``b``, ``~b``, ``""``) is in the global namespace ``/``.
    """
    name = canonicalize_name(name)
    if not name or name == SEP:
        return GLOBAL_NS
    cut = name.rfind(SEP)
    if cut < 0:
        return GLOBAL_NS
    return name[: cut + 1]


def base_name(name: str) -> str:
    """The last component of ``name`` (``/a/b/`` -> ``b``, ``~p`` -> ``p``, ``/`` -> ``""``)."""
    name = canonicalize_name(name)
    last = name.rsplit(SEP, 1)[-1]
    return last[1:] if last.startswith(PRIV) else last


def join_names(ns: str, name: str) -> str:
    """Join a namespace and a name: ``join_names("/a", "b")`` -> ``/a/b``.

    A global or private ``name`` is returned unchanged; an empty ``ns`` returns
    ``name``; ``ns="~"`` gives the private name ``~name``.
    """
    if is_global(name) or is_private(name):
        return name
    if not ns:
        return name
    if ns == PRIV:
        return PRIV + name
    if ns.endswith(SEP):
        return ns + name
    return ns + SEP + name


def make_global_ns(ns: str) -> str:
    """Make ``ns`` a global namespace with leading and trailing ``/`` (``a`` -> ``/a/``).

    ``""`` -> ``/``.  A private name cannot be a global namespace: raises
    :class:`InvalidNameError`.
    """
    if is_private(ns):
        raise InvalidNameError(ns, "a private name cannot be turned into a global namespace", "namespace")
    if not ns.startswith(SEP):
        ns = SEP + ns
    if not ns.endswith(SEP):
        ns += SEP
    return ns


def _ns_prefix(namespace: str | None) -> str:
    """A namespace in the form ready for appending a relative name (trailing ``/``)."""
    if not namespace or namespace == SEP:
        return GLOBAL_NS
    namespace = canonicalize_name(namespace)
    return namespace if namespace.endswith(SEP) else namespace + SEP


# --------------------------------------------------------------------------- resolution


def resolve_name(
    name: str,
    namespace: str,
    node_name: str | None = None,
    remappings: Mapping[str, str] | None = None,
) -> str:
    """Resolve ``name`` to its global, canonical form, then apply ``remappings``.

    * global names are only canonicalized;
    * relative names are resolved in ``namespace`` (``/turtle1`` or ``/turtle1/``;
      empty means ``/``);
    * private ``~x`` names are resolved under ``node_name``, the node's global
      name (``~max_vel`` for ``/sim1/pubvel`` -> ``/sim1/pubvel/max_vel``);
      without a ``node_name`` they raise :class:`InvalidNameError`;
    * the empty name resolves to the namespace itself, with a trailing slash,
      and is never remapped.

    ``remappings`` maps already-resolved names to their replacements (see
    :func:`resolve_remappings`); the resolved name is looked up by exact string
    comparison and the replacement is returned as stored.

    Like ``rosgraph.names.resolve_name(name, node_name, remappings)`` when
    ``namespace`` is the namespace of ``node_name``.  The name itself is not
    validated; use :func:`validate_name` for that.
    """
    if not name:
        return _ns_prefix(namespace)
    name = canonicalize_name(name)
    if is_global(name):
        resolved = name
    elif is_private(name):
        if node_name is None:
            raise InvalidNameError(name, "a private name cannot be resolved without a node name")
        resolved = canonicalize_name(node_name + SEP + name[1:])
    else:
        resolved = _ns_prefix(namespace) + name
    if remappings and resolved in remappings:
        return remappings[resolved]
    return resolved


_anon_lock = threading.Lock()
_anon_last_ms = 0


def anonymous_name(base: str) -> str:
    """A unique node name in rospy style: ``base_<pid>_<milliseconds>``.

    ``base`` must be a legal base name.  Within one process successive calls
    never repeat a suffix, even within the same millisecond.
    """
    global _anon_last_ms
    _validate_base_name(base, "node name")
    with _anon_lock:
        ms = int(time.time() * 1000)
        if ms <= _anon_last_ms:
            ms = _anon_last_ms + 1
        _anon_last_ms = ms
    return f"{base}_{os.getpid()}_{ms}"


# --------------------------------------------------------------------------- argv


class NodeArgs(Record):
    """What a ROS 1 command line carries for a node, split from the program's own arguments.

    ``remaps`` holds ``from:=to`` remappings as written (unresolved); the special
    keys land in ``name`` (``__name:=``), ``namespace`` (``__ns:=``), ``log``,
    ``ip``, ``hostname`` and ``master``; ``specials`` holds every ``__key:=value``
    as written, known or not; ``params`` holds private parameters
    (``_rate:=10`` -> ``{"rate": 10}``) with YAML-typed values; ``args`` is
    everything else, in order.

    A record rather than a dataclass: :mod:`rostui.core.records` says why.
    """

    _fields = ("remaps", "name", "namespace", "log", "ip", "hostname", "master", "params", "args", "specials")

    def __init__(self, remaps: dict[str, str] | None = None, name: str | None = None, namespace: str | None = None,
                 log: str | None = None, ip: str | None = None, hostname: str | None = None,
                 master: str | None = None, params: dict[str, Any] | None = None, args: list[str] | None = None,
                 specials: dict[str, str] | None = None) -> None:
        self.remaps: dict[str, str] = {} if remaps is None else remaps
        self.name = name
        self.namespace = namespace
        self.log = log
        self.ip = ip
        self.hostname = hostname
        self.master = master
        self.params: dict[str, Any] = {} if params is None else params
        self.args: list[str] = [] if args is None else args
        self.specials: dict[str, str] = {} if specials is None else specials




_SPECIAL_FIELDS = {
    "__name": "name",
    "__ns": "namespace",
    "__log": "log",
    "__ip": "ip",
    "__hostname": "hostname",
    "__master": "master",
}


def parse_argv(argv: Sequence[str]) -> NodeArgs:
    """Split a ROS command line (without the program name) into :class:`NodeArgs`.

    Every argument containing ``:=`` is ROS's, as rospy's ``myargv`` treats it;
    the rest go to ``args`` in order.  Whitespace around either side of ``:=``
    is stripped.  For each ``key:=value``:

    * ``__key`` -> a special key (``__name``, ``__ns``, ... and unknown ones in
      ``specials``); an empty value is kept (``__ns:=`` means the root);
    * ``_param`` -> a private parameter whose value is parsed as YAML like rospy
      (``_rate:=10`` -> ``10``, ``_b:=true`` -> ``True``, ``_l:=[1,2]`` -> ``[1, 2]``);
    * anything else -> a remapping, kept as written.

    A later occurrence of a key wins.  An empty value drops a remapping or
    parameter, as rospy does.

    Raises :class:`InvalidNameError` for an illegal remapping or parameter name
    (or a second ``:=``), where rospy silently ignores the argument and roscpp
    fails; raises ``ValueError`` for a parameter value that is not valid YAML.
    """
    out = NodeArgs()
    for arg in argv:
        if REMAP not in arg:
            out.args.append(arg)
            continue
        raw_src, raw_dst = arg.split(REMAP, 1)
        src, dst = raw_src.strip(), raw_dst.strip()
        if REMAP in dst:
            raise InvalidNameError(arg, "a remapping has exactly one ':='", "remapping")
        if not src:
            raise InvalidNameError(arg, "nothing before ':='", "remapping")
        if src.startswith("__"):
            if not _SPECIAL_KEY.fullmatch(src):
                raise InvalidNameError(src, "illegal special key", "remapping")
            out.specials[src] = dst
            attr = _SPECIAL_FIELDS.get(src)
            if attr is not None:
                setattr(out, attr, dst)
            continue
        if src.startswith("_") and len(src) > 1:
            param = src[1:]
            reason = _illegal_reason(PRIV + param)
            if reason is not None:
                raise InvalidNameError(src, reason, "parameter name")
            if not dst:
                continue
            import yaml  # here: a node given no _param:=value never loads it

            try:
                out.params[param] = yaml.safe_load(dst)
            except yaml.YAMLError as exc:
                detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                raise ValueError(f"invalid value for parameter {src!r}: {dst!r} is not valid YAML ({detail})") from exc
            continue
        validate_name(src, "remapping source")
        if not dst:
            continue
        validate_name(dst, "remapping target")
        out.remaps[src] = dst
    return out


def resolve_remappings(remaps: Mapping[str, str], namespace: str, node_name: str) -> dict[str, str]:
    """Resolve both sides of each remapping, as ROS does before comparing names.

    Relative names resolve in ``namespace`` (the node's namespace), ``~names``
    under ``node_name`` (the node's global name).  Special ``__key`` entries are
    skipped.  Both sides are validated (:class:`InvalidNameError`).
    """
    resolved: dict[str, str] = {}
    for src, dst in remaps.items():
        if src.startswith("__"):
            continue
        validate_name(src, "remapping source")
        validate_name(dst, "remapping target")
        resolved[resolve_name(src, namespace, node_name)] = resolve_name(dst, namespace, node_name)
    return resolved


def node_namespace(args: NodeArgs, env: Mapping[str, str] = os.environ) -> str:
    """The node's namespace, with leading and trailing ``/``.

    ``__ns:=`` wins over ``ROS_NAMESPACE``; the default is ``/``.  A relative
    value is made global (``__ns:=robot`` -> ``/robot/``), repeated slashes are
    collapsed, and an illegal or private value raises :class:`InvalidNameError`.
    """
    raw = args.namespace if args.namespace is not None else env.get(ROS_NAMESPACE_ENV, GLOBAL_NS)
    raw = raw.strip()
    if is_private(raw):
        raise InvalidNameError(raw, "a namespace cannot be private", "namespace")
    ns = canonicalize_name(make_global_ns(raw))
    validate_name(ns, "namespace")
    return ns if ns.endswith(SEP) else ns + SEP


def node_global_name(
    default_name: str,
    args: NodeArgs,
    env: Mapping[str, str] = os.environ,
    anonymous: bool = False,
    lenient: bool = False,
) -> str:
    """The node's global name: namespace + (``__name`` or ``default_name``) [+ anonymous suffix].

    A non-empty ``__name:=`` replaces ``default_name`` and turns ``anonymous``
    off, as in rospy and roscpp.  The base name must be legal (letters, digits,
    ``_``; no ``/``), else :class:`InvalidNameError` -- stricter than rospy,
    which only warns; with ``lenient`` any non-empty name without ``/`` or
    ``~`` is taken, as rospy takes it.
    """
    name = default_name
    if args.name:
        name = args.name
        anonymous = False
    if not (lenient and isinstance(name, str) and name and SEP not in name and PRIV not in name):
        _validate_base_name(name, "node name")
    if anonymous:
        name = anonymous_name(name)
    return node_namespace(args, env) + name


def resolve_for_caller(name: str, caller_id: str) -> str:
    """Resolve a name the way the master does for a caller: in the caller's namespace, ``~`` under it."""
    return resolve_name(name, namespace_of(caller_id), caller_id)
