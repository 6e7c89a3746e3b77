"""The few ROS graph-name operations the master needs, with rosmaster's semantics.

Kept here (rather than in ``rostui.core.names``) so the master depends on
nothing but itself; the rules are ROS 1's: ``/global``, ``relative`` (in the
caller's namespace) and ``~private`` (under the caller's own name).
"""

from __future__ import annotations

SEP = "/"


def canonicalize(name: str) -> str:
    """Drop empty segments and any trailing slash: ``//a//b/`` -> ``/a/b``."""
    if not name or name == SEP:
        return name
    if name[0] == SEP:
        if "//" not in name and name[-1] != SEP:
            return name
        return SEP + SEP.join([x for x in name.split(SEP) if x])
    return SEP.join([x for x in name.split(SEP) if x])


def namespace(name: str) -> str:
    """The namespace of ``name``, with a trailing slash: ``/a/b`` -> ``/a/``."""
    if not name:
        return SEP
    if name[-1] == SEP:
        name = name[:-1]
    return name[: name.rfind(SEP) + 1] or SEP


def ns_join(ns: str, name: str) -> str:
    """Join ``ns`` and ``name`` unless ``name`` is global or private."""
    if name[:1] in (SEP, "~"):
        return name
    if ns == "~":
        return "~" + name
    if not ns:
        return name
    if ns[-1] == SEP:
        return ns + name
    return ns + SEP + name


def resolve(name: str, caller_id: str) -> str:
    """Resolve ``name`` to a global canonical name for the node ``caller_id``."""
    if not name:
        return namespace(caller_id)
    name = canonicalize(name)
    first = name[0]
    if first == SEP:
        return name
    if first == "~":
        return canonicalize(caller_id + SEP + name[1:])
    return namespace(caller_id) + name
