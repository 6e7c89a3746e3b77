"""sensor_msgs/PointCloud2 projected onto the ground plane: the x and y fields of every point (numpy).

Any field layout is read: x and y of any PointField datatype, at any offset,
in either byte order, with any ``point_step`` and ``row_step`` (padding
between rows is skipped).  Points whose x or y is NaN or infinite are left out.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import Points

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


def cloud_points(cloud: Any) -> Points:
    """The (x, y) of every point of ``cloud`` with finite x and y, as an N x 2 float64 array in its frame.

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
    data = bytes(cloud.data)
    need = row_step * (height - 1) + width * step
    if len(data) < need:
        raise CloudError(f"{len(data)} bytes of data, {need} needed for {width} x {height} points")
    dtype = np.dtype({"names": ["x", "y"], "formats": [order + xt, order + yt], "offsets": [xo, yo],
                      "itemsize": step})
    rows = [np.frombuffer(data, dtype=dtype, count=width, offset=r * row_step) for r in range(height)]
    pts = rows[0] if height == 1 else np.concatenate(rows)
    xy = np.column_stack((pts["x"].astype(np.float64), pts["y"].astype(np.float64)))
    return xy[np.isfinite(xy).all(axis=1)]
