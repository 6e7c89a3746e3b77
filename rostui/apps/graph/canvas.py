"""The graph drawn as characters: box-drawing lines for edges, boxes for vertices (no Textual here).

Nodes are rounded boxes, topics square boxes, collapsed namespaces double
boxes; edges are light lines with ``▶`` heads (``◀`` on the real target of an
edge that had to point backwards to break a cycle).  Every cell remembers
what drew it, so the widget can colour, highlight and hit-test by cell.

An edge of the nodes-only view carries its topic names as rqt_graph's do:
the layout gives each label a place of its own, like a vertex of one row
per topic between the two nodes (Graphviz lays out edge labels the same
way), and the edge's line runs into the label and out of it on its middle
row.  Abbreviated labels get a legend under the drawing.
"""

from __future__ import annotations

from typing import Mapping

from rostui.models.graph.labels import EdgeLabels
from rostui.models.graph.layout import Box, Layout, LayoutHint, back_edges, layered_layout
from rostui.models.graph.view import Kind, ViewGraph

__all__ = ["Canvas", "draw", "label_text", "box_size", "layout_view", "label_id", "MAX_LABEL", "LEGEND_TITLE"]

#: Longest label drawn in full; longer names are cut in the middle with "…".
MAX_LABEL = 48

_UP, _DOWN, _LEFT, _RIGHT = 1, 2, 4, 8
_LINES = {
    0: " ", _UP: "│", _DOWN: "│", _UP | _DOWN: "│", _LEFT: "─", _RIGHT: "─", _LEFT | _RIGHT: "─",
    _DOWN | _RIGHT: "╭", _DOWN | _LEFT: "╮", _UP | _RIGHT: "╰", _UP | _LEFT: "╯",
    _UP | _DOWN | _RIGHT: "├", _UP | _DOWN | _LEFT: "┤", _LEFT | _RIGHT | _DOWN: "┬", _LEFT | _RIGHT | _UP: "┴",
    _UP | _DOWN | _LEFT | _RIGHT: "┼",
}
#: Corners and sides per kind: top-left, top-right, bottom-left, bottom-right, horizontal, vertical.
_BORDERS: dict[Kind, tuple[str, ...]] = {
    Kind.NODE: tuple("╭╮╰╯─│"),
    Kind.TOPIC: tuple("┌┐└┘─│"),
    Kind.GROUP: tuple("╔╗╚╝═║"),
}

#: Owner value of a cell nothing drew.
EMPTY = -1


def label_text(name: str, limit: int = MAX_LABEL) -> str:
    """``name`` cut in the middle with "…" when longer than ``limit``."""
    if len(name) <= limit:
        return name
    head = (limit - 1) // 2
    return name[:head] + "…" + name[len(name) - (limit - 1 - head):]


def box_size(label: str) -> tuple[int, int]:
    """Columns and rows of the box around ``label``."""
    return len(label_text(label)) + 4, 3


#: The line above the legend of abbreviated edge labels.
LEGEND_TITLE = "Topics on the edges:"


def label_id(edge: tuple[str, str]) -> str:
    """The layout id of the label on ``edge`` (never a vertex id: those start with n:, t: or g:)."""
    return f"l:{edge[0]}>{edge[1]}"


def layout_view(view: ViewGraph, hint: LayoutHint | None = None,
                labels: Mapping[tuple[str, str], tuple[str, ...]] | None = None) -> Layout:
    """The layered layout of ``view`` with every vertex sized for its label.

    Each edge in ``labels`` goes through a place of its own for its lines
    (as wide as the longest line plus a space each side, one row a line).
    An edge that closes a cycle goes through its label backwards, target
    first, so the label stays between its two nodes; its label starts with
    ``◀`` (two columns more) to say which way the messages go.
    """
    sizes = {vid: box_size(v.label) for vid, v in view.vertices.items()}
    if not labels:
        return layered_layout(sizes, view.edges, hint)
    backwards = back_edges(list(sizes), view.edges, hint)
    edges: list[tuple[str, str]] = []
    for edge in view.edges:
        lines = labels.get(edge)
        if not lines:
            edges.append(edge)
            continue
        lid = label_id(edge)
        back = edge in backwards
        sizes[lid] = (max(len(line) for line in lines) + 2 + 2 * back, len(lines))
        a, b = edge
        edges += [(b, lid), (lid, a)] if back else [(a, lid), (lid, b)]
    return layered_layout(sizes, edges, hint)


