"""Successive snapshots of the graph, with what appeared or vanished marked for a few refreshes.

A vertex that vanished stays in the merged graph as a ghost (with the
registrations it last had) for :data:`KEEP_REFRESHES` refreshes, so the
drawing can show it fading out instead of reshuffling at once.
"""

from __future__ import annotations

from enum import Enum

from rostui.models.graph.model import RosGraph
from rostui.models.graph.view import node_id, topic_id

__all__ = ["Mark", "LiveGraph", "KEEP_REFRESHES"]

#: Refreshes a "new" or "gone" mark lasts.
KEEP_REFRESHES = 3


class Mark(str, Enum):
    """How a vertex changed lately."""

    NEW = "new"
    GONE = "gone"


class LiveGraph:
    """The latest snapshot plus recently vanished nodes and topics, and marks for both kinds of change."""

    def __init__(self, keep: int = KEEP_REFRESHES) -> None:
        self.keep = keep
        self.generation = -1
        self.current = RosGraph()
        self.graph = RosGraph()
        self._first_seen: dict[str, int] = {}
        self._ghosts: dict[str, tuple[int, dict[str, tuple[str, ...]], dict[str, tuple[str, ...]]]] = {}

    def update(self, snapshot: RosGraph) -> None:
        """Take a new snapshot; the first one marks nothing as new."""
        self.generation += 1
        gen = self.generation
        before = self.current
        present = {node_id(n) for n in snapshot.nodes()} | {topic_id(t) for t in snapshot.topics()}
        for vid in present:
            if vid not in self._first_seen:
                self._first_seen[vid] = gen if gen > 0 else -self.keep
            self._ghosts.pop(vid, None)
        for vid in list(self._first_seen):
            if vid in present:
                continue
            del self._first_seen[vid]
            self._ghosts[vid] = (gen, *_registrations(before, vid))
        for vid, (since, _, _) in list(self._ghosts.items()):
            if gen - since >= self.keep:
                del self._ghosts[vid]
        self.current = snapshot
        self.graph = self._merged(snapshot)

    def marks(self) -> dict[str, Mark]:
        """Vertex ids (``n:``/``t:``) that appeared or vanished within the last refreshes."""
        out = {vid: Mark.NEW for vid, seen in self._first_seen.items() if self.generation - seen < self.keep}
        out.update({vid: Mark.GONE for vid in self._ghosts})
        return out

    def _merged(self, snapshot: RosGraph) -> RosGraph:
        if not self._ghosts:
            return snapshot
        pubs = {t: set(n) for t, n in snapshot.publishers.items()}
        subs = {t: set(n) for t, n in snapshot.subscribers.items()}
        for _, old_pubs, old_subs in self._ghosts.values():
            for table, old in ((pubs, old_pubs), (subs, old_subs)):
                for topic, nodes in old.items():
                    table.setdefault(topic, set()).update(nodes)
        return RosGraph.build(pubs, subs, snapshot.services, snapshot.topic_types)


def _registrations(graph: RosGraph, vid: str) -> tuple[dict[str, tuple[str, ...]], dict[str, tuple[str, ...]]]:
    """The publisher and subscriber entries a vanished vertex had (a node's topics, or a topic's nodes)."""
    name = vid[2:]
    if vid.startswith("n:"):
        return ({t: (name,) for t in graph.publications_of(name)},
                {t: (name,) for t in graph.subscriptions_of(name)})
    return ({name: graph.publishers[name]} if name in graph.publishers else {},
            {name: graph.subscribers[name]} if name in graph.subscribers else {})
