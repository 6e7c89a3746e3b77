"""sensor_msgs/PointCloud2 projected onto the ground plane: the x and y fields of every point (numpy).

Any field layout is read: x and y of any PointField datatype, at any offset,
in either byte order, with any ``point_step`` and ``row_step`` (padding
between rows is skipped).  Points whose x or y is NaN or infinite are left out.
The data is read in place through strides, and a cloud of more than
:data:`~rostui.models.sensors.pose2d.MAX_POINTS` points with a stride over its
points: only the points drawn are touched, however many rows it has.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import MAX_POINTS, Points, every

__all__ = ["CloudError", "DATATYPES", "cloud_points"]

#: sensor_msgs/PointField datatype constants -> numpy type codes (without byte order).
DATATYPES: dict[int, str] = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


class CloudError(ValueError):
    """A PointCloud2 that cannot be read: no x or y field, an unknown datatype, or too little data."""


def _field(cloud: Any, name: str) -> tuple[int, str]:
    for field in cloud.fields:
        if field.name == name:
            code = DATATYPES.get(int(field.datatype))
            if code is None:
                raise CloudError(f"field {name} has unknown datatype {field.datatype}")
            return int(field.offset), code
    raise CloudError(f"no {name} field (fields: {', '.join(f.name for f in cloud.fields) or 'none'})")


def cloud_points(cloud: Any, max_points: int = MAX_POINTS) -> Points:
    """The (x, y) of the points of ``cloud`` (at most ``max_points``, evenly strided) with finite x and y, as an
    N x 2 float64 array in its frame.

    Raises :class:`CloudError` when the cloud cannot be read.
    """
    width, height = int(cloud.width), int(cloud.height)
    step, row_step = int(cloud.point_step), int(cloud.row_step)
    if width * height == 0:
        return np.zeros((0, 2))
    order = ">" if cloud.is_bigendian else "<"
    (xo, xt), (yo, yt) = _field(cloud, "x"), _field(cloud, "y")
    size_x, size_y = np.dtype(xt).itemsize, np.dtype(yt).itemsize
    if step < max(xo + size_x, yo + size_y) or row_step < width * step:
        raise CloudError(f"point_step {step} / row_step {row_step} too small for fields at {xo} and {yo}")
    data = np.frombuffer(cloud.data, dtype=np.uint8)
    need = row_step * (height - 1) + width * step
    if data.size < need:
        raise CloudError(f"{data.size} bytes of data, {need} needed for {width} x {height} points")
    picked = np.arange(0, width * height, every(width * height, max_points), dtype=np.int64)
    rows, cols = np.divmod(picked, width)

    def column(offset: int, code: str) -> np.ndarray:
        grid = np.ndarray((height, width), dtype=np.dtype(order + code), buffer=data, offset=offset,
                          strides=(row_step, step))
        return grid[rows, cols].astype(np.float64)

    xy = np.column_stack((column(xo, xt), column(yo, yt)))
    return xy[np.isfinite(xy).all(axis=1)]
