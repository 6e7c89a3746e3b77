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
import numpy.typing as npt

from rostui.models.sensors.mesh_bounds import MeshError, mesh_extent
from rostui.models.sensors.pose2d import MAX_POINTS, Points, every, pose_of

IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

__all__ = ["MARKER_TYPES", "MAX_MARKERS", "MarkerShape", "MarkerStore", "Rgb", "marker_shape"]

#: The two marker message types.
MARKER_TYPES = ("visualization_msgs/Marker", "visualization_msgs/MarkerArray")

#: Most markers one topic holds; adds beyond it are counted and not kept.
MAX_MARKERS = 20_000

#: Most segments and dots all the markers of one topic hold (a marker that would pass it is refused).
MAX_ELEMENTS = 1 << 19

ARROW, CUBE, SPHERE, CYLINDER, LINE_STRIP, LINE_LIST, CUBE_LIST, SPHERE_LIST, POINTS, TEXT, MESH, TRIANGLES = range(12)

#: The types rviz colours point by point when ``colors`` has one per point.
PER_POINT_COLORS = frozenset({LINE_STRIP, LINE_LIST, CUBE_LIST, SPHERE_LIST, POINTS, TRIANGLES})
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
    """One marker in its own ``frame``: line segments and dots, each element with a colour (an index into
    ``palette``, colours grouped to :data:`COLOR_LEVELS` a channel), and an optional label."""

    frame: str
    starts: Points = field(default_factory=lambda: np.zeros((0, 2)))
    ends: Points = field(default_factory=lambda: np.zeros((0, 2)))
    dots: Points = field(default_factory=lambda: np.zeros((0, 2)))
    palette: list[Rgb] = field(default_factory=list)
    segment_colors: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    """For each segment, its colour's index in ``palette``."""
    dot_colors: IntArray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    """For each dot, its colour's index in ``palette``."""
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
        """Every finite vertex, dot and the label's place (for fitting a view around it)."""
        parts = [self.starts, self.ends, self.dots]
        if self.label:
            parts.append(np.array([self.label_at]))
        every_point = np.concatenate(parts).reshape(-1, 2)
        return every_point[np.isfinite(every_point).all(axis=1)]


#: Marker colours are grouped to this many levels a channel (each group is drawn as one colour).
COLOR_LEVELS = 8


