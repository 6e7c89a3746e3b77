"""rqt_graph's views and filters: which vertices and edges of a :class:`RosGraph` are drawn.

Vertex ids keep nodes, topics and namespace groups apart even when names
collide (the ``/rosout`` node and the ``/rosout`` topic): ``n:/name``,
``t:/name`` and ``g:/namespace``.
"""

from __future__ import annotations

import re
from collections import deque
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import Any, Iterable, Mapping, Sequence

from rostui.models.graph.model import RosGraph

__all__ = [
    "Kind", "ViewMode", "Vertex", "ViewGraph", "GraphOptions", "FilterError", "book_setup",
    "is_debug_node", "is_debug_topic", "is_tool_node", "TOOL_NODES", "node_id", "topic_id", "group_id", "name_of", "kind_of",
    "compile_pattern", "build_view", "focus_view", "namespace_of",
]


class Kind(str, Enum):
    """What a vertex stands for."""

    NODE = "node"
    TOPIC = "topic"
    GROUP = "group"


class ViewMode(str, Enum):
    """rqt_graph's drop-down: which vertices a view has."""

    NODES = "nodes"
    ACTIVE = "active"
    ALL = "all"

    @property
    def label(self) -> str:
        """The name rqt_graph gives the view."""
        return {"nodes": "Nodes only", "active": "Nodes/Topics (active)", "all": "Nodes/Topics (all)"}[self.value]

    def next(self) -> "ViewMode":
        """The following view, wrapping around."""
        order = list(ViewMode)
        return order[(order.index(self) + 1) % len(order)]


_PREFIX = {Kind.NODE: "n:", Kind.TOPIC: "t:", Kind.GROUP: "g:"}
_KINDS = {"n": Kind.NODE, "t": Kind.TOPIC, "g": Kind.GROUP}


def node_id(name: str) -> str:
    """The vertex id of node ``name``."""
    return "n:" + name


def topic_id(name: str) -> str:
    """The vertex id of topic ``name``."""
    return "t:" + name


def group_id(namespace: str) -> str:
    """The vertex id of the group standing for ``namespace``."""
    return "g:" + namespace


def name_of(vertex: str) -> str:
    """The graph name inside a vertex id."""
    return vertex[2:]


def kind_of(vertex: str) -> Kind:
    """The kind of a vertex id."""
    return _KINDS[vertex[0]]


#: Base names of the introspection tools whose nodes "Hide debug" hides: ROS's command-line tools, rqt's
#: plugin hosts and rostui's own apps.  Data sources and sinks a user runs on purpose (rosbag's and
#: rostui's recorders and players, the bag view) are not tools in this sense: their edges are data flow.
TOOL_NODES = frozenset({
    "rostopic", "rosnode", "rosservice", "rosparam", "roswtf", "rqt_gui_py_node", "rqt_gui_cpp_node",
    "rostui_graph", "rostui_console", "rostui_monitor", "rostui_loggers",
})
#: ``base_<pid>_<ms>`` (rospy's and rostui's anonymous names), ``base_<ns>`` (roscpp's) or
#: ``base_<pid>`` (rqt's plugin hosts): a base name followed by one or two numbers.
_NUMBERED = re.compile(r"^(?P<base>.+?)(?:_\d+){1,2}$")
#: Nodes that exist for logging and introspection only.
DEBUG_NODES = frozenset({"/rosout"})
#: Topics that carry logging and introspection only.
DEBUG_TOPICS = frozenset({"/rosout", "/rosout_agg", "/statistics"})


def is_tool_node(name: str) -> bool:
    """True for an introspection tool's anonymous node: ``/rostopic_1234_1700000000000``, in any namespace.

    Only a :data:`TOOL_NODES` base with the numbers an anonymous name gets
    counts: a user's ``/rostui_listener`` is not a tool, nor is a user's
    anonymous ``/talker_1234_1700000000000`` (rospy's tutorial listener is
    anonymous, and it is part of the user's system).
    """
    match = _NUMBERED.match(name[name.rfind("/") + 1:])
    return match is not None and match.group("base") in TOOL_NODES


def is_debug_node(name: str) -> bool:
    """True for nodes that "Hide debug" hides: /rosout and the anonymous tool nodes (:func:`is_tool_node`)."""
    return name in DEBUG_NODES or is_tool_node(name)


def is_debug_topic(name: str) -> bool:
    """True for topics that "Hide debug" hides: /rosout, /rosout_agg, /statistics."""
    return name in DEBUG_TOPICS


def namespace_of(name: str) -> str | None:
    """The top-level namespace of a name (``/turtle1/pose`` -> ``/turtle1``); None for names in ``/``."""
    second = name.find("/", 1)
    return name[:second] if second > 0 else None


class FilterError(ValueError):
    """A filter the user typed cannot be used; the message says which and why, in one line."""


def compile_pattern(pattern: str, what: str) -> re.Pattern[str] | None:
    """Compile a user's regular expression (None when empty); FilterError when malformed."""
    if not pattern:
        return None
    try:
        return re.compile(pattern)
    except re.error as exc:
        raise FilterError(f"bad {what} regex {pattern!r}: {exc}") from None


