"""Why a view is empty: which filter hides which nodes and topics, and the key that shows them again.

The graph's first screen must not just say "nothing to show" when the only
nodes running are ``rostopic pub``'s or rosout, or when a filter matches
nothing: :func:`explain_empty` turns each filter that is on off in turn and
names what it would bring back, and :meth:`Explanation.lines` words that
for the screen.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from typing import Any, Callable

from rostui.models.graph.model import RosGraph
from rostui.models.graph.view import (
    DEBUG_NODES, FilterError, GraphOptions, Kind, ViewMode, build_view, is_tool_node,
)

__all__ = ["Hidden", "Explanation", "explain_empty", "START_HINT"]

#: What to run when the master has none of the user's nodes.
START_HINT = "rostui run turtlesim turtlesim_node"
#: Names listed in full before the rest are only counted.
NAMES_LISTED = 3


@dataclass(frozen=True)
class Hidden:
    """The nodes and topics one filter hides on its own, the filter's name and the key that turns it off."""

    filter: str
    short: str
    key: str
    how: str
    nodes: tuple[str, ...]
    topics: tuple[str, ...]


@dataclass(frozen=True)
class Explanation:
    """What the master holds although nothing is drawn, and which filters hide it.

    ``together`` names the filters that are on when no single one of them
    explains the empty view (each hides part, or several must go at once).
    """

    nodes: int
    topics: int
    hidden: tuple[Hidden, ...]
    together: tuple[Hidden, ...] = ()
    only_debug: bool = False

    def lines(self) -> list[str]:
        """The explanation as short lines: what the master has, then one line per filter and its key."""
        if self.nodes == 0:
            return ["The master has no nodes yet.",
                    f"Start one (for example `{START_HINT}`) and it appears here."]
        out = [f"Nothing drawn, but the master has {_count(self.nodes, 'node')} and "
               f"{_count(self.topics, 'topic')}:"]
        for hidden in self.hidden:
            out.append(f"• {_what(hidden)} hidden: {hidden.filter}. {hidden.how}.")
        if self.together:
            out.append(f"• hidden by {_together(self.together)} together: turn them off one by one.")
        if self.only_debug:
            out.append(f"Only ROS's own and the tools' nodes are running: start one of yours "
                       f"(for example `{START_HINT}`) and it appears here.")
        return out


def explain_empty(graph: RosGraph, options: GraphOptions) -> Explanation:
    """Why ``options`` draw nothing of ``graph``: what each filter that is on hides by itself."""
    plain = GraphOptions(view=ViewMode.ALL, hide_debug=False)
    everything = _shown(graph, plain)
    base = options.with_(view=ViewMode.ALL, group_namespaces=False, expanded=frozenset())
    shown = _shown(graph, base)
    nodes = sum(1 for vid in everything if vid.startswith("n:"))
    topics = len(everything) - nodes
    candidates = _filters(options)
    hidden: list[Hidden] = []
    for change, make in candidates:
        revealed = _shown(graph, base.with_(**change)) - shown
        if revealed:
            hidden.append(make(_names(revealed, Kind.NODE), _names(revealed, Kind.TOPIC)))
    together: tuple[Hidden, ...] = ()
    if not hidden and everything - shown:
        together = tuple(make((), ()) for _, make in candidates)
    graph_nodes = graph.nodes()
    only_debug = bool(graph_nodes) and options.hide_debug and all(
        n in DEBUG_NODES or is_tool_node(n) for n in graph_nodes)
    return Explanation(nodes, topics, tuple(hidden), together, only_debug)


def _shown(graph: RosGraph, options: GraphOptions) -> set[str]:
    try:
        return set(build_view(graph, options).vertices)
    except FilterError:
        return set()


def _names(vertices: set[str], kind: Kind) -> tuple[str, ...]:
    prefix = "n:" if kind is Kind.NODE else "t:"
    return tuple(sorted(v[2:] for v in vertices if v.startswith(prefix)))


def _filters(options: GraphOptions) -> list[tuple[dict[str, Any], Callable[..., Hidden]]]:
    """(the change that turns it off, a Hidden factory taking nodes and topics) for every filter that is on."""
    out: list[tuple[dict[str, Any], Callable[..., Hidden]]] = []
    if options.hide_debug:
        out.append(({"hide_debug": False},
                    partial(Hidden, "hide debug is on", "hide debug", "d", "Press d to show them")))
    if options.include:
        out.append(({"include": ""},
                    partial(Hidden, f"the include filter /{options.include}/ matches none of them",
                           f"include /{options.include}/", "i",
                           "Press i, clear the pattern and press Enter to show them")))
    if options.exclude:
        out.append(({"exclude": ""},
                    partial(Hidden, f"the exclude filter /{options.exclude}/ matches them",
                           f"exclude /{options.exclude}/", "x",
                           "Press x, clear the pattern and press Enter to show them")))
    if options.hide_leaf_topics:
        out.append(({"hide_leaf_topics": False},
                    partial(Hidden, "hide leaf topics is on", "hide leaf topics", "l", "Press l to show them")))
    if options.hide_dead_sinks:
        out.append(({"hide_dead_sinks": False},
                    partial(Hidden, "hide dead sinks is on", "hide dead sinks", "s", "Press s to show them")))
    return out


def _together(filters: tuple[Hidden, ...]) -> str:
    """``hide debug (d) and include /x/ (i)``."""
    named = [f"{h.short} ({h.key})" for h in filters]
    return named[0] if len(named) == 1 else ", ".join(named[:-1]) + " and " + named[-1]


def _what(hidden: Hidden) -> str:
    """``/rosout, 1 tool node (/rostopic_1_2) and 1 topic (/foo)``."""
    parts: list[str] = []
    tools = [n for n in hidden.nodes if is_tool_node(n)]
    rosout = [n for n in hidden.nodes if n in DEBUG_NODES]
    others = [n for n in hidden.nodes if n not in tools and n not in rosout]
    if others:
        parts.append(_listed(others, "node"))
    if tools:
        parts.append(_listed(tools, "tool node"))
    parts.extend(rosout)
    if hidden.topics:
        parts.append(_listed(list(hidden.topics), "topic"))
    if not parts:
        return "some nodes and topics are"
    text = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
    many = len(hidden.nodes) + len(hidden.topics) > 1
    return text + (" are" if many else " is")


def _listed(names: list[str], noun: str) -> str:
    """``2 tool nodes (/a, /b)``; past :data:`NAMES_LISTED` names only the first are named."""
    shown = ", ".join(names[:NAMES_LISTED]) + (", …" if len(names) > NAMES_LISTED else "")
    return f"{_count(len(names), noun)} ({shown})"


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" if number == 1 else f"{number} {noun}s"
