"""visualization_msgs/Marker and MarkerArray from above: the markers a topic holds, as coloured ground-plane shapes.

A marker topic is not "the newest message": each message adds, replaces or deletes
markers by namespace and id, as rviz's Marker display keeps them.
:class:`MarkerStore` holds them (ADD/MODIFY replace, DELETE removes one,
DELETEALL empties the store, a non-zero ``lifetime`` ends a marker that long
after it came); :func:`marker_shape` turns one marker into lines, dots and a
label in its own frame, each type projected onto the ground plane:

- ARROW: a shaft from its pose along x, ``scale.x`` long (or from its first
  point to its second) with a two-stroke head;
- CUBE, SPHERE, CYLINDER: the outline of their footprint (``scale.x`` by
  ``scale.y``); MESH_RESOURCE: the outline of its mesh's extent (STL or COLLADA,
  read once; a box of its scale when the file cannot be read, and the legend
  says why);
- LINE_STRIP, LINE_LIST, TRIANGLE_LIST: their lines (triangles as outlines);
- POINTS, CUBE_LIST, SPHERE_LIST: a dot each;
- TEXT_VIEW_FACING: its text, at its position.

A marker with ``colors`` gives each point its own colour, as rviz does; an
alpha of 0 hides a marker in rviz, so it is not drawn here either.
"""

from __future__ import annotations

import math
import unicodedata
from dataclasses import dataclass, field
from typing import Any, Iterable

import numpy as np

from rostui.models.sensors.mesh_bounds import MeshError, mesh_extent
from rostui.models.sensors.pose2d import MAX_POINTS, Points, every, pose_of

__all__ = ["MARKER_TYPES", "MAX_MARKERS", "MarkerShape", "MarkerStore", "Rgb", "marker_shape"]

#: The two marker message types.
MARKER_TYPES = ("visualization_msgs/Marker", "visualization_msgs/MarkerArray")

#: Most markers one topic holds; adds beyond it are counted and not kept.
MAX_MARKERS = 20_000

ARROW, CUBE, SPHERE, CYLINDER, LINE_STRIP, LINE_LIST, CUBE_LIST, SPHERE_LIST, POINTS, TEXT, MESH, TRIANGLES = range(12)
ADD, DEPRECATED_MODIFY, DELETE, DELETEALL = 0, 1, 2, 3

#: Vertices of a sphere's or cylinder's outline.
ELLIPSE_VERTICES = 24

#: Longest text label drawn (characters).
MAX_LABEL = 60

Rgb = tuple[int, int, int]
"""A colour, 0-255 per channel."""


def _rgb(color: Any) -> Rgb:
    """A std_msgs/ColorRGBA (0-1 floats) as 0-255 integers, out-of-range values clamped."""
    def channel(value: Any) -> int:
        v = float(value)
        return 0 if not math.isfinite(v) else max(0, min(255, round(v * 255)))
    return channel(color.r), channel(color.g), channel(color.b)


def _printable(text: str) -> str:
    """``text`` on one line, one cell per character: control and combining characters dropped, wide ones as
    ``?``."""
    kept = "".join("?" if unicodedata.east_asian_width(c) in "WF" else c
                   for c in " ".join(text.split()) if unicodedata.category(c)[0] not in "CM")
    return kept


def _visible(color: Any) -> bool:
    alpha = float(color.a)
    return not math.isfinite(alpha) or alpha > 0.0


@dataclass
class MarkerShape:
    """One marker in its own ``frame``: line segments and dots, each with a colour, and an optional label."""

    frame: str
    starts: Points = field(default_factory=lambda: np.zeros((0, 2)))
    ends: Points = field(default_factory=lambda: np.zeros((0, 2)))
    segment_colors: list[Rgb] = field(default_factory=list)
    dots: Points = field(default_factory=lambda: np.zeros((0, 2)))
    dot_colors: list[Rgb] = field(default_factory=list)
    label: str = ""
    label_at: tuple[float, float] = (0.0, 0.0)
    label_color: Rgb = (255, 255, 255)
    note: str = ""
    """What is not as rviz draws it (a mesh whose file was not read), for the legend."""

    @property
    def size(self) -> int:
        """Segments and dots it draws (what the store's budget counts)."""
        return len(self.starts) + len(self.dots)

    def points(self) -> Points:
        """Every vertex, dot and the label's place (for fitting a view around it)."""
        parts = [self.starts, self.ends, self.dots]
        if self.label:
            parts.append(np.array([self.label_at]))
        return np.concatenate(parts).reshape(-1, 2)


