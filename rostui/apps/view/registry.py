"""Which widget shows which message type: the registry behind `rostui view`, the monitor's Enter and the bag inspector.

Each view module registers its types with ONE entry in :data:`VIEWS`:
the message types it shows and ``"module:Class"`` of its widget.  Modules
are imported only when a topic of their type is shown, so asking what can
be shown costs nothing.

A view is a :class:`TopicView`: a Textual widget created with the topic's
name (``cls(topic)``, or ``cls(topic, classes=...)`` in the bag inspector:
keep that signature) that gets each decoded message through
:meth:`TopicView.show_message`, or, when it has costly work that needs no
screen (decoding an image), through :meth:`TopicView.off_loop` (the work,
run by a live panel on a worker thread) and :meth:`TopicView.show_prepared`.  Callers hand it only the newest message,
when they are ready to draw (frames are dropped, never queued); the panel
around it subscribes only while it is on screen.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable

from textual.widget import Widget

from rostui.apps.view.feed import Rate

__all__ = ["TopicView", "VIEWS", "UnknownViewError", "view_class", "viewable", "viewable_types"]


class TopicView(Widget):
    """Base of every view: shows the messages of one topic, given one at a time to :meth:`show_message`."""

    def __init__(self, topic: str, *, id: str | None = None, classes: str | None = None) -> None:
        super().__init__(id=id, classes=classes)
        self.topic = topic
        self.arrivals: Rate | None = None
        """Every message the topic delivered, drawn or dropped (set by the live panel; None in a bag)."""

    @classmethod
    def for_bag(cls, topic: str, *, classes: str | None = None) -> TopicView:
        """The view as `bag view`'s inspector shows it: one message at a time, given to :meth:`show_message`.

        Views that would otherwise listen on their own (the tf tree) override it to listen to nothing.
        """
        return cls(topic, classes=classes)

    def show_message(self, msg: Any, received: float) -> None:
        """Draw ``msg`` (a decoded message), which arrived at wall time ``received`` (seconds).

        Views override it; the base draws nothing, so a subclass that forgets it shows nothing.
        """
        raise NotImplementedError(f"{type(self).__name__} must define show_message")

    def dropped(self, topic: str, count: int) -> None:
        """``count`` messages of ``topic`` that every one counts (markers) were dropped before they were shown,
        the screen being too slow; views that keep such topics say so (the base ignores it)."""

    def off_loop(self, msg: Any, received: float) -> Callable[[], Any] | None:
        """Work on ``msg`` that needs no screen, for a live panel to run on a worker thread (called on the loop;
        None: nothing to do off the loop, :meth:`show_message` is called instead).

        What the returned callable makes is handed to :meth:`show_prepared` on the loop.
        """
        return None

    def show_prepared(self, prepared: Any, received: float) -> None:
        """Draw what the callable of :meth:`off_loop` made."""
        raise NotImplementedError(f"{type(self).__name__} must define show_prepared with off_loop")


#: (message types, "module:Class") for each view; one entry per view module.
VIEWS: tuple[tuple[tuple[str, ...], str], ...] = (
    (("sensor_msgs/Image", "sensor_msgs/CompressedImage"), "rostui.apps.view.image_view:ImageView"),
    (("tf2_msgs/TFMessage",), "rostui.apps.view.tf_tree_view:TfTreeView"),
    (("sensor_msgs/LaserScan", "nav_msgs/Odometry", "nav_msgs/Path", "geometry_msgs/PoseStamped",
      "geometry_msgs/PoseArray", "nav_msgs/OccupancyGrid", "sensor_msgs/PointCloud2", "geometry_msgs/PolygonStamped",
      "visualization_msgs/Marker", "visualization_msgs/MarkerArray"),
     "rostui.apps.view.topdown_view:TopDownView"),
)


class UnknownViewError(LookupError):
    """No view shows this message type; the message names the types that can be shown."""


def viewable_types() -> list[str]:
    """Every message type some view shows, sorted."""
    return sorted({t for types, _ in VIEWS for t in types})


def viewable(msg_type: str) -> bool:
    """True when a view shows messages of ``msg_type``."""
    return any(msg_type in types for types, _ in VIEWS)


def view_class(msg_type: str) -> type[TopicView]:
    """The widget class that shows ``msg_type``; :class:`UnknownViewError` (one clear line) when none does."""
    for types, where in VIEWS:
        if msg_type in types:
            module, _, name = where.partition(":")
            cls = getattr(importlib.import_module(module), name)
            assert isinstance(cls, type) and issubclass(cls, TopicView)
            return cls
    raise UnknownViewError(f"no view shows {msg_type}; rostui view shows {', '.join(viewable_types())}")
