"""The drawn graph as Graphviz DOT text (``rostui graph --dot``), shaped like rqt_graph's.

Nodes are ellipses, topics boxes, collapsed namespaces folders; edges go
from publisher to subscriber, and in the nodes-only view carry the names of
the topics behind them as labels.  Output is sorted, so the same graph always
prints the same text.
"""

from __future__ import annotations

from rostui.models.graph.view import Kind, ViewGraph

__all__ = ["to_dot"]

_SHAPES = {Kind.NODE: "ellipse", Kind.TOPIC: "box", Kind.GROUP: "folder"}


def _quote(text: str) -> str:
    """A DOT string literal."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def to_dot(view: ViewGraph, *, title: str = "rosgraph", label_edges: bool = False) -> str:
    """DOT text for ``view`` (``label_edges``: name each edge's topics, as the nodes-only view does)."""
    lines = [f"digraph {_quote(title)} {{", "  rankdir=LR;"]
    for vid, vertex in view.vertices.items():
        lines.append(f"  {_quote(vid)} [label={_quote(vertex.label)}, shape={_SHAPES[vertex.kind]}];")
    for a, b in view.edges:
        topics = view.edge_topics.get((a, b), ())
        attrs = f" [label={_quote(chr(10).join(topics))}]" if label_edges and topics else ""
        lines.append(f"  {_quote(a)} -> {_quote(b)}{attrs};")
    lines.append("}")
    return "\n".join(lines) + "\n"
