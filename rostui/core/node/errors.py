"""The errors of the synchronous, rospy-shaped face of a node (:mod:`rostui.core.node.sync`)."""

from __future__ import annotations

__all__ = ["ROSException", "ROSInterruptException", "ROSTimeMovedBackwardsException"]


class ROSException(Exception):
    """Base error of the sync API."""


class ROSInterruptException(ROSException, KeyboardInterrupt):
    """Raised by sleep() and Rate.sleep() when the node shuts down."""


class ROSTimeMovedBackwardsException(ROSInterruptException):
    """ROS time went backwards during a sleep (simulated time was reset); *time* is the jump in seconds."""

    def __init__(self, time: float = 0.0) -> None:
        self.time = time
        super().__init__("ROS time moved backwards")
