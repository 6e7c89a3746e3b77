"""nav_msgs/OccupancyGrid as an array that answers "what is at this point?" (numpy; no screen)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from rostui.models.sensors.pose2d import Points, Pose2D, pose_of

__all__ = ["OCCUPIED", "UNKNOWN", "GridError", "Grid2D", "grid_of"]

#: Occupancy (0..100) from which a cell counts as occupied (map_server's default occupied_thresh 0.65).
OCCUPIED = 65

#: The value of unknown cells, and of every point off the grid.
UNKNOWN = -1


class GridError(ValueError):
    """An OccupancyGrid whose data does not match its width and height."""


@dataclass(frozen=True)
class Grid2D:
    """An occupancy grid: ``values[row, col]`` (-1 unknown, 0..100), cells of ``resolution`` metres.

    Cell (0, 0) has its corner at ``origin`` (a pose in the grid's frame);
    rows grow along the origin's y axis, columns along its x axis.
    """

    values: npt.NDArray[np.int8]
    resolution: float
    origin: Pose2D

    def sample(self, points: Points) -> npt.NDArray[np.int8]:
        """The value of the cell under each point (N x 2, in the grid's frame); -1 off the grid."""
        local = self.origin.inverse().apply(points) / self.resolution
        cols = np.floor(local[:, 0]).astype(np.int64)
        rows = np.floor(local[:, 1]).astype(np.int64)
        height, width = self.values.shape
        inside = (cols >= 0) & (cols < width) & (rows >= 0) & (rows < height)
        out = np.full(len(points), UNKNOWN, dtype=np.int8)
        out[inside] = self.values[rows[inside], cols[inside]]
        return out

    def occupied(self, points: Points) -> npt.NDArray[np.bool_]:
        """True for each point over an occupied cell (occupancy of :data:`OCCUPIED` or more)."""
        return self.sample(points) >= OCCUPIED


def grid_of(msg: Any) -> Grid2D:
    """The :class:`Grid2D` of a nav_msgs/OccupancyGrid; :class:`GridError` when its data has the wrong size."""
    info = msg.info
    width, height, resolution = int(info.width), int(info.height), float(info.resolution)
    raw = msg.data
    values = (np.frombuffer(raw, dtype=np.int8) if isinstance(raw, (bytes, bytearray, memoryview, np.ndarray))
              else np.asarray(raw, dtype=np.int64).astype(np.int8))
    if values.size != width * height:
        raise GridError(f"{values.size} cells of data for a {width} x {height} grid")
    if resolution <= 0 or not np.isfinite(resolution):
        raise GridError(f"resolution {resolution} is not a positive number of metres")
    return Grid2D(values.reshape(height, width), resolution, pose_of(info.origin))
