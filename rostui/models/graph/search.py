"""Fuzzy matching of what the user types against node and topic names (for jumping around big graphs)."""

from __future__ import annotations

from typing import Iterable

__all__ = ["fuzzy_score", "fuzzy_rank"]


def fuzzy_score(query: str, text: str) -> float | None:
    """How well ``query`` matches ``text`` as a subsequence (higher is better); None when it does not.

    Case is ignored.  Consecutive characters, characters right after ``/``
    or ``_``, an exact substring and shorter texts score higher.
    """
    if not query:
        return 0.0
    q, t = query.lower(), text.lower()
    if q in t:
        at = t.index(q)
        boundary = at == 0 or t[at - 1] in "/_"
        return 1000.0 + (200.0 if boundary else 0.0) - len(t) - at * 0.1
    score = 0.0
    pos = 0
    run = 0
    for ch in q:
        found = t.find(ch, pos)
        if found < 0:
            return None
        run = run + 1 if found == pos and pos > 0 else 0
        score += 10.0 + 15.0 * run
        if found == 0 or t[found - 1] in "/_":
            score += 20.0
        score -= (found - pos) * 0.5
        pos = found + 1
    return score - len(t) * 0.1


def fuzzy_rank(query: str, names: Iterable[str], limit: int | None = None) -> list[str]:
    """``names`` matching ``query``, best first (ties by name)."""
    scored = [(s, name) for name in names if (s := fuzzy_score(query, name)) is not None]
    scored.sort(key=lambda item: (-item[0], item[1]))
    found = [name for _, name in scored]
    return found if limit is None else found[:limit]
