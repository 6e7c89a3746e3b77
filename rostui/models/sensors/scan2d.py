"""sensor_msgs/LaserScan as points on the scanner's plane (numpy; no screen).

A range counts when it is finite and within ``[range_min, range_max]``;
the others (out of range, NaN, inf: "no return") are left out, as rviz does.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import Points

__all__ = ["scan_points"]


def scan_points(scan: Any) -> Points:
    """The returns of ``scan`` as an N x 2 array of (x, y) in the scan's frame, in beam order."""
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    if ranges.size == 0:
        return np.zeros((0, 2))
    angles = float(scan.angle_min) + float(scan.angle_increment) * np.arange(ranges.size)
    with np.errstate(invalid="ignore"):
        keep = np.isfinite(ranges) & (ranges >= float(scan.range_min)) & (ranges <= float(scan.range_max))
    r, a = ranges[keep], angles[keep]
    return np.column_stack((r * np.cos(a), r * np.sin(a)))
