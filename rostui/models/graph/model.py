"""One snapshot of the master's registrations: nodes, topics with their publishers and subscribers, services."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Collection, Mapping, Sequence

from rostui.tools.node import Registrations

__all__ = ["RosGraph", "fetch_graph", "fetch_graph_async"]


@dataclass(frozen=True)
class RosGraph(Registrations):
    """What ``getSystemState`` and ``getTopicTypes`` report at one moment.

    Every mapping goes from a topic (or service) name to the sorted tuple of
    node names holding that registration; ``topic_types`` maps topic names
    to message types (``"unknown type"`` is never stored: absent means unknown).
    """

    publishers: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    subscribers: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    services: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    topic_types: Mapping[str, str] = field(default_factory=dict)

    @classmethod
    def from_wire(cls, state: Sequence[Any], types: Sequence[Any] = ()) -> "RosGraph":
        """Build from the values of ``getSystemState`` and ``getTopicTypes`` (already unwrapped)."""
        pubs, subs, srvs = (list(part) for part in state)

        def table(entries: list) -> dict[str, tuple[str, ...]]:
            out: dict[str, set[str]] = {}
            for name, nodes in entries:
                out.setdefault(str(name), set()).update(str(n) for n in nodes)
            return {name: tuple(sorted(nodes)) for name, nodes in sorted(out.items()) if nodes}

        return cls(table(pubs), table(subs), table(srvs), {str(t): str(ty) for t, ty in types})

    @classmethod
    def build(cls, publishers: Mapping[str, Collection[str]] | None = None,
              subscribers: Mapping[str, Collection[str]] | None = None,
              services: Mapping[str, Collection[str]] | None = None,
              topic_types: Mapping[str, str] | None = None) -> "RosGraph":
        """A graph from plain mappings (benchmarks, tests, merged live views)."""
        def norm(table: Mapping[str, Collection[str]] | None) -> dict[str, tuple[str, ...]]:
            return {k: tuple(sorted(set(v))) for k, v in sorted((table or {}).items()) if v}

        return cls(norm(publishers), norm(subscribers), norm(services), dict(topic_types or {}))

    def nodes(self) -> list[str]:
        """Every node holding a registration, sorted."""
        return list(self._nodes)

    def topics(self) -> list[str]:
        """Every topic with a publisher or a subscriber, sorted."""
        return list(self._topics)

    @cached_property
    def vertex_cache(self) -> dict[str, Any]:
        """Vertex objects of this graph's views, by id (filled by :func:`rostui.models.graph.view.build_view`)."""
        return {}

    @cached_property
    def _nodes(self) -> tuple[str, ...]:
        found: set[str] = set()
        for table in (self.publishers, self.subscribers, self.services):
            for nodes in table.values():
                found.update(nodes)
        return tuple(sorted(found))

    @cached_property
    def _topics(self) -> tuple[str, ...]:
        return tuple(sorted(set(self.publishers) | set(self.subscribers)))

    def topic_type(self, topic: str) -> str:
        """The message type of ``topic`` as the master knows it."""
        return self.topic_types.get(topic, "unknown type")



def fetch_graph(call: Callable[..., Any]) -> RosGraph:
    """Ask the master (``call(method, *args)`` returning unwrapped values) for the current graph."""
    return RosGraph.from_wire(call("getSystemState"), call("getTopicTypes"))


async def fetch_graph_async(call: Callable[..., Any]) -> RosGraph:
    """:func:`fetch_graph` for an async ``call`` (e.g. a bound XmlRpcClient wrapper)."""
    state = await call("getSystemState")
    types = await call("getTopicTypes")
    return RosGraph.from_wire(state, types)
