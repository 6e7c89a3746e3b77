"""``Publisher.impl`` and ``Subscriber.impl``: the part of rospy's topic internals that libraries read.

actionlib (rospy's and rostui's) asks a publisher's ``impl.has_connection(callerid)`` and walks a
subscriber's ``impl.connections`` for each publisher's ``callerid_pub`` to know when an action server is
connected both ways; message_filters and others read ``impl.get_num_connections()``.
"""

from __future__ import annotations

from typing import Any

from rostui.core.records import FrozenRecord

__all__ = ["PublisherImpl", "SubscriberImpl", "Connection"]


class Connection(FrozenRecord):
    """One connection of a subscriber: the publisher it comes from."""

    __slots__ = _fields = ("callerid_pub",)

    callerid_pub: str

    def __init__(self, callerid_pub: str) -> None:
        self._set(callerid_pub)


class PublisherImpl:
    """A publisher's connections, as rospy's ``_PublisherImpl`` shows them."""

    def __init__(self, topic: Any) -> None:
        self._topic = topic

    def has_connection(self, endpoint_id: str) -> bool:
        """Whether the node ``endpoint_id`` subscribes through a live connection."""
        handle = self._topic._impl
        return handle is not None and endpoint_id in handle.subscriber_names()

    def get_num_connections(self) -> int:
        """Connected subscribers."""
        handle = self._topic._impl
        return 0 if handle is None else int(handle.get_num_connections())


class SubscriberImpl:
    """A subscriber's connections, as rospy's ``_SubscriberImpl`` shows them."""

    def __init__(self, topic: Any) -> None:
        self._topic = topic

    @property
    def connections(self) -> list[Connection]:
        """One entry per connected publisher."""
        handle = self._topic._impl
        return [] if handle is None else [Connection(name) for name in sorted(handle.publisher_names())]

    def get_num_connections(self) -> int:
        """Connected publishers."""
        handle = self._topic._impl
        return 0 if handle is None else int(handle.get_num_connections())