#: Rows per bucket of the vertical-segment index.
_BLOCK = 64


class Canvas:
    """The drawing of a view at the places a layout gives, built row by row when a row is first asked for.

    Each row is a list of characters plus, per cell, the index of the vertex
    (>= 0, into ``vertex_ids``), the edge (``-2 - k`` for edge ``k`` of
    ``edges``) or the edge label (``-2 - len(edges) - k``) that drew it;
    :data:`EMPTY` where nothing did.  Rows are cached, so scrolling back
    costs nothing.  ``boxes`` holds the vertices' boxes only, ``legend`` the
    abbreviations spelt out under the drawing.
    """

    def __init__(self, view: ViewGraph, layout: Layout, labels: EdgeLabels | None = None) -> None:
        self.vertex_ids: list[str] = list(view.vertices)
        self.boxes: dict[str, Box] = {k: b for k, b in layout.boxes.items() if k in view.vertices}
        self.edges: list[tuple[str, str]] = [e for e in view.edges if e[0] in self.boxes and e[1] in self.boxes]
        self.labels = labels
        self.legend: tuple[tuple[str, str], ...] = labels.legend if labels is not None else ()
        self._horizontal: dict[int, list[tuple[int, int, int]]] = {}
        self._vertical: dict[int, list[tuple[int, int, int, int]]] = {}
        self._box_rows: dict[int, list[tuple[int, str, int]]] = {}
        self._arrows: dict[int, list[tuple[int, str, int]]] = {}
        self._cache: dict[int, tuple[list[str], list[int]]] = {}
        index = {e: k for k, e in enumerate(self.edges)}
        labelled = {label_id(e): e for e in self.edges if labels is not None and e in labels.lines}
        view_edge: list[int] = []
        for a, b in layout.edges:
            edge = labelled.get(b) or labelled.get(a) or (a, b)
            view_edge.append(index.get(edge, -1))
        self.width = max(layout.width, 1)
        self.height = max(layout.height, 1)
        for seg in layout.segments:
            owner = -2 - view_edge[seg.edge]
            if seg.y0 == seg.y1:
                lo, hi = sorted((seg.x0, seg.x1))
                self._horizontal.setdefault(seg.y0, []).append((lo, hi, owner))
            else:
                lo, hi = sorted((seg.y0, seg.y1))
                item = (seg.x0, lo, hi, owner)
                for block in range(lo // _BLOCK, hi // _BLOCK + 1):
                    self._vertical.setdefault(block, []).append(item)
        for number, vid in enumerate(self.vertex_ids):
            box = layout.boxes.get(vid)
            if box is None:
                continue
            vertex = view.vertices[vid]
            for dy, text in enumerate(_box_lines(box, vertex.kind, label_text(vertex.label))):
                self._box_rows.setdefault(box.y + dy, []).append((box.x, text, number))
        hops = set(layout.edges)
        for lid, edge in labelled.items():
            box = layout.boxes[lid]
            assert labels is not None
            owner = -2 - len(self.edges) - index[edge]
            backwards = (edge[1], lid) in hops
            for dy, text in enumerate(_label_lines(box, labels.lines[edge], backwards)):
                self._box_rows.setdefault(box.y + dy, []).append((box.x, text, owner))
        for arrow in layout.arrows:
            tail, head = layout.edges[arrow.edge]
            owner = -2 - view_edge[arrow.edge]
            if head in labelled and not arrow.left:
                continue  # the head goes on the node after the label
            if tail in labelled and head == labelled[tail][0]:
                # a backwards edge (label, then its source): the head goes on its target, to the left
                target = self.boxes[labelled[tail][1]]
                self._arrows.setdefault(target.center_row, []).append((target.x + target.w, "◀", owner))
                continue
            self._arrows.setdefault(arrow.y, []).append((arrow.x, "◀" if arrow.left else "▶", owner))
        if self.legend:
            column = max(len(short) for short, _ in self.legend)
            rows = [LEGEND_TITLE] + [f"  {short.ljust(column)}  {full}" for short, full in self.legend]
            top = self.height + 1
            for dy, text in enumerate(rows):
                self._box_rows.setdefault(top + dy, []).append((0, text, EMPTY))
            self.height = top + len(rows)
            self.width = max(self.width, max(len(r) for r in rows))

    def row(self, y: int) -> tuple[list[str], list[int]]:
        """Characters and owners of row ``y`` (built on first use)."""
        cached = self._cache.get(y)
        if cached is not None:
            return cached
        width = self.width
        masks = bytearray(width)
        owners = [EMPTY] * width
        for lo, hi, owner in self._horizontal.get(y, ()):
            if lo == hi:
                masks[lo] |= _LEFT | _RIGHT
                owners[lo] = owner
                continue
            masks[lo] |= _RIGHT
            owners[lo] = owner
            for x in range(lo + 1, hi):
                masks[x] |= _LEFT | _RIGHT
                owners[x] = owner
            masks[hi] |= _LEFT
            owners[hi] = owner
        for x, lo, hi, owner in self._vertical.get(y // _BLOCK, ()):
            if lo <= y <= hi:
                masks[x] |= (_UP if y > lo else 0) | (_DOWN if y < hi else 0)
                owners[x] = owner
        lines = _LINES
        chars = [lines[m] for m in masks]
        for x, text, owner in self._box_rows.get(y, ()):
            chars[x:x + len(text)] = text
            owners[x:x + len(text)] = [owner] * len(text)
        for x, char, owner in self._arrows.get(y, ()):
            chars[x] = char
            owners[x] = owner
        self._cache[y] = (chars, owners)
        return chars, owners

    def line(self, y: int) -> str:
        """Row ``y`` as a string."""
        return "".join(self.row(y)[0])

    def text(self) -> str:
        """The whole drawing as lines of text (trailing spaces removed)."""
        return "\n".join(self.line(y).rstrip() for y in range(self.height))

    def edge_of(self, owner: int) -> tuple[int, bool] | None:
        """For an owner value: the index into ``edges`` and whether it is the edge's label (None: not an edge)."""
        if owner > -2:
            return None
        k = -2 - owner
        count = len(self.edges)
        return (k, False) if k < count else (k - count, True)

    def owner_at(self, x: int, y: int) -> str | None:
        """The vertex id drawn at ``(x, y)``, if a box covers it."""
        if 0 <= y < self.height and 0 <= x < self.width:
            owner = self.row(y)[1][x]
            if owner >= 0:
                return self.vertex_ids[owner]
        return None

    def edge_at(self, x: int, y: int) -> tuple[str, str] | None:
        """The edge drawn at ``(x, y)``, if a line covers it."""
        if 0 <= y < self.height and 0 <= x < self.width:
            found = self.edge_of(self.row(y)[1][x])
            if found is not None:
                return self.edges[found[0]]
        return None


def draw(view: ViewGraph, layout: Layout, labels: EdgeLabels | None = None) -> Canvas:
    """Draw ``view`` at the places ``layout`` gives (with ``labels`` on its edges, laid out by :func:`layout_view`)."""
    return Canvas(view, layout, labels)


def _label_lines(box: Box, lines: tuple[str, ...], backwards: bool = False) -> list[str]:
    """The rows of an edge label: one line each, the middle one continuing the edge's line to its right.

    A backwards edge's label has ``◀`` before its middle line.
    """
    middle = box.h // 2
    out = []
    for dy, line in enumerate(lines):
        text = " " + ("◀ " if backwards and dy == middle else "  " if backwards else "") + line + " "
        out.append(text + ("─" if dy == middle else " ") * (box.w - len(text)))
    return out


def _box_lines(box: Box, kind: Kind, label: str) -> tuple[str, str, str]:
    """Top border, label row and bottom border of a box."""
    tl, tr, bl, br, h, v = _BORDERS[kind]
    inner = box.w - 2
    return (tl + h * inner + tr, v + (" " + label).ljust(inner)[:inner] + v, bl + h * inner + br)