def _points(items: Any, most: int) -> Points:
    """``geometry_msgs/Point[]`` (or a numpy view) as N x 2, strided to at most ``most``."""
    n = len(items)
    step = every(n, most)
    out = np.array([[float(p.x), float(p.y)] for p in items[::step]], dtype=np.float64)
    return out.reshape(-1, 2)


def _colors(marker: Any, count: int, step: int = 1) -> list[Rgb]:
    """The colour of each of ``count`` points: its own from ``colors`` when there is one per point, else the
    marker's."""
    colors = marker.colors
    if len(colors) and len(colors) >= count * step - (step - 1):
        return [_rgb(c) for c in list(colors)[::step][:count]]
    return [_rgb(marker.color)] * count


def _outline(vertices: Points) -> tuple[Points, Points]:
    """Segments joining each vertex to the next and the last to the first."""
    return vertices, np.roll(vertices, -1, axis=0)


def _ellipse(rx: float, ry: float) -> Points:
    angles = np.linspace(0.0, 2 * math.pi, ELLIPSE_VERTICES, endpoint=False)
    return np.column_stack((rx * np.cos(angles), ry * np.sin(angles)))


def _box(sx: float, sy: float) -> Points:
    hx, hy = sx / 2, sy / 2
    return np.array([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]])


def marker_shape(marker: Any, most: int = MAX_POINTS) -> MarkerShape:
    """``marker`` (an ADD) as lines, dots and a label in its header's frame; ValueError (one line) for a type
    rviz does not know."""
    kind = int(marker.type)
    pose = pose_of(marker.pose)
    frame = str(marker.header.frame_id)
    shape = MarkerShape(frame)
    color = _rgb(marker.color)
    sx, sy = float(marker.scale.x), float(marker.scale.y)
    if kind == ARROW:
        if len(marker.points) >= 2:
            tail, tip = _points(marker.points[:2], 2)
            tail, tip = pose.apply(np.array([tail, tip]))
        else:
            tail = np.array([pose.x, pose.y])
            tip = tail + sx * np.array([math.cos(pose.yaw), math.sin(pose.yaw)])
        heading = math.atan2(tip[1] - tail[1], tip[0] - tail[0])
        barb = 0.3 * float(np.hypot(*(tip - tail)))
        barbs = [tip + barb * np.array([math.cos(heading + a), math.sin(heading + a)])
                 for a in (math.radians(150), math.radians(-150))]
        shape.starts, shape.ends = np.array([tail, tip, tip]), np.array([tip, *barbs])
    elif kind == CUBE:
        shape.starts, shape.ends = _outline(pose.apply(_box(sx, sy)))
    elif kind == MESH:
        try:
            x0, y0, x1, y1 = mesh_extent(str(marker.mesh_resource))
            corners = np.array([[x0 * sx, y0 * sy], [x1 * sx, y0 * sy], [x1 * sx, y1 * sy], [x0 * sx, y1 * sy]])
        except MeshError as exc:
            corners = _box(sx, sy)
            shape.note = f"a mesh drawn as a box of its scale: {exc}"
        shape.starts, shape.ends = _outline(pose.apply(corners))
    elif kind in (SPHERE, CYLINDER):
        shape.starts, shape.ends = _outline(pose.apply(_ellipse(sx / 2, sy / 2)))
    elif kind in (LINE_STRIP, LINE_LIST, TRIANGLES):
        points = pose.apply(_points(marker.points, most))
        colors = _colors(marker, len(points), every(len(marker.points), most))
        if kind == LINE_STRIP:
            shape.starts, shape.ends, shape.segment_colors = points[:-1], points[1:], colors[:-1]
        elif kind == LINE_LIST:
            pairs = len(points) // 2
            shape.starts, shape.ends = points[0:2 * pairs:2], points[1:2 * pairs:2]
            shape.segment_colors = colors[0:2 * pairs:2]
        else:
            count = len(points) // 3
            corners = points[:3 * count].reshape(count, 3, 2)
            shape.starts = corners.reshape(-1, 2)
            shape.ends = np.roll(corners, -1, axis=1).reshape(-1, 2)
            shape.segment_colors = [c for c in colors[0:3 * count:3] for _ in range(3)]
    elif kind in (POINTS, CUBE_LIST, SPHERE_LIST):
        shape.dots = pose.apply(_points(marker.points, most))
        shape.dot_colors = _colors(marker, len(shape.dots), every(len(marker.points), most))
    elif kind == TEXT:
        text = _printable(str(marker.text))
        shape.label = text if len(text) <= MAX_LABEL else text[:MAX_LABEL - 1] + "…"
        shape.label_at = (pose.x, pose.y)
        shape.label_color = color
    else:
        raise ValueError(f"marker type {kind} is not one rviz draws")
    if len(shape.starts) and not shape.segment_colors:
        shape.segment_colors = [color] * len(shape.starts)
    return shape


