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

import time

import numpy as np

from rostui.core.msg import foreign_version
from rostui.models.sensors.canvas2d import BrailleCanvas, Viewport, nice_step
from rostui.models.sensors.cloud2d import CloudError, cloud_points
from rostui.models.sensors.footprint import polygon_points
from rostui.models.sensors.grid2d import Grid2D, GridError, grid_of
from rostui.models.sensors.markers2d import MARKER_TYPES, MarkerStore, Rgb
from rostui.models.sensors.pose2d import Planar, Points, Pose2D
from rostui.models.sensors.poses2d import odometry_pose, path_points, pose_array_poses, stamped_pose
from rostui.models.sensors.scan2d import scan_points

__all__ = ["TOPDOWN_TYPES", "Drawing", "Label", "Lookup", "Scene2D", "drawing_of", "same_frame_only",
           "GRID_SPACING_DOTS", "MAX_COLOR_LAYERS"]

#: Message types the top-down view draws.
TOPDOWN_TYPES = ("sensor_msgs/LaserScan", "nav_msgs/Odometry", "nav_msgs/Path", "geometry_msgs/PoseStamped",
                 "geometry_msgs/PoseArray", "nav_msgs/OccupancyGrid", "sensor_msgs/PointCloud2",
                 "geometry_msgs/PolygonStamped") + MARKER_TYPES

#: Most colours markers are drawn in at once (each is a layer); markers of further colours take their topic's.
MAX_COLOR_LAYERS = 24


#: The name :attr:`Scene2D.layer_colors` gives the cursor's layer, and its colour.
CURSOR = "(cursor)"
CURSOR_COLOR: Rgb = (255, 255, 255)

#: The cursor's arrow, in dots.
CURSOR_LENGTH = 12.0

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
    if kind == "geometry_msgs/PolygonStamped":
        return Drawing(frame, polyline=polygon_points(msg))
    raise ValueError(f"the top-down view does not draw {kind}")


@dataclass(frozen=True)
class Label:
    """Text drawn over the canvas from cell (``col``, ``row``) in ``layer``'s colour."""

    col: int
    row: int
    text: str
    layer: int


