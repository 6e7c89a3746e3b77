"""A Publisher's ``subscriber_listener``: rospy's SubscribeListener told of each subscriber, as rospy tells it.

``peer_subscribe(topic_name, topic_publish, peer_publish)`` runs when a
subscriber connects, before a latched message reaches it: ``topic_publish``
sends to every subscriber, ``peer_publish`` to that one only.
``peer_unsubscribe(topic_name, num_peers)`` runs when one leaves, with the
number still connected. Both run on the node's engine thread.
"""

from __future__ import annotations

from typing import Any, Callable

from rostui.core.node.topics import OutgoingLink, Publication

__all__ = ["ListenerRelay", "rospy_service_header"]


class ListenerRelay:
    """Relays a :class:`~rostui.core.node.topics.Publication`'s peer events to a rospy SubscribeListener."""

    def __init__(self, listener: Any, topic_publish: Callable[..., None]) -> None:
        self.listener = listener
        self.topic_publish = topic_publish

    def peer_added(self, pub: Publication, link: OutgoingLink) -> None:
        """Call ``peer_subscribe`` with publish functions for the topic and for this subscriber."""
        def peer_publish(msg: Any) -> None:
            pub.publish_to(link, msg)

        self.listener.peer_subscribe(pub.topic, self.topic_publish, peer_publish)

    def peer_removed(self, pub: Publication, remaining: int) -> None:
        """Call ``peer_unsubscribe`` with the number of subscribers left."""
        self.listener.peer_unsubscribe(pub.topic, remaining)


def rospy_service_header(name: str, service_class: Any, caller_id: str) -> Callable[[], dict[str, str]]:
    """The header fields a rospy service server sends its clients, in rospy's order."""
    def fields() -> dict[str, str]:
        return {"callerid": caller_id, "md5sum": service_class._md5sum, "service": name,
                "type": service_class._type}

    return fields
