""""Did you mean …": the closest of the master's current names to a misspelt one."""

from __future__ import annotations

from typing import Any, Iterable

CUTOFF = 0.6
"""How alike (difflib's ratio, 0..1) a name must be to be suggested."""


def closest_names(name: str, candidates: Iterable[str]) -> list[str]:
    """The candidates most like ``name``: the best one, and any that tie with it; [] when none is close.

    ``name`` itself is never suggested.  difflib is imported here, on the error
    path only, so commands that succeed never load it.
    """
    import difflib

    pool = sorted({c for c in candidates if c != name})
    matches = difflib.get_close_matches(name, pool, n=3, cutoff=CUTOFF)
    if not matches:
        return []

    def score(candidate: str) -> float:
        return difflib.SequenceMatcher(None, name, candidate).ratio()

    best = score(matches[0])
    return sorted(m for m in matches if score(m) == best)


def with_namespaces(names: Iterable[str]) -> set[str]:
    """``names`` and every namespace above them (``/a/b/c`` gives ``/a``, ``/a/b``, ``/a/b/c``)."""
    found: set[str] = set()
    for name in names:
        parts = name.strip("/").split("/")
        found.update("/" + "/".join(parts[:i]) for i in range(1, len(parts) + 1))
    return found


def registered_topics(system_state: Any) -> set[str]:
    """The topics someone publishes or subscribes to now, from getSystemState's value.

    Not getTopicTypes': the master keeps a topic's type after its last publisher and subscriber have gone
    (rosmaster does too), so its names include topics no one can echo any more.
    """
    publishers, subscribers = system_state[0], system_state[1]
    return {topic for topic, _nodes in publishers} | {topic for topic, _nodes in subscribers}


def did_you_mean(name: str, candidates: Iterable[str]) -> str | None:
    """``did you mean /turtle1/pose?`` (``/a or /b?`` for ties), or None when nothing is close."""
    names = closest_names(name, candidates)
    if not names:
        return None
    listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
    return f"did you mean {listed}?"
