"""sensor_msgs/LaserScan as points on the scanner's plane (numpy; no screen).

A range counts when it is finite and within ``[range_min, range_max]``;
the others (out of range, NaN, inf: "no return") are left out, as rviz does.
A scan of more than :data:`~rostui.models.sensors.pose2d.MAX_POINTS` beams is
read with a stride (every k-th beam): only the beams drawn are touched.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import MAX_POINTS, Points, every

__all__ = ["scan_points"]


def scan_points(scan: Any, max_points: int = MAX_POINTS) -> Points:
    """The returns of ``scan`` (at most ``max_points`` beams, evenly strided) as an N x 2 array of (x, y) in
    the scan's frame, in beam order."""
    count = len(scan.ranges)
    if count == 0:
        return np.zeros((0, 2))
    stride = every(count, max_points)
    ranges = np.asarray(scan.ranges[::stride], dtype=np.float64)
    angles = float(scan.angle_min) + float(scan.angle_increment) * stride * np.arange(ranges.size)
    with np.errstate(invalid="ignore"):
        keep = np.isfinite(ranges) & (ranges >= float(scan.range_min)) & (ranges <= float(scan.range_max))
    r, a = ranges[keep], angles[keep]
    return np.column_stack((r * np.cos(a), r * np.sin(a)))
