"""A metric viewport over the ground plane and a braille raster of layers drawn in it (numpy; no screen).

Each terminal cell holds a braille character: 2 x 4 dots, each about square
on screen, so one dot is ``scale`` metres wide and tall.  Dots count from the
top-left of the canvas; +y in the world points up the screen.  Every layer
(one per topic, one for the grid) keeps its own dot bits; a cell shows the
union of all layers' dots in the colour of the topmost layer that has a dot there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

from rostui.models.sensors.pose2d import Points, Pose2D

__all__ = ["BRAILLE_BASE", "BrailleCanvas", "Viewport", "nice_step"]

#: The empty braille pattern; a cell's character is this plus its dot bits.
BRAILLE_BASE = 0x2800

#: Bit of each dot of a braille cell, indexed [row 0..3, column 0..1].
DOT_BITS = np.array([[0x01, 0x08], [0x02, 0x10], [0x04, 0x20], [0x40, 0x80]], dtype=np.uint8)

IntArray = npt.NDArray[np.int64]


def nice_step(minimum: float) -> float:
    """The smallest 1, 2 or 5 times a power of ten that is at least ``minimum`` (> 0)."""
    power = 10.0 ** math.floor(math.log10(minimum))
    for factor in (1.0, 2.0, 5.0, 10.0):
        if factor * power >= minimum * (1 - 1e-9):
            return factor * power
    return 10.0 * power


@dataclass(frozen=True)
class Viewport:
    """``cols`` x ``rows`` cells of braille showing the plane around ``(cx, cy)`` at ``scale`` metres per dot."""

    cols: int
    rows: int
    cx: float = 0.0
    cy: float = 0.0
    scale: float = 0.05

    @property
    def dots_wide(self) -> int:
        """Dots across the canvas."""
        return 2 * self.cols

    @property
    def dots_high(self) -> int:
        """Dots down the canvas."""
        return 4 * self.rows

    def to_dots(self, points: Points) -> Points:
        """World points (N x 2, metres) as fractional dot coordinates (column, row)."""
        col = (points[:, 0] - self.cx) / self.scale + self.dots_wide / 2
        row = self.dots_high / 2 - (points[:, 1] - self.cy) / self.scale
        return np.column_stack((col, row))

    def dot_centres(self) -> Points:
        """The world point at the centre of every dot, row by row (dots_high * dots_wide x 2)."""
        cols = (np.arange(self.dots_wide) + 0.5 - self.dots_wide / 2) * self.scale + self.cx
        rows = (self.dots_high / 2 - np.arange(self.dots_high) - 0.5) * self.scale + self.cy
        xs, ys = np.meshgrid(cols, rows)
        return np.column_stack((xs.ravel(), ys.ravel()))

    def cell_centre(self, col: int, row: int) -> tuple[float, float]:
        """The world point at the centre of cell (``col``, ``row``)."""
        x = (2 * col + 1 - self.dots_wide / 2) * self.scale + self.cx
        y = (self.dots_high / 2 - 4 * row - 2) * self.scale + self.cy
        return float(x), float(y)

    def zoomed(self, factor: float) -> "Viewport":
        """The same centre, ``factor`` times closer (2: things look twice as big)."""
        return replace(self, scale=self.scale / factor)

    def panned(self, cells_right: float, cells_up: float) -> "Viewport":
        """Moved by whole cells: ``cells_right`` columns and ``cells_up`` rows (a row is 4 dots, a column 2)."""
        return replace(self, cx=self.cx + 2 * cells_right * self.scale, cy=self.cy + 4 * cells_up * self.scale)

    def resized(self, cols: int, rows: int) -> "Viewport":
        """The same centre and scale over ``cols`` x ``rows`` cells."""
        return replace(self, cols=cols, rows=rows)

    def fitting(self, points: Points, margin: float = 0.1) -> "Viewport":
        """Centred on ``points``' bounding box, scaled so all of it shows with ``margin`` to spare."""
        points = points[np.isfinite(points).all(axis=1)] if len(points) else points
        if len(points) == 0 or self.cols <= 0 or self.rows <= 0:
            return self
        lo, hi = points.min(axis=0), points.max(axis=0)
        span_x, span_y = max(hi[0] - lo[0], 1e-3), max(hi[1] - lo[1], 1e-3)
        scale = max(span_x / self.dots_wide, span_y / self.dots_high) * (1 + 2 * margin)
        centre = (lo + hi) / 2
        return replace(self, cx=float(centre[0]), cy=float(centre[1]), scale=float(scale))

    def cell_of(self, x: float, y: float) -> tuple[int, int] | None:
        """The (column, row) of the cell showing world point ``(x, y)``; None when it is off the canvas (or not a
        finite point)."""
        col, row = self.to_dots(np.array([[x, y]]))[0]
        if not (math.isfinite(col) and math.isfinite(row)):
            return None
        c, r = math.floor(col), math.floor(row)
        if 0 <= c < self.dots_wide and 0 <= r < self.dots_high:
            return c // 2, r // 4
        return None