class _Topic:
    __slots__ = ("name", "msg", "drawing", "drawn_from", "error", "received", "count", "markers")

    def __init__(self, name: str) -> None:
        self.name = name
        self.markers: MarkerStore | None = None
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
        self.layer_colors: list[tuple[str, Rgb]] = []
        """After :meth:`render`: the topic and colour of each layer past the topics' own (markers' colours)."""
        self.labels: list[Label] = []
        """After :meth:`render`: the text markers, placed on the canvas."""
        self.cursor: Pose2D | None = None
        """A pose in the fixed frame drawn over everything (the view's goal and pose-estimate cursor)."""
        for name in topics:
            self.add(name)

    @property
    def topics(self) -> list[str]:
        """The topics, in the order they were added (the order their layers stack, last on top)."""
        return list(self._topics)

    def add(self, topic: str) -> None:
        """Draw ``topic`` too (a no-op when it is drawn already)."""
        self._topics.setdefault(topic, _Topic(topic))

    def offer(self, topic: str, msg: Any, received: float = 0.0, alone: bool = False) -> None:
        """``msg`` is ``topic``'s newest message (the one before it is dropped, drawn or not); its geometry is
        made now, so the cost of reading it falls on whoever offers it (a panel, within its own budget).

        A marker message adds to and deletes from the markers the topic holds, unless ``alone`` (a recorded
        message stepped to): then it shows only its own."""
        self.add(topic)
        entry = self._topics[topic]
        entry.msg, entry.received = msg, received
        entry.count += 1
        if getattr(msg, "_type", "") in MARKER_TYPES:
            if entry.markers is None or alone:
                entry.markers = MarkerStore()
            entry.markers.offer(msg, received or time.time(), lifetimes=not alone)
            header = next((m.header for m in (msg.markers if hasattr(msg, "markers") else (msg,))
                           if str(m.header.frame_id)), None)
        else:
            header = getattr(msg, "header", None)
        if self.fixed_frame is None:
            frame = str(getattr(header, "frame_id", "")).lstrip("/")
            self.fixed_frame = frame or None
        self.generation += 1
        if entry.markers is None:
            self.drawing(topic)

    def set_drawing(self, name: str, drawing: Drawing) -> None:
        """Draw ``drawing`` as the layer ``name`` (not a topic: the robot's footprint), in its frame through tf."""
        self.add(name)
        entry = self._topics[name]
        entry.msg = entry.drawn_from = drawing
        entry.drawing, entry.error = drawing, ""
        self.generation += 1

    def markers(self, topic: str) -> MarkerStore | None:
        """The markers ``topic`` holds (None for a topic of another type)."""
        entry = self._topics.get(topic)
        return entry.markers if entry is not None else None

    def expire(self, now: float) -> bool:
        """Drop markers whose lifetime ended by ``now``; True when the picture changed."""
        changed = False
        for entry in self._topics.values():
            if entry.markers is not None and entry.markers.expire(now):
                changed = True
        if changed:
            self.generation += 1
        return changed

    def set_fixed_frame(self, frame: str | None) -> None:
        """Draw in ``frame`` from now on (markers that are not frame-locked are placed again)."""
        self.fixed_frame = frame.lstrip("/") if frame else None
        for entry in self._topics.values():
            if entry.markers is not None:
                entry.markers.forget_placements()
        self.generation += 1

    def received(self, topic: str) -> int:
        """How many messages ``topic`` has offered so far."""
        entry = self._topics.get(topic)
        return entry.count if entry else 0

    def drawing(self, topic: str) -> Drawing | None:
        """``topic``'s newest message as geometry in its own frame (None before one came, when unreadable, and
        for markers: see :meth:`markers`)."""
        entry = self._topics[topic]
        if entry.markers is not None:
            return None
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
        if entry.markers is not None:
            return self._marker_note(entry.markers)
        drawing = self.drawing(topic)
        if entry.msg is None:
            return "no message yet"
        if drawing is None:
            return entry.error
        if self.transform(drawing) is None:
            return f"no transform from {drawing.frame or '(no frame)'} to {self.fixed_frame}"
        return ""

    def _marker_note(self, store: MarkerStore) -> str:
        parts = [f"{len(store)} marker{'s' if len(store) != 1 else ''}"]
        frames = {shape.frame for _, shape, _ in store.held()}
        unplaced = sorted(frame for frame in frames if self._frame_where(frame) is None)
        if unplaced:
            parts.append(f"no transform from {', '.join(unplaced[:3])} to {self.fixed_frame}")
        if store.refused:
            parts.append(f"{store.refused} not drawn: {store.problem}")
        if store.dropped:
            parts.append(f"{store.dropped} messages dropped: the screen fell behind")
        notes = sorted({shape.note for _, shape, _ in store.held() if shape.note})
        if notes:
            parts.append(notes[0] if len(notes) == 1 else f"{notes[0]} (and {len(notes) - 1} more)")
        return "; ".join(parts)

    def _frame_where(self, frame: str) -> Planar | None:
        if self.fixed_frame is None:
            return None
        frame = frame.lstrip("/")
        where = Pose2D() if frame == self.fixed_frame else self.lookup(self.fixed_frame, frame)
        return None if where is None else Planar.of(where)

    def _marker_where(self, store: MarkerStore, key: tuple[str, int], frame: str, locked: bool) -> Planar | None:
        """Where a marker lies: frame-locked ones follow tf at every frame; others stay where they were first put."""
        if not locked:
            placed = store.placement(key)
            if placed is not None:
                return placed
        where = self._frame_where(frame)
        if not locked and where is not None:
            store.place(key, where)
        return where

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
        for topic, entry in self._topics.items():
            if entry.markers is not None:
                for key, shape, locked in entry.markers.held():
                    where = self._marker_where(entry.markers, key, shape.frame, locked)
                    if where is not None:
                        parts.append(where.apply(shape.points()))
                continue
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
        every_point = np.concatenate(parts) if parts else np.zeros((0, 2))
        return every_point[np.isfinite(every_point).all(axis=1)]

    def grid_step(self, view: Viewport) -> float:
        """Metres between two grid lines at ``view``'s scale."""
        return nice_step(GRID_SPACING_DOTS * view.scale)

    def render(self, view: Viewport) -> BrailleCanvas:
        """Layer 0: the grid; layer i + 1: the i-th topic, in the fixed frame; past those, one layer per colour
        markers are drawn in (:attr:`layer_colors`); text markers in :attr:`labels`."""
        colors = self._marker_colors()
        canvas = BrailleCanvas(view, 1 + len(self._topics) + len(colors) + (self.cursor is not None))
        self.layer_colors = list(colors)
        self.labels = []
        if self.cursor is not None:
            self.layer_colors.append((CURSOR, CURSOR_COLOR))
            self._draw_cursor(canvas, view, len(canvas.bits) - 1, self.cursor)
        self._draw_grid(canvas, view)
        for layer, (topic, entry) in enumerate(self._topics.items(), start=1):
            if entry.markers is not None:
                with np.errstate(all="ignore"):  # a marker's NaN or inf points are clipped away, not warned of
                    self._draw_markers(canvas, view, layer, topic, entry.markers, colors)
                continue
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

    @staticmethod
    def _draw_cursor(canvas: BrailleCanvas, view: Viewport, layer: int, cursor: Pose2D) -> None:
        """An arrow from the cursor's place along its heading, and a small cross on the place."""
        canvas.arrow(layer, cursor, CURSOR_LENGTH)
        centre = view.to_dots(np.array([[cursor.x, cursor.y]]))[0]
        offsets = np.array([[-2.0, 0.0], [2.0, 0.0], [0.0, -2.0], [0.0, 2.0]])
        canvas.segments(layer, centre + offsets[[0, 2]], centre + offsets[[1, 3]], in_dots=True)

    def _marker_colors(self) -> dict[tuple[str, Rgb], int]:
        """A layer (counted past the topics') for each grouped colour markers use, at most
        :data:`MAX_COLOR_LAYERS`."""
        layers: dict[tuple[str, Rgb], int] = {}
        first = 1 + len(self._topics)
        for topic, entry in self._topics.items():
            if entry.markers is None:
                continue
            for _, shape, _ in entry.markers.held():
                for rgb in (*shape.palette, *((shape.label_color,) if shape.label else ())):
                    key = (topic, rgb)
                    if key not in layers and len(layers) < MAX_COLOR_LAYERS:
                        layers[key] = first + len(layers)
        return layers

    def _draw_markers(self, canvas: BrailleCanvas, view: Viewport, own: int, topic: str, store: MarkerStore,
                      colors: dict[tuple[str, Rgb], int]) -> None:
        """Each marker in the layer of its colour (or its topic's), where tf puts its frame."""
        def layer_of(rgb: Rgb) -> int:
            return colors.get((topic, rgb), own)

        for key, shape, locked in store.held():
            where = self._marker_where(store, key, shape.frame, locked)
            if where is None:
                continue
            layers = np.array([layer_of(rgb) for rgb in shape.palette], dtype=np.int64)
            if len(shape.starts):
                starts, ends = where.apply(shape.starts), where.apply(shape.ends)
                segment_layers = layers[shape.segment_colors]
                for layer in np.unique(segment_layers):
                    mine = segment_layers == layer
                    canvas.segments(int(layer), starts[mine], ends[mine])
            if len(shape.dots):
                dots = where.apply(shape.dots)
                keep = np.isfinite(dots).all(axis=1)
                dot_layers = layers[shape.dot_colors]
                for layer in np.unique(dot_layers[keep]):
                    canvas.points(int(layer), dots[keep & (dot_layers == layer)])
            if shape.label:
                cell = view.cell_of(*where.apply(np.array([shape.label_at]))[0])
                if cell is not None:
                    col = max(0, min(cell[0] - len(shape.label) // 2, view.cols - len(shape.label)))
                    self.labels.append(Label(col, cell[1], shape.label[:view.cols], layer_of(shape.label_color)))

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
