"""What every ``rostui topic`` tool shares: the master-call and output callables, its errors, name resolution."""

from __future__ import annotations

import os
from typing import Any, Callable

MasterCall = Callable[..., Any]
Out = Callable[[str], None]

#: rostopic's node name for master calls.
CALLER_ID = "/rostopic"


class TopicToolError(Exception):
    """A failure to report as one ``ERROR: ...`` line (exit 1)."""


class UsageError(TopicToolError):
    """Bad command-line input (reported like a parser error, exit 1)."""


def one_line(text: str) -> str:
    """Fold a multi-line message into one line."""
    parts = [p.strip() for p in str(text).splitlines() if p.strip()]
    if not parts:
        return ""
    head, rest = parts[0], [p.lstrip("* ").strip() for p in parts[1:]]
    if not rest:
        return head
    return head + (" " if head.endswith(":") else ": ") + ", ".join(rest)


def resolve_topic(name: str) -> str:
    """Resolve a command-line topic name as rostopic does (ROS_NAMESPACE, ``~`` under /rostopic)."""
    from rostui.core import names

    ns = os.environ.get("ROS_NAMESPACE", "/") or "/"
    if not ns.startswith("/"):
        ns = "/" + ns
    return names.resolve_name(name, ns, CALLER_ID)