@dataclass(frozen=True)
class GraphOptions:
    """What to draw: rqt_graph's view drop-down, its "Hide" and "Group" boxes, and two regex filters.

    ``include``: a vertex is kept when its name matches, or when it is
    directly connected to a node or topic whose name matches (so
    ``/turtle1`` shows the /turtle1 topics with the nodes that use them).
    ``exclude``: vertices whose names match are never shown.
    ``expanded``: namespaces drawn member by member while grouping is on.
    """

    view: ViewMode = ViewMode.NODES
    hide_debug: bool = True
    hide_dead_sinks: bool = False
    hide_leaf_topics: bool = False
    group_namespaces: bool = False
    expanded: frozenset[str] = frozenset()
    include: str = ""
    exclude: str = ""

    def with_(self, **changes: Any) -> "GraphOptions":
        """A copy with ``changes`` applied."""
        return replace(self, **changes)

    def describe(self) -> str:
        """One line naming the view and every option that is on."""
        parts = [self.view.label]
        for flag, label in ((self.hide_debug, "hide debug"), (self.hide_dead_sinks, "hide dead sinks"),
                            (self.hide_leaf_topics, "hide leaf topics"), (self.group_namespaces, "group ns")):
            if flag:
                parts.append(label)
        if self.include:
            parts.append(f"include /{self.include}/")
        if self.exclude:
            parts.append(f"exclude /{self.exclude}/")
        return " · ".join(parts)


def book_setup(options: GraphOptions | None = None) -> GraphOptions:
    """The book's preferred setup: Nodes/Topics (all) with every box unchecked except Hide debug."""
    return GraphOptions(view=ViewMode.ALL, hide_debug=True)


@dataclass(frozen=True)
class Vertex:
    """One box on the screen: a node, a topic, or a collapsed namespace (``members`` are its vertex ids)."""

    id: str
    kind: Kind
    name: str
    members: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        """The text in the box."""
        if self.kind is Kind.GROUP:
            return f"▸ {self.name} ({len(self.members)})"
        return self.name


@dataclass(frozen=True)
class ViewGraph:
    """The vertices and directed edges a view draws (edges point from publisher to subscriber).

    ``edge_topics`` names the topics behind each edge of the nodes-only
    view (and the collapsed edges of groups).
    """

    vertices: Mapping[str, Vertex]
    edges: tuple[tuple[str, str], ...]
    edge_topics: Mapping[tuple[str, str], tuple[str, ...]] = field(default_factory=dict)

    def neighbours(self) -> dict[str, set[str]]:
        """Each vertex's neighbours, ignoring edge direction."""
        adj: dict[str, set[str]] = {v: set() for v in self.vertices}
        for a, b in self.edges:
            adj[a].add(b)
            adj[b].add(a)
        return adj

    def signature(self) -> tuple:
        """A value equal for two views with the same vertices (and labels), edges and edge topics."""
        return (tuple((v.id, v.label) for v in self.vertices.values()), self.edges,
                tuple(sorted(self.edge_topics.items())))


def _matches(pattern: re.Pattern[str] | None, name: str) -> bool:
    return pattern is not None and pattern.search(name) is not None