@dataclass
class _Held:
    shape: MarkerShape
    expires: float | None
    frame_locked: bool
    placed: Any = None
    """Where a marker that is not frame-locked was placed in the fixed frame (kept until the fixed frame changes)."""


class MarkerStore:
    """The markers of one topic, by (namespace, id), as rviz's Marker display keeps them."""

    def __init__(self, most: int = MAX_MARKERS) -> None:
        self.most = most
        self._held: dict[tuple[str, int], _Held] = {}
        self.refused = 0
        """Markers not kept: over :data:`MAX_MARKERS`, of an unknown type or action, or with no frame."""
        self.problem = ""
        """What the last refused marker was refused for (one line)."""
        self.generation = 0
        self.expired = 0
        """Markers that ended because their lifetime passed."""

    def __len__(self) -> int:
        return len(self._held)

    def offer(self, msg: Any, now: float, lifetimes: bool = True) -> None:
        """Apply a Marker, or each marker of a MarkerArray in order, received at wall time ``now`` (without
        ``lifetimes``, as for a recorded message shown on its own, every marker stays)."""
        markers: Iterable[Any] = msg.markers if hasattr(msg, "markers") else (msg,)
        for marker in markers:
            self._apply(marker, now if lifetimes else None)
        self.generation += 1

    def _refuse(self, why: str) -> None:
        self.refused += 1
        self.problem = why

    def _apply(self, marker: Any, now: float | None) -> None:
        action = int(marker.action)
        key = (str(marker.ns), int(marker.id))
        if action == DELETEALL:
            self._held.clear()
        elif action == DELETE:
            self._held.pop(key, None)
        elif action in (ADD, DEPRECATED_MODIFY):
            if not str(marker.header.frame_id):
                self._refuse(f"marker {key[0]}/{key[1]} has no frame_id")
                return
            if not _visible(marker.color) and not len(marker.colors):
                self._held.pop(key, None)
                return
            if key not in self._held and len(self._held) >= self.most:
                self._refuse(f"more than {self.most} markers")
                return
            try:
                shape = marker_shape(marker)
            except (ValueError, AttributeError, TypeError) as exc:
                self._refuse(str(exc))
                return
            lifetime = float(marker.lifetime.secs) + float(marker.lifetime.nsecs) * 1e-9
            expires = now + lifetime if lifetime > 0 and now is not None else None
            self._held[key] = _Held(shape, expires, bool(marker.frame_locked))
        else:
            self._refuse(f"marker action {action} is not one rviz knows")

    def expire(self, now: float) -> bool:
        """Drop the markers whose lifetime has passed at ``now``; True when any went."""
        gone = [key for key, held in self._held.items() if held.expires is not None and held.expires <= now]
        for key in gone:
            del self._held[key]
        self.expired += len(gone)
        if gone:
            self.generation += 1
        return bool(gone)

    def next_expiry(self) -> float | None:
        """When the next marker's lifetime ends (wall seconds), or None."""
        times = [held.expires for held in self._held.values() if held.expires is not None]
        return min(times) if times else None

    def held(self) -> list[tuple[tuple[str, int], MarkerShape, bool]]:
        """Each marker's (namespace, id), shape and whether it is frame-locked, in namespace and id order."""
        return [(key, self._held[key].shape, self._held[key].frame_locked) for key in sorted(self._held)]

    def placement(self, key: tuple[str, int]) -> Any:
        """Where a non-frame-locked marker was first placed in the fixed frame (None before it was)."""
        held = self._held.get(key)
        return held.placed if held is not None else None

    def place(self, key: tuple[str, int], where: Any) -> None:
        """Remember where a non-frame-locked marker lies in the fixed frame."""
        held = self._held.get(key)
        if held is not None:
            held.placed = where

    def forget_placements(self) -> None:
        """The fixed frame changed: every marker is placed again."""
        for held in self._held.values():
            held.placed = None
