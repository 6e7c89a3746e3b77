"""A top-down :data:`~rostui.models.sensors.scene2d.Lookup` over a tf buffer: transforms projected to the ground.

The transform between two frames is looked up at the latest time both are
known (tf's ``lookupTransform(target, source, Time(0))``) and applied to the
source frame's ground plane (z = 0), then seen from above: exact for points
on that plane, so an upside-down laser is drawn mirrored, as it scans.
"""

from __future__ import annotations

from rostui.models.sensors.pose2d import Planar
from rostui.models.sensors.scene2d import Lookup
from rostui.tools.tf.buffer import TfBuffer, TfError

__all__ = ["buffer_lookup"]


def buffer_lookup(buffer: TfBuffer) -> Lookup:
    """``lookup(target, source)`` answering from ``buffer``: ``source``'s plane in ``target``, or None."""
    def lookup(target: str, source: str) -> Planar | None:
        try:
            transform = buffer.lookup_transform(target, source).transform
        except (TfError, ValueError):
            return None
        return Planar.from_rotation(transform.matrix()[:3, :3], transform.translation)

    return lookup