def grouped(rgb: Rgb) -> Rgb:
    """``rgb`` moved to the middle of its group (:data:`COLOR_LEVELS` a channel)."""
    size = 256 // COLOR_LEVELS
    return tuple(min(255, (c // size) * size + size // 2) for c in rgb)  # type: ignore[return-value]


def _vertices(items: Any, indices: IntArray) -> Points:
    """The x and y of ``items[i]`` (geometry_msgs/Point) for each index."""
    return np.array([[float(items[i].x), float(items[i].y)] for i in indices], dtype=np.float64).reshape(-1, 2)


def _chosen(count: int, group: int, most: int) -> IntArray:
    """Indices of the vertices kept of ``count``, whole groups of ``group`` (a line's pair, a triangle's three)
    at a time, at most ``most`` vertices."""
    groups = count // group
    step = every(groups, max(1, most // group))
    firsts = np.arange(0, groups, step, dtype=np.int64) * group
    return (firsts[:, None] + np.arange(group, dtype=np.int64)).reshape(-1)


def _colored(marker: Any, indices: IntArray) -> tuple[list[Rgb], IntArray, BoolArray]:
    """The palette, each chosen vertex's colour index in it, and which vertices show: their own colours when the
    marker has one per point (an alpha of 0 hides a point, as in rviz), else the marker's."""
    colors = marker.colors
    if len(colors) and len(colors) == len(marker.points):
        rgba = np.array([(float(colors[i].r), float(colors[i].g), float(colors[i].b), float(colors[i].a))
                         for i in indices], dtype=np.float64).reshape(-1, 4)
    else:
        c = marker.color
        rgba = np.tile(np.array([float(c.r), float(c.g), float(c.b), float(c.a)]), (len(indices), 1))
    shown = ~(rgba[:, 3] <= 0.0)  # NaN alpha counts as shown
    levels = np.nan_to_num(np.clip(rgba[:, :3], 0.0, 1.0), nan=0.0)
    size = 256 // COLOR_LEVELS
    codes = np.minimum(np.round(levels * 255).astype(np.int64) // size, COLOR_LEVELS - 1)
    packed = (codes[:, 0] * COLOR_LEVELS + codes[:, 1]) * COLOR_LEVELS + codes[:, 2]
    unique, index = np.unique(packed, return_inverse=True)
    palette = [grouped((int(u // COLOR_LEVELS ** 2) * size, int(u // COLOR_LEVELS % COLOR_LEVELS) * size,
                        int(u % COLOR_LEVELS) * size)) for u in unique]
    return palette, index.astype(np.int64).reshape(-1), shown


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
            tail, tip = pose.apply(_vertices(marker.points, np.array([0, 1])))
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
        group = {LINE_STRIP: 1, LINE_LIST: 2, TRIANGLES: 3}[kind]
        indices = _chosen(len(marker.points), group, most)
        points = pose.apply(_vertices(marker.points, indices))
        palette, colors, shown = _colored(marker, indices)
        shape.palette = palette
        if kind == LINE_STRIP:
            keep = shown[:-1] & shown[1:]
            shape.starts, shape.ends, shape.segment_colors = points[:-1][keep], points[1:][keep], colors[:-1][keep]
        elif kind == LINE_LIST:
            keep = shown[0::2] & shown[1::2]
            shape.starts, shape.ends = points[0::2][keep], points[1::2][keep]
            shape.segment_colors = colors[0::2][keep]
        else:
            corners = points.reshape(-1, 3, 2)
            keep = np.repeat(shown.reshape(-1, 3).all(axis=1), 3)
            shape.starts = corners.reshape(-1, 2)[keep]
            shape.ends = np.roll(corners, -1, axis=1).reshape(-1, 2)[keep]
            shape.segment_colors = np.repeat(colors[0::3], 3)[keep]
    elif kind in (POINTS, CUBE_LIST, SPHERE_LIST):
        indices = _chosen(len(marker.points), 1, most)
        palette, colors, shown = _colored(marker, indices)
        shape.palette, shape.dots, shape.dot_colors = palette, pose.apply(_vertices(marker.points, indices))[shown], \
            colors[shown]
    elif kind == TEXT:
        text = _printable(str(marker.text))
        shape.label = text if len(text) <= MAX_LABEL else text[:MAX_LABEL - 1] + "…"
        shape.label_at = (pose.x, pose.y)
        shape.label_color = grouped(color)
    else:
        raise ValueError(f"marker type {kind} is not one rviz draws")
    if len(shape.starts) and not shape.palette:
        shape.palette, shape.segment_colors = [grouped(color)], np.zeros(len(shape.starts), dtype=np.int64)
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

    def __init__(self, most: int = MAX_MARKERS, most_elements: int = MAX_ELEMENTS) -> None:
        self.most = most
        self.most_elements = most_elements
        self._held: dict[tuple[str, int], _Held] = {}
        self.elements = 0
        """Segments and dots of every marker held (at most ``most_elements``)."""
        self.refused = 0
        """Markers not kept: past :data:`MAX_MARKERS` or :data:`MAX_ELEMENTS`, of an unknown type or action, or with
        no frame."""
        self.problem = ""
        """What the last refused marker was refused for (one line)."""
        self.generation = 0
        self.expired = 0
        """Markers that ended because their lifetime passed."""
        self.dropped = 0
        """Marker messages dropped before they reached the store (the screen fell behind): what they added or
        deleted is missing."""

    def __len__(self) -> int:
        return len(self._held)

    def offer(self, msg: Any, now: float, lifetimes: bool = True) -> None:
        """Apply a Marker, or each marker of a MarkerArray in order, received at wall time ``now`` (without
        ``lifetimes``, as for a recorded message shown on its own, every marker stays)."""
        markers: Iterable[Any] = msg.markers if hasattr(msg, "markers") else (msg,)
        for marker in markers:
            self._apply(marker, now if lifetimes else None)
        self.generation += 1

    def _drop(self, key: tuple[str, int]) -> None:
        held = self._held.pop(key, None)
        if held is not None:
            self.elements -= held.shape.size

    def _refuse(self, why: str) -> None:
        self.refused += 1
        self.problem = why

    def _apply(self, marker: Any, now: float | None) -> None:
        action = int(marker.action)
        key = (str(marker.ns), int(marker.id))
        if action == DELETEALL:
            self._held.clear()
            self.elements = 0
        elif action == DELETE:
            self._drop(key)
        elif action in (ADD, DEPRECATED_MODIFY):
            if not str(marker.header.frame_id):
                self._refuse(f"marker {key[0]}/{key[1]} has no frame_id")
                return
            per_point = int(marker.type) in PER_POINT_COLORS and 0 < len(marker.colors) == len(marker.points)
            if not _visible(marker.color) and not per_point:
                self._drop(key)
                return
            if key not in self._held and len(self._held) >= self.most:
                self._refuse(f"more than {self.most} markers")
                return
            try:
                with np.errstate(all="ignore"):  # NaN and inf in a marker are left out when drawn, not warned of
                    shape = marker_shape(marker)
            except (ValueError, AttributeError, TypeError, OverflowError) as exc:
                self._refuse(str(exc))
                return
            before = self._held[key].shape.size if key in self._held else 0
            if self.elements - before + shape.size > self.most_elements:
                self._refuse(f"more than {self.most_elements} points and lines in all markers")
                return
            lifetime = float(marker.lifetime.secs) + float(marker.lifetime.nsecs) * 1e-9
            expires = now + lifetime if lifetime > 0 and now is not None else None
            self._held[key] = _Held(shape, expires, bool(marker.frame_locked))
            self.elements += shape.size - before
        else:
            self._refuse(f"marker action {action} is not one rviz knows")

    def expire(self, now: float) -> bool:
        """Drop the markers whose lifetime has passed at ``now``; True when any went."""
        gone = [key for key, held in self._held.items() if held.expires is not None and held.expires <= now]
        for key in gone:
            self._drop(key)
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
