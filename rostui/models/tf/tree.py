"""The tf tree as rows to draw: each frame under its parent, with its edge's broadcaster, rate, age and kind.

Roots come first in name order, each followed by its subtree (children in name order), drawn
with box-drawing branches as ``view_frames`` lays them out top-down. Frames whose parent links
go round in a loop have no root; they follow, marked as such.
"""

from __future__ import annotations

from dataclasses import dataclass

from rostui.models.tf.buffer import Edge, TfBuffer

__all__ = ["TreeRow", "tree_rows", "format_rate", "format_age", "summary"]


@dataclass(frozen=True)
class TreeRow:
    """One frame on screen: ``prefix`` (branches) then ``frame``; ``edge`` is None for a root."""

    frame: str
    depth: int
    prefix: str
    edge: Edge | None
    in_loop: bool = False

    def label(self) -> str:
        """The branches and the frame name."""
        return self.prefix + self.frame


def tree_rows(buffer: TfBuffer) -> list[TreeRow]:
    """Every frame of ``buffer`` in drawing order."""
    children: dict[str, list[str]] = {}
    for edge in buffer.edges():
        children.setdefault(edge.parent, []).append(edge.child)
    rows: list[TreeRow] = []
    placed: set[str] = set()

    def walk(frame: str, depth: int, lead: str, last: bool) -> None:
        branch = "" if depth == 0 else lead + ("└─ " if last else "├─ ")
        rows.append(TreeRow(frame, depth, branch, buffer.edge(frame)))
        placed.add(frame)
        kids = [c for c in children.get(frame, []) if c not in placed]
        below = "" if depth == 0 else lead + ("   " if last else "│  ")
        for i, kid in enumerate(kids):
            walk(kid, depth + 1, below, i == len(kids) - 1)

    for root in buffer.roots():
        walk(root, 0, "", True)
    for frame in buffer.frames():
        if frame not in placed:
            rows.append(TreeRow(frame, 0, "", buffer.edge(frame), in_loop=True))
            placed.add(frame)
    return rows


def format_rate(edge: Edge | None) -> str:
    """``20.0 Hz``, ``static``, or empty (a root, or too few messages yet)."""
    if edge is None:
        return ""
    if edge.static:
        return "static"
    rate = edge.rate()
    return f"{rate:.1f} Hz" if rate is not None else ""


def format_age(edge: Edge | None, now: float) -> str:
    """Seconds since the newest stamp of a dynamic edge (``0.02 s``); empty for roots and static edges."""
    if edge is None or edge.static:
        return ""
    age = edge.age(now)
    if abs(age) < 10:
        return f"{age:.2f} s"
    return f"{age:.0f} s"


def summary(buffer: TfBuffer) -> str:
    """``5 frames, 1 tree`` (and how many are static, how many in a loop)."""
    frames = len(buffer.frames())
    roots = len(buffer.roots())
    static = sum(1 for e in buffer.edges() if e.static)
    text = f"{frames} frame{'' if frames == 1 else 's'}, {roots} tree{'' if roots == 1 else 's'}"
    if static:
        text += f", {static} static"
    loops = sum(1 for r in tree_rows(buffer) if r.in_loop)
    if loops:
        text += f", {loops} in a loop"
    return text
