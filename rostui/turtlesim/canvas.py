"""The turtlesim path image: the 500x500 RGB picture the pens draw on.

Image coordinates are pixels, x to the right and y *down*, as in ROS
turtlesim's Qt image.  A pixel ``(i, j)`` stands for the point ``(i, j)``:
a pen stroke covers every pixel whose point lies inside the stroke's
rectangle (the segment widened by the pen width, with square ends), and the
colour sensor reads the pixel nearest to the turtle.

Every change bumps :attr:`PathImage.generation` and records the dirty
rectangle, so a renderer can redraw only what changed
(:meth:`PathImage.changes_since`).
"""

from __future__ import annotations

import collections
import math
from typing import Iterator

PIXELS = 500
"""Width and height of the path image in pixels."""

RGB = tuple[int, int, int]
Rect = tuple[int, int, int, int]

_HISTORY = 4096


class PathImage:
    """A square RGB image with pen strokes, a change counter and dirty rectangles.

    ``rows`` is a list of ``PIXELS`` bytearrays of ``PIXELS * 3`` bytes
    (r, g, b per pixel); the list and its bytearrays are never replaced, so a
    reader may keep references to them.
    """

    def __init__(self, background: RGB, size: int = PIXELS) -> None:
        self.size = size
        self.background: RGB = _rgb(background)
        self.rows: list[bytearray] = [bytearray(bytes(self.background) * size) for _ in range(size)]
        self.generation = 0
        self._cleared_at = 0
        self._dirty: collections.deque[tuple[int, Rect]] = collections.deque(maxlen=_HISTORY)

    # -- reading -----------------------------------------------------------------
    def pixel(self, px: int, py: int) -> RGB:
        """The colour of pixel ``(px, py)`` (x right, y down)."""
        row = self.rows[py]
        i = px * 3
        return row[i], row[i + 1], row[i + 2]

    def region(self, x0: int, y0: int, x1: int, y1: int) -> Iterator[RGB]:
        """The colours of a rectangle (inclusive bounds), row by row."""
        for py in range(y0, y1 + 1):
            row = self.rows[py]
            for i in range(x0 * 3, x1 * 3 + 3, 3):
                yield row[i], row[i + 1], row[i + 2]

    def changes_since(self, generation: int) -> tuple[int, list[Rect] | None]:
        """The current generation and the rectangles changed after ``generation``.

        ``None`` instead of a list means "redraw everything": the image was
        cleared since then, or the change is older than the kept history.
        """
        now = self.generation
        if generation >= now:
            return now, []
        if generation < self._cleared_at:
            return now, None
        dirty = self._dirty
        if not dirty or dirty[0][0] > generation + 1:
            return now, None
        return now, [rect for gen, rect in dirty if gen > generation]

    # -- writing -----------------------------------------------------------------
    def clear(self, rgb: RGB | None = None) -> None:
        """Fill the whole image with ``rgb`` (default: the current background), which becomes the background."""
        if rgb is not None:
            self.background = _rgb(rgb)
        line = bytes(self.background) * self.size
        for row in self.rows:
            row[:] = line
        self.generation += 1
        self._cleared_at = self.generation
        self._dirty.clear()

    def draw_line(self, x0: float, y0: float, x1: float, y1: float, rgb: RGB, width: int) -> Rect | None:
        """Stroke a segment in image pixels with a square-ended pen; return the dirty rectangle.

        A zero-length segment draws nothing (None).
        """
        dx = x1 - x0
        dy = y1 - y0
        length = math.hypot(dx, dy)
        if length == 0.0 or not math.isfinite(length):
            return None
        half = max(width, 1) / 2.0
        ux = dx / length * half
        uy = dy / length * half
        # The stroke rectangle: the segment extended by half a width at both ends, half a width to each side.
        corners = (
            (x0 - ux - uy, y0 - uy + ux),
            (x1 + ux - uy, y1 + uy + ux),
            (x1 + ux + uy, y1 + uy - ux),
            (x0 - ux + uy, y0 - uy - ux),
        )
        return self._fill_convex(corners, bytes(rgb))

    def _fill_convex(self, corners: tuple[tuple[float, float], ...], color: bytes) -> Rect | None:
        """Set every pixel whose point lies inside a convex polygon."""
        last = self.size - 1
        ys = [c[1] for c in corners]
        top = max(math.ceil(min(ys)), 0)
        bottom = min(math.floor(max(ys)), last)
        edges = list(zip(corners, corners[1:] + corners[:1]))
        rows = self.rows
        left_most, right_most = self.size, -1
        for py in range(top, bottom + 1):
            lo = math.inf
            hi = -math.inf
            for (ax, ay), (bx, by) in edges:
                if ay == by:
                    if ay == py:
                        lo = min(lo, ax, bx)
                        hi = max(hi, ax, bx)
                elif (ay - py) * (by - py) <= 0.0:
                    x = ax + (py - ay) * (bx - ax) / (by - ay)
                    lo = min(lo, x)
                    hi = max(hi, x)
            if hi < lo:
                continue
            start = max(math.ceil(lo), 0)
            stop = min(math.floor(hi), last)
            if stop < start:
                continue
            rows[py][start * 3:stop * 3 + 3] = color * (stop - start + 1)
            left_most = min(left_most, start)
            right_most = max(right_most, stop)
        if right_most < 0:
            return None
        rect = (left_most, top, right_most, bottom)
        self.generation += 1
        self._dirty.append((self.generation, rect))
        return rect


def _rgb(value: RGB) -> RGB:
    """Validate a colour: three integers 0..255."""
    r, g, b = (int(c) for c in value)
    for c in (r, g, b):
        if not 0 <= c <= 255:
            raise ValueError(f"colour component {c} is outside 0..255")
    return r, g, b