class BrailleCanvas:
    """Layers of braille dots over a :class:`Viewport`; draw world points, segments, arrows into a layer."""

    def __init__(self, view: Viewport, layers: int) -> None:
        self.view = view
        self.bits = np.zeros((layers, max(view.rows, 0), max(view.cols, 0)), dtype=np.uint8)

    def plot_dots(self, layer: int, cols: IntArray, rows: IntArray) -> None:
        """Set dots (integer column, row arrays) of ``layer``; those off the canvas are ignored."""
        inside = (cols >= 0) & (cols < self.view.dots_wide) & (rows >= 0) & (rows < self.view.dots_high)
        cols, rows = cols[inside], rows[inside]
        np.bitwise_or.at(self.bits[layer], (rows // 4, cols // 2), DOT_BITS[rows % 4, cols % 2])

    def points(self, layer: int, points: Points) -> None:
        """One dot for each world point."""
        if len(points):
            dots = np.floor(self.view.to_dots(points)).astype(np.int64)
            self.plot_dots(layer, dots[:, 0], dots[:, 1])

    def segments(self, layer: int, starts: Points, ends: Points, in_dots: bool = False) -> None:
        """A line of dots from each start to its end (world points, or dot coordinates with ``in_dots``)."""
        if len(starts) == 0:
            return
        a = starts if in_dots else self.view.to_dots(starts)
        b = ends if in_dots else self.view.to_dots(ends)
        a, b = self._clip(a, b)
        if len(a) == 0:
            return
        counts = (np.ceil(np.abs(b - a).max(axis=1)).astype(np.int64) + 1)
        index = np.repeat(np.arange(len(a)), counts)
        first = np.cumsum(counts) - counts
        t = (np.arange(counts.sum()) - first[index]) / np.maximum(counts[index] - 1, 1)
        pts = a[index] + (b - a)[index] * t[:, None]
        dots = np.floor(pts).astype(np.int64)
        self.plot_dots(layer, dots[:, 0], dots[:, 1])

    def polyline(self, layer: int, points: Points) -> None:
        """Segments joining consecutive world points."""
        if len(points) >= 2:
            self.segments(layer, points[:-1], points[1:])
        else:
            self.points(layer, points)

    def arrow(self, layer: int, pose: Pose2D, length: float = 10.0) -> None:
        """An arrow ``length`` dots long from ``pose``'s position along its heading, with a two-stroke head."""
        tail = self.view.to_dots(np.array([[pose.x, pose.y]]))[0]
        heading = -pose.yaw  # dot rows grow downwards
        tip = tail + length * np.array([math.cos(heading), math.sin(heading)])
        barbs = [tip + 0.4 * length * np.array([math.cos(heading + a), math.sin(heading + a)])
                 for a in (math.radians(150), math.radians(-150))]
        starts = np.array([tail, tip, tip])
        self.segments(layer, starts, np.array([tip, *barbs]), in_dots=True)

    def _clip(self, a: Points, b: Points) -> tuple[Points, Points]:
        """Liang-Barsky: the parts of segments a->b inside the canvas (those wholly outside dropped)."""
        width, height = self.view.dots_wide - 1e-6, self.view.dots_high - 1e-6
        d = b - a
        t0, t1 = np.zeros(len(a)), np.ones(len(a))
        keep = np.isfinite(a).all(axis=1) & np.isfinite(b).all(axis=1)
        for p, q in ((-d[:, 0], a[:, 0]), (d[:, 0], width - a[:, 0]), (-d[:, 1], a[:, 1]), (d[:, 1], height - a[:, 1])):
            parallel = p == 0
            keep &= ~(parallel & (q < 0))
            with np.errstate(divide="ignore", invalid="ignore"):
                r = np.where(parallel, 0.0, q / np.where(parallel, 1.0, p))
            t0 = np.where(~parallel & (p < 0), np.maximum(t0, r), t0)
            t1 = np.where(~parallel & (p > 0), np.minimum(t1, r), t1)
        keep &= t0 <= t1
        a, d, t0, t1 = a[keep], d[keep], t0[keep], t1[keep]
        return a + d * t0[:, None], a + d * t1[:, None]

    def compose(self, background: int = 1) -> tuple[npt.NDArray[np.uint8], npt.NDArray[np.int64]]:
        """Each cell's dot bits and the topmost layer with a dot there (-1: empty).

        The first ``background`` layers (the grid) show only in cells where no
        other layer has a dot, so a topic's cells carry its dots alone.
        """
        has = self.bits != 0
        top = np.where(has.any(axis=0), len(self.bits) - 1 - np.argmax(has[::-1], axis=0), -1).astype(np.int64)
        front = self.bits[background:]
        if len(front):
            union = np.bitwise_or.reduce(front, axis=0)
        else:
            union = np.zeros(self.bits.shape[1:], np.uint8)
        back = self.bits[:background]
        if len(back):
            union = np.asarray(np.where(union != 0, union, np.bitwise_or.reduce(back, axis=0)), dtype=np.uint8)
        return union, top
