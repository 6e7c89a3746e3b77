"""The top-down scene: the newest message of each topic, as geometry in one fixed frame (numpy; no screen).

:class:`Scene2D` keeps only the newest message of each topic (older ones are
dropped, never queued) and turns it into :class:`Drawing` geometry once, when
it is offered (a scan or cloud strided to at most
:data:`~rostui.models.sensors.pose2d.MAX_POINTS` points).  At
each frame it carries every drawing into the fixed frame (``--frame``, or the
first message's ``header.frame_id``) with a transform lookup and rasterises it
into one braille layer per topic, over a dotted metric grid.  A topic whose
frame has no transform to the fixed frame is left out with a note saying so.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from rostui.core.msg import foreign_version
from rostui.models.sensors.canvas2d import BrailleCanvas, Viewport, nice_step
from rostui.models.sensors.cloud2d import CloudError, cloud_points
from rostui.models.sensors.grid2d import Grid2D, GridError, grid_of
from rostui.models.sensors.pose2d import Planar, Points, Pose2D
from rostui.models.sensors.poses2d import odometry_pose, path_points, pose_array_poses, stamped_pose
from rostui.models.sensors.scan2d import scan_points

__all__ = ["TOPDOWN_TYPES", "Drawing", "Lookup", "Scene2D", "drawing_of", "same_frame_only", "GRID_SPACING_DOTS"]

#: Message types the top-down view draws.
TOPDOWN_TYPES = ("sensor_msgs/LaserScan", "nav_msgs/Odometry", "nav_msgs/Path", "geometry_msgs/PoseStamped",
                 "geometry_msgs/PoseArray", "nav_msgs/OccupancyGrid", "sensor_msgs/PointCloud2")

#: The grid's lines are at least this many dots apart (8 cells across).
GRID_SPACING_DOTS = 16

#: ``lookup(target_frame, source_frame)``: how ``source_frame`` lies in ``target_frame``'s plane, or None.
Lookup = Callable[[str, str], "Planar | Pose2D | None"]


def same_frame_only(target: str, source: str) -> Planar | Pose2D | None:
    """The lookup used without a tf buffer: identity within one frame, nothing between frames."""
    return Pose2D() if target.lstrip("/") == source.lstrip("/") else None


@dataclass
class Drawing:
    """One message as geometry in its own ``frame``: dots, a polyline, pose arrows and/or a grid."""

    frame: str
    points: Points = field(default_factory=lambda: np.zeros((0, 2)))
    polyline: Points = field(default_factory=lambda: np.zeros((0, 2)))
    poses: list[Pose2D] = field(default_factory=list)
    grid: Grid2D | None = None


def drawing_of(msg: Any) -> Drawing:
    """The geometry of a top-down message; ValueError (one line) when it cannot be read or is not one (nor rostui's
    version of its type: a bag's own version may lack the fields read here)."""
    other = foreign_version(msg)
    if other is not None:
        raise ValueError(f"{other}: not drawn")
    kind = getattr(msg, "_type", type(msg).__name__)
    frame = str(msg.header.frame_id)
    if kind == "sensor_msgs/LaserScan":
        return Drawing(frame, points=scan_points(msg))
    if kind == "sensor_msgs/PointCloud2":
        return Drawing(frame, points=cloud_points(msg))
    if kind == "nav_msgs/Odometry":
        return Drawing(frame, poses=[odometry_pose(msg)])
    if kind == "geometry_msgs/PoseStamped":
        return Drawing(frame, poses=[stamped_pose(msg)])
    if kind == "geometry_msgs/PoseArray":
        return Drawing(frame, poses=pose_array_poses(msg))
    if kind == "nav_msgs/Path":
        return Drawing(frame, polyline=path_points(msg))
    if kind == "nav_msgs/OccupancyGrid":
        return Drawing(frame, grid=grid_of(msg))
    raise ValueError(f"the top-down view does not draw {kind}")


class _Topic:
    __slots__ = ("name", "msg", "drawing", "drawn_from", "error", "received", "count")

    def __init__(self, name: str) -> None:
        self.name = name
        self.msg: Any = None
        self.drawing: Drawing | None = None
        self.drawn_from: Any = None
        self.error = ""
        self.received = 0.0
        self.count = 0


class Scene2D:
    """The topics of one top-down view and the newest message of each, drawn in ``fixed_frame``.

    ``fixed_frame`` None means: the first message's ``header.frame_id``.
    """

    def __init__(self, topics: list[str] | tuple[str, ...] = (), fixed_frame: str | None = None,
                 lookup: Lookup = same_frame_only) -> None:
        self.fixed_frame = fixed_frame.lstrip("/") if fixed_frame else None
        self.lookup = lookup
        self._topics: dict[str, _Topic] = {}
        self.generation = 0
        for name in topics:
            self.add(name)

    @property
    def topics(self) -> list[str]:
        """The topics, in the order they were added (the order their layers stack, last on top)."""
        return list(self._topics)

    def add(self, topic: str) -> None:
        """Draw ``topic`` too (a no-op when it is drawn already)."""
        self._topics.setdefault(topic, _Topic(topic))

    def offer(self, topic: str, msg: Any, received: float = 0.0) -> None:
        """``msg`` is ``topic``'s newest message (the one before it is dropped, drawn or not); its geometry is
        made now, so the cost of reading it falls on whoever offers it (a panel, within its own budget)."""
        self.add(topic)
        entry = self._topics[topic]
        entry.msg, entry.received = msg, received
        entry.count += 1
        if self.fixed_frame is None:
            frame = str(getattr(getattr(msg, "header", None), "frame_id", "")).lstrip("/")
            self.fixed_frame = frame or None
        self.generation += 1
        self.drawing(topic)

    def received(self, topic: str) -> int:
        """How many messages ``topic`` has offered so far."""
        entry = self._topics.get(topic)
        return entry.count if entry else 0

    def drawing(self, topic: str) -> Drawing | None:
        """``topic``'s newest message as geometry in its own frame (None before one came or when unreadable)."""
        entry = self._topics[topic]
        if entry.msg is not None and entry.drawn_from is not entry.msg:
            entry.drawn_from = entry.msg
            try:
                entry.drawing, entry.error = drawing_of(entry.msg), ""
            except (ValueError, AttributeError, CloudError, GridError) as exc:
                entry.drawing, entry.error = None, f"cannot draw: {exc}"
        return entry.drawing

    def note(self, topic: str) -> str:
        """Why ``topic`` is not drawn ("no message yet", "no transform from X to Y", ...), or "" when it is."""
        entry = self._topics[topic]
        drawing = self.drawing(topic)
        if entry.msg is None:
            return "no message yet"
        if drawing is None:
            return entry.error
        if self.transform(drawing) is None:
            return f"no transform from {drawing.frame or '(no frame)'} to {self.fixed_frame}"
        return ""

    def transform(self, drawing: Drawing) -> Planar | None:
        """How ``drawing``'s frame lies in the fixed frame's plane, or None when there is no transform."""
        if self.fixed_frame is None:
            return None
        frame = drawing.frame.lstrip("/")
        where = Pose2D() if frame == self.fixed_frame else self.lookup(self.fixed_frame, frame)
        return None if where is None else Planar.of(where)

    def world_points(self) -> Points:
        """Every point, polyline vertex, pose and grid corner in the fixed frame (for fitting the view)."""
        parts = []
        for topic in self._topics:
            drawing = self.drawing(topic)
            where = self.transform(drawing) if drawing is not None else None
            if drawing is None or where is None:
                continue
            parts += [where.apply(drawing.points), where.apply(drawing.polyline)]
            parts += [where.apply(np.array([[p.x, p.y] for p in drawing.poses], dtype=np.float64).reshape(-1, 2))]
            if drawing.grid is not None:
                h, w = drawing.grid.values.shape
                corners = np.array([[0, 0], [w, 0], [0, h], [w, h]], dtype=np.float64) * drawing.grid.resolution
                parts.append(where.compose(drawing.grid.origin).apply(corners))
        return np.concatenate(parts) if parts else np.zeros((0, 2))

    def grid_step(self, view: Viewport) -> float:
        """Metres between two grid lines at ``view``'s scale."""
        return nice_step(GRID_SPACING_DOTS * view.scale)

    def render(self, view: Viewport) -> BrailleCanvas:
        """Layer 0: the grid; layer i + 1: the i-th topic, in the fixed frame."""
        canvas = BrailleCanvas(view, 1 + len(self._topics))
        self._draw_grid(canvas, view)
        for layer, topic in enumerate(self._topics, start=1):
            drawing = self.drawing(topic)
            where = self.transform(drawing) if drawing is not None else None
            if drawing is None or where is None:
                continue
            if drawing.grid is not None:
                self._draw_occupancy(canvas, layer, view, drawing.grid, where)
            canvas.points(layer, where.apply(drawing.points))
            canvas.polyline(layer, where.apply(drawing.polyline))
            for pose in drawing.poses:
                canvas.arrow(layer, where.pose(pose))
        return canvas

    def _draw_grid(self, canvas: BrailleCanvas, view: Viewport) -> None:
        """Dotted lines every :meth:`grid_step` metres, through the fixed frame's origin."""
        step = self.grid_step(view)
        half_w, half_h = view.dots_wide / 2 * view.scale, view.dots_high / 2 * view.scale
        xs = np.arange(np.ceil((view.cx - half_w) / step), np.floor((view.cx + half_w) / step) + 1) * step
        ys = np.arange(np.ceil((view.cy - half_h) / step), np.floor((view.cy + half_h) / step) + 1) * step
        dots = view.to_dots(np.column_stack((xs, np.full(len(xs), view.cy))))[:, 0] if len(xs) else np.zeros(0)
        rows = np.arange(1, view.dots_high, 4)  # one dot per cell: a faint line
        for col in np.floor(dots).astype(np.int64):
            canvas.plot_dots(0, np.full(len(rows), col), rows)
        dots = view.to_dots(np.column_stack((np.full(len(ys), view.cx), ys)))[:, 1] if len(ys) else np.zeros(0)
        cols = np.arange(0, view.dots_wide, 2)
        for row in np.floor(dots).astype(np.int64):
            canvas.plot_dots(0, cols, np.full(len(cols), row))

    def _draw_occupancy(self, canvas: BrailleCanvas, layer: int, view: Viewport, grid: Grid2D, where: Planar) -> None:
        """A dot wherever the dot's centre lies over an occupied cell."""
        back = where.inverse()
        if back is None:
            return
        centres = back.apply(view.dot_centres())
        occupied = grid.occupied(centres).reshape(view.dots_high, view.dots_wide)
        rows, cols = np.nonzero(occupied)
        canvas.plot_dots(layer, cols.astype(np.int64), rows.astype(np.int64))
