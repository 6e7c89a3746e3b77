"""``--clock``: the bag time on ``/clock`` (rosgraph_msgs/Clock), as ``rosbag play --clock`` publishes it.

One piece serves ``rostui bag play`` and ``rostui bag view``. The clock is
published before each message with that message's time, and on every tick of
the transport (``hz`` times a second) with the bag time then, never ahead of
the next message. While paused it keeps publishing the time playback stands
at, as rosbag play does, so nodes on simulated time see the clock stop, not
vanish; a seek while paused moves it.
"""

from __future__ import annotations

from typing import Any

from rostui.core.bag.model import BagError

__all__ = ["BagClock", "DEFAULT_HZ"]

#: ``--hz``'s default: rosbag play's clock rate.
DEFAULT_HZ = 100.0


class BagClock:
    """A ``/clock`` publisher of bag time on a node, at most every ``1/hz`` s on ticks (plus one per message)."""

    def __init__(self, hz: float = DEFAULT_HZ) -> None:
        if not hz > 0 or hz == float("inf"):
            raise BagError(f"the clock rate (--hz) must be a positive number, not {hz:g}")
        self.hz = hz
        self.publisher: Any = None
        self.last_ns: int | None = None

    @property
    def period(self) -> float:
        """Seconds between two ticks of the clock."""
        return 1.0 / self.hz

    def tick_period(self, other: float) -> float:
        """The transport's tick period that serves both the clock and a caller ticking every ``other`` s."""
        return min(other, self.period)

    async def advertise(self, node: Any) -> None:
        """Advertise ``/clock`` on ``node``; publishing does nothing before this."""
        from rostui.core.msg import get_message_class

        self.publisher = await node.advertise("/clock", get_message_class("rosgraph_msgs/Clock"), queue_size=1)

    def publish(self, bag_ns: int) -> None:
        """Publish ``bag_ns`` (nanoseconds of bag time) on ``/clock``."""
        pub = self.publisher
        if pub is None:
            return
        msg = pub.msg_class()
        msg.clock.secs, msg.clock.nsecs = divmod(bag_ns, 1_000_000_000)
        pub.publish(msg)
        self.last_ns = bag_ns