def build_view(graph: RosGraph, options: GraphOptions) -> ViewGraph:
    """The vertices and edges ``options`` select from ``graph`` (FilterError for a bad regex).

    Runs on every keystroke of a filter, so it avoids work it can: vertices
    are cached per graph, and they and the edges come out already in id order.
    """
    include = compile_pattern(options.include, "include")
    exclude = compile_pattern(options.exclude, "exclude")
    topic_views = options.view is not ViewMode.NODES
    hide_debug = options.hide_debug
    active_only = options.view is ViewMode.ACTIVE
    dead_sinks, leaves = options.hide_dead_sinks, options.hide_leaf_topics

    nodes = [n for n in graph.nodes() if not is_debug_node(n)] if hide_debug else graph.nodes()
    visible_nodes = set(nodes)
    pubs: dict[str, Sequence[str]] = {}
    subs: dict[str, Sequence[str]] = {}
    empty: tuple[str, ...] = ()
    publishers, subscribers = graph.publishers, graph.subscribers
    for topic in graph.topics():
        if hide_debug and topic in DEBUG_TOPICS:
            continue
        all_pubs, all_subs = publishers.get(topic, empty), subscribers.get(topic, empty)
        if active_only and not (all_pubs and all_subs):
            continue
        p: Sequence[str] = all_pubs
        s: Sequence[str] = all_subs
        if hide_debug:
            p = [n for n in all_pubs if n in visible_nodes]
            s = [n for n in all_subs if n in visible_nodes]
        if not p and not s:
            continue
        if dead_sinks and not s:
            continue
        if leaves and len(set(p) | set(s)) < 2:
            continue
        pubs[topic], subs[topic] = p, s

    if include is not None:
        nodes, topics = _included(include, nodes, pubs, subs, topic_views)
    else:
        topics = list(pubs)
    if exclude is not None:
        nodes = [n for n in nodes if not exclude.search(n)]
        topics = [t for t in topics if not exclude.search(t)]
    shown_nodes = set(nodes)
    cache = graph.vertex_cache

    def vertex(vid: str, kind: Kind, name: str) -> Vertex:
        found = cache.get(vid)
        if found is None:
            found = cache[vid] = Vertex(vid, kind, name)
        return found

    vertices: dict[str, Vertex] = {}
    for n in nodes:
        nid = "n:" + n
        vertices[nid] = vertex(nid, Kind.NODE, n)
    if topic_views:
        edge_list: list[tuple[str, str]] = []
        for topic in topics:
            tid = "t:" + topic
            ends = [("n:" + n, tid) for n in pubs[topic] if n in shown_nodes]
            ends += [(tid, "n:" + n) for n in subs[topic] if n in shown_nodes]
            if not ends and include is not None and not include.search(topic):
                continue
            vertices[tid] = vertex(tid, Kind.TOPIC, topic)
            edge_list += ends
        if options.group_namespaces:
            topic_of = {e: [name_of(e[1] if e[1][0] == "t" else e[0])] for e in edge_list}
            return _grouped(vertices, topic_of, options.expanded)
        edge_list.sort()
        return ViewGraph(vertices, tuple(edge_list), {})
    edges: dict[tuple[str, str], list[str]] = {}
    for topic in topics:
        for pub in pubs[topic]:
            if pub not in shown_nodes:
                continue
            for sub in subs[topic]:
                if pub != sub and sub in shown_nodes:
                    edges.setdefault(("n:" + pub, "n:" + sub), []).append(topic)
    if options.group_namespaces:
        return _grouped(vertices, edges, options.expanded)
    return ViewGraph(vertices, tuple(sorted(edges)), {e: tuple(sorted(ts)) for e, ts in edges.items()})


def _included(include: re.Pattern[str], nodes: list[str], pubs: Mapping[str, Sequence[str]],
              subs: Mapping[str, Sequence[str]], topic_views: bool) -> tuple[list[str], list[str]]:
    """Nodes and topics kept by ``include``: the matches plus their direct neighbours."""
    seed_nodes = {n for n in nodes if include.search(n)}
    keep_nodes = set(seed_nodes)
    keep_topics: set[str] = set()
    for topic in pubs:
        ends = set(pubs[topic]) | set(subs[topic])
        if include.search(topic):
            keep_topics.add(topic)
            keep_nodes.update(ends)
        elif not topic_views or ends & seed_nodes:
            keep_topics.add(topic)
    return [n for n in nodes if n in keep_nodes], [t for t in pubs if t in keep_topics]


def _grouped(vertices: dict[str, Vertex], edges: dict[tuple[str, str], list[str]],
             expanded: frozenset[str]) -> ViewGraph:
    """Fold every collapsed namespace with two or more members into one group vertex."""
    members: dict[str, list[str]] = {}
    for vid, vertex in vertices.items():
        ns = namespace_of(vertex.name)
        if ns is not None:
            members.setdefault(ns, []).append(vid)
    owner: dict[str, str] = {}
    out: dict[str, Vertex] = {}
    for ns, ids in members.items():
        if len(ids) >= 2 and ns not in expanded:
            gid = group_id(ns)
            out[gid] = Vertex(gid, Kind.GROUP, ns, tuple(sorted(ids)))
            for vid in ids:
                owner[vid] = gid
    for vid, vertex in vertices.items():
        if vid not in owner:
            out[vid] = vertex
    folded: dict[tuple[str, str], set[str]] = {}
    for (a, b), topics in edges.items():
        a2, b2 = owner.get(a, a), owner.get(b, b)
        if a2 != b2:
            folded.setdefault((a2, b2), set()).update(topics)
    ordered = {k: out[k] for k in sorted(out)}
    return ViewGraph(ordered, tuple(sorted(folded)), {e: tuple(sorted(ts)) for e, ts in folded.items()})


def focus_view(view: ViewGraph, center: str, hops: int) -> ViewGraph:
    """``center`` and every vertex at most ``hops`` edges away (either direction), with their edges."""
    if center not in view.vertices:
        return view
    adj = view.neighbours()
    seen = {center: 0}
    queue = deque([center])
    while queue:
        v = queue.popleft()
        if seen[v] >= hops:
            continue
        for w in sorted(adj[v]):
            if w not in seen:
                seen[w] = seen[v] + 1
                queue.append(w)
    vertices = {k: v for k, v in view.vertices.items() if k in seen}
    edges = tuple(e for e in view.edges if e[0] in seen and e[1] in seen)
    return ViewGraph(vertices, edges, {e: view.edge_topics[e] for e in edges if e in view.edge_topics})


def element_ids(view: ViewGraph) -> Iterable[str]:
    """Every vertex id of ``view``, in drawing order."""
    return iter(view.vertices)
