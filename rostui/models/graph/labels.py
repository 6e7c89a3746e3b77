"""The topic names written on the edges of the nodes-only view, in full or abbreviated with a legend.

rqt_graph labels every node-to-node edge with its topic.  On a terminal a
label takes columns, so :func:`edge_labels` gives each edge up to
:data:`MAX_ROWS` lines (one topic a line, the rest counted) in one of three
styles, widest first: full names; abbreviations (``…/cmd_vel``: the last
segments, as many as keep two topics apart, or ``/sim1/…/cmd_vel``); or
numbered keys (``[1]``).  The last two come with a legend that spells them
out.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Iterable, Mapping

from rostui.models.graph.view import ViewGraph

__all__ = ["LabelStyle", "EdgeLabels", "edge_labels", "abbreviations", "MAX_ROWS", "FULL_LIMIT", "SHORT_LIMIT",
           "cut_middle"]

#: Topics written on one edge before the rest are counted ("+2 more").
MAX_ROWS = 3
#: Longest full label; longer names are cut in the middle.
FULL_LIMIT = 40
#: Longest abbreviated label.
SHORT_LIMIT = 32


class LabelStyle(str, Enum):
    """How topics are written on edges: in full, abbreviated, or as numbered keys (widest first)."""

    FULL = "full"
    SHORT = "short"
    KEYS = "keys"


@dataclass(frozen=True)
class EdgeLabels:
    """The lines written on each edge and, when abbreviated, the legend ``(abbreviation, topic)``."""

    lines: Mapping[tuple[str, str], tuple[str, ...]]
    legend: tuple[tuple[str, str], ...] = ()
    style: LabelStyle = LabelStyle.FULL


def cut_middle(text: str, limit: int) -> str:
    """``text`` cut in the middle with "…" when longer than ``limit``."""
    if len(text) <= limit:
        return text
    head = (limit - 1) // 2
    return text[:head] + "…" + text[len(text) - (limit - 1 - head):]


def _candidates(topic: str) -> list[str]:
    """Shorter names of ``topic``, shortest first: ``…/c``, ``…/b/c``, ``/a/…/c``, then the name itself."""
    segments = [p for p in topic.split("/") if p]
    out = ["…/" + "/".join(segments[-keep:]) for keep in range(1, len(segments))]
    if len(segments) > 2:
        out.append(f"/{segments[0]}/…/{segments[-1]}")
    out.sort(key=len)
    return out + [topic]


def abbreviations(topics: Iterable[str]) -> dict[str, str]:
    """Each topic's shortest abbreviation that could stand for no other topic here (``…/cmd_vel``)."""
    names = sorted(set(topics))
    options = {t: _candidates(t) for t in names}
    out: dict[str, str] = {}
    for topic in names:
        taken = {c for other in names if other != topic for c in options[other]}
        out[topic] = next(c for c in options[topic] if c not in taken or c == topic)
    return out


def edge_labels(view: ViewGraph, style: LabelStyle = LabelStyle.FULL) -> EdgeLabels:
    """The label lines of every edge of ``view`` that carries topics, in ``style``."""
    topics = sorted({t for ts in view.edge_topics.values() for t in ts})
    if style is LabelStyle.SHORT:
        names = {t: cut_middle(a, SHORT_LIMIT) for t, a in abbreviations(topics).items()}
    elif style is LabelStyle.KEYS:
        names = {t: f"[{number}]" for number, t in enumerate(topics, 1)}
    else:
        names = {t: cut_middle(t, FULL_LIMIT) for t in topics}
    lines: dict[tuple[str, str], tuple[str, ...]] = {}
    written: set[str] = set()
    for edge in view.edges:
        ts = view.edge_topics.get(edge, ())
        if not ts:
            continue
        shown = ts if len(ts) <= MAX_ROWS else ts[:MAX_ROWS - 1]
        written.update(shown)
        lines[edge] = tuple(names[t] for t in shown)
        if len(shown) < len(ts):
            lines[edge] += (f"+{len(ts) - len(shown)} more",)
    legend = tuple((names[t], t) for t in sorted(written) if names[t] != t)
    return EdgeLabels(lines, legend, style)
