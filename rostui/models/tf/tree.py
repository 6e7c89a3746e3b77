"""The tf tree as rows to draw: each frame under its parent, with its edge's broadcaster, rate, age and kind.

Roots come first in name order, each followed by its subtree (children in name order), drawn
with box-drawing branches as ``view_frames`` lays them out top-down; below :data:`MAX_INDENT`
levels the branches above are counted, not drawn (``┄2984┄``), so a row stays narrow however deep
its frame. Frames whose parent links go round in a loop have no root; they follow, marked as
such, each with the frames that hang below it.
"""

from __future__ import annotations

from dataclasses import dataclass

from rostui.tools.tf.buffer import Edge, TfBuffer

__all__ = ["TreeRow", "tree_rows", "loop_frames", "format_rate", "format_age", "summary", "MAX_INDENT"]

MAX_INDENT = 16
"""Levels of branches drawn before a row; a deeper frame's row counts the levels above them instead."""


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
    """Every frame of ``buffer`` in drawing order (walked without recursion: a chain may be thousands deep)."""
    children: dict[str, list[str]] = {}
    for edge in buffer.edges():
        children.setdefault(edge.parent, []).append(edge.child)
    looping = loop_frames(buffer)
    rows: list[TreeRow] = []
    placed: set[str] = set()

    def walk(top: str) -> None:
        # (frame, depth, the "last child" marks of the ancestors drawn as branches, this frame's mark)
        stack: list[tuple[str, int, tuple[bool, ...], bool]] = [(top, 0, (), True)]
        while stack:
            frame, depth, marks, last = stack.pop()
            rows.append(TreeRow(frame, depth, _prefix(depth, marks, last), buffer.edge(frame), frame in looping))
            placed.add(frame)
            kids = [c for c in children.get(frame, []) if c not in placed and c not in looping]
            below = () if depth == 0 else (marks + (last,))[-MAX_INDENT:]
            for i in range(len(kids) - 1, -1, -1):
                stack.append((kids[i], depth + 1, below, i == len(kids) - 1))

    for root in buffer.roots():
        walk(root)
    for frame in sorted(looping):
        walk(frame)
    return rows


def _prefix(depth: int, marks: tuple[bool, ...], last: bool) -> str:
    """The branches before a frame at ``depth``: one column of three cells per ancestor, the deepest
    :data:`MAX_INDENT` drawn, those above them counted."""
    if depth == 0:
        return ""
    lead = "".join("   " if done else "│  " for done in marks)
    hidden = depth - 1 - len(marks)
    return (f"┄{hidden}┄ " if hidden > 0 else "") + lead + ("└─ " if last else "├─ ")


def loop_frames(buffer: TfBuffer) -> set[str]:
    """The frames whose parent links go round in a circle (not those that merely hang below one)."""
    state: dict[str, int] = {}  # 1: on the path walked now, 2: done
    looping: set[str] = set()
    for start in buffer.frames():
        path: list[str] = []
        frame: str | None = start
        while frame is not None and frame not in state:
            state[frame] = 1
            path.append(frame)
            frame = buffer.parent(frame)
        if frame is not None and state[frame] == 1:
            looping.update(path[path.index(frame):])
        for f in path:
            state[f] = 2
    return looping


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


def summary(buffer: TfBuffer, rows: list[TreeRow] | None = None) -> str:
    """``5 frames, 1 tree`` (and how many are static, how many in a loop); ``rows``: the buffer's, if made."""
    frames = len(buffer.frames())
    roots = len(buffer.roots())
    static = sum(1 for e in buffer.edges() if e.static)
    text = f"{frames} frame{'' if frames == 1 else 's'}, {roots} tree{'' if roots == 1 else 's'}"
    if static:
        text += f", {static} static"
    loops = sum(1 for r in (tree_rows(buffer) if rows is None else rows) if r.in_loop)
    if loops:
        text += f", {loops} in a loop"
    return text
