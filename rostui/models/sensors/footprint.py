"""The robot's footprint as costmap_2d reads it, and geometry_msgs/PolygonStamped, as closed outlines.

costmap_2d takes ``footprint`` either as a string, ``"[[x, y], [x, y], ...]"``,
or as a list of ``[x, y]`` pairs, with at least three points; without one it
takes ``robot_radius``, a circle.  :func:`footprint_outline` accepts all three
(a number is the radius) and says in one line what is wrong with anything else.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rostui.models.sensors.pose2d import MAX_POSES, Points

__all__ = ["FootprintError", "footprint_outline", "polygon_points", "closed"]

#: Vertices of a round robot's outline.
CIRCLE_VERTICES = 32

#: Longest footprint string read (a footprint is a few dozen points).
MAX_TEXT = 1 << 16


class FootprintError(ValueError):
    """A footprint costmap_2d would refuse, in one line."""


def _number(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise FootprintError(f"{where}: {str(value)[:40]!r} is not a number")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        raise FootprintError(f"{where}: {str(value)[:40]!r} is not a finite number")
    return number


def _parse_text(text: str) -> Any:
    import yaml

    if len(text) > MAX_TEXT:
        raise FootprintError(f"a footprint string of {len(text)} characters is longer than {MAX_TEXT}")
    try:
        return yaml.safe_load(text)
    except (yaml.YAMLError, ValueError, RecursionError):
        raise FootprintError(f"the footprint string {text[:80]!r} is not a list of [x, y] points") from None


def footprint_outline(value: Any) -> Points:
    """The closed outline (first point repeated last) of a footprint: a string or list of ``[x, y]`` pairs, or a
    number (``robot_radius``: a circle)."""
    if isinstance(value, str):
        value = _parse_text(value)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        radius = _number(value, "the robot radius")
        if radius <= 0:
            raise FootprintError(f"the robot radius {radius:g} is not positive")
        angles = np.linspace(0.0, 2 * math.pi, CIRCLE_VERTICES, endpoint=False)
        return closed(np.column_stack((radius * np.cos(angles), radius * np.sin(angles))))
    if not isinstance(value, list) or len(value) < 3:
        raise FootprintError("a footprint needs at least three [x, y] points, as costmap_2d reads it")
    if len(value) > MAX_POSES:
        raise FootprintError(f"a footprint of {len(value)} points is more than {MAX_POSES}")
    points = []
    for index, point in enumerate(value):
        if not isinstance(point, list) or len(point) != 2:
            raise FootprintError(f"footprint point {index + 1}: {point!r} is not an [x, y] pair")
        points.append((_number(point[0], f"footprint point {index + 1}"),
                       _number(point[1], f"footprint point {index + 1}")))
    return closed(np.array(points, dtype=np.float64))


def closed(points: Points) -> Points:
    """``points`` with the first repeated at the end (a polyline that closes)."""
    return np.concatenate((points, points[:1])) if len(points) else points


def polygon_points(msg: Any, most: int = MAX_POSES) -> Points:
    """A geometry_msgs/PolygonStamped as a closed N x 2 polyline in its header's frame (at most ``most``
    vertices, every k-th past that)."""
    points = msg.polygon.points
    step = max(1, -(-len(points) // most))
    out = np.array([(float(p.x), float(p.y)) for p in points[::step]], dtype=np.float64).reshape(-1, 2)
    return closed(out)
