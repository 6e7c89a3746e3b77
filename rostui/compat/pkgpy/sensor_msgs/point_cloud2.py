"""sensor_msgs.point_cloud2: build and read ``sensor_msgs/PointCloud2`` messages, for unmodified scripts.

The Python module the sensor_msgs package ships, written for rostui: the same
functions and results. A point is one value per field (a field whose ``count``
is above 1 takes that many values), packed at the field's offset with
``struct`` in the cloud's byte order; bytes between fields are padding.
"""

from __future__ import annotations

import math
import struct
import sys
from collections import namedtuple
from typing import Any, Iterable, Iterator, Sequence

from rostui.core.msg import get_message_class

__all__ = ["create_cloud", "create_cloud_xyz32", "read_points", "read_points_list"]

PointCloud2: Any = get_message_class("sensor_msgs/PointCloud2")
PointField: Any = get_message_class("sensor_msgs/PointField")

_CODES: dict[int, tuple[str, int]] = {
    PointField.INT8: ("b", 1), PointField.UINT8: ("B", 1),
    PointField.INT16: ("h", 2), PointField.UINT16: ("H", 2),
    PointField.INT32: ("i", 4), PointField.UINT32: ("I", 4),
    PointField.FLOAT32: ("f", 4), PointField.FLOAT64: ("d", 8),
}


def _layout(is_bigendian: bool, fields: Iterable[Any], field_names: Sequence[str] | None = None) -> str:
    """The ``struct`` format of one point's chosen fields, padding included, in the cloud's byte order."""
    fmt = ">" if is_bigendian else "<"
    position = 0
    for field in sorted(fields, key=lambda f: f.offset):
        if field_names is not None and field.name not in field_names:
            continue
        code = _CODES.get(field.datatype)
        if code is None:
            print(f"Skipping unknown PointField datatype [{field.datatype}]", file=sys.stderr)
            continue
        if position < field.offset:
            fmt += "x" * (field.offset - position)
            position = field.offset
        fmt += code[0] * field.count
        position += code[1] * field.count
    return fmt


def read_points(cloud: Any, field_names: Sequence[str] | None = None, skip_nans: bool = False,
                uvs: Iterable[tuple[int, int]] = ()) -> Iterator[tuple[Any, ...]]:
    """Yield each point of *cloud* as a tuple of its (chosen) fields' values.

    *skip_nans* leaves out points with a NaN value; *uvs*, ``(column, row)``
    pairs, reads only those points.
    """
    point = struct.Struct(_layout(cloud.is_bigendian, cloud.fields, field_names))
    data = bytes(cloud.data)
    step, row_step = cloud.point_step, cloud.row_step

    def offsets() -> Iterator[int]:
        if uvs:
            for u, v in uvs:
                yield row_step * v + step * u
            return
        for v in range(cloud.height):
            for u in range(cloud.width):
                yield row_step * v + step * u

    for offset in offsets():
        values = point.unpack_from(data, offset)
        if skip_nans and any(isinstance(x, float) and math.isnan(x) for x in values):
            continue
        yield values


def read_points_list(cloud: Any, field_names: Sequence[str] | None = None, skip_nans: bool = False,
                     uvs: Iterable[tuple[int, int]] = ()) -> list[Any]:
    """:func:`read_points` as a list of namedtuples ``Point`` whose fields are the field names."""
    names = list(field_names) if field_names is not None else [f.name for f in cloud.fields]
    Point = namedtuple("Point", names)  # type: ignore[misc]
    return [Point._make(values) for values in read_points(cloud, field_names, skip_nans, uvs)]


def create_cloud(header: Any, fields: Sequence[Any], points: Iterable[Iterable[Any]]) -> Any:
    """An unorganised (one row), little-endian PointCloud2 of *points*, one value per field each."""
    point = struct.Struct(_layout(False, fields))
    rows = list(points)
    data = bytearray(point.size * len(rows))
    for index, values in enumerate(rows):
        point.pack_into(data, index * point.size, *values)
    return PointCloud2(header=header, height=1, width=len(rows), is_dense=False, is_bigendian=False,
                       fields=fields, point_step=point.size, row_step=point.size * len(rows), data=bytes(data))


def create_cloud_xyz32(header: Any, points: Iterable[Iterable[Any]]) -> Any:
    """:func:`create_cloud` with three float32 fields ``x``, ``y``, ``z``."""
    fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
              PointField("z", 8, PointField.FLOAT32, 1)]
    return create_cloud(header, fields, points)
