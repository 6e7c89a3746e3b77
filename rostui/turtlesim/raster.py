"""The path image reduced to a square grid of terminal cell-pixels (no Textual here).

A cell-pixel is half a terminal cell (an upper or lower half block), about
square on screen.  Each one covers a block of image pixels; it shows the
image's background colour unless any pixel of its block differs, in which
case it takes that pixel's colour, so a 3-pixel pen trail survives being
shrunk into a 44-cell-pixel-wide world.
"""

from __future__ import annotations

from typing import Protocol, Sequence

RGB = tuple[int, int, int]


class PixelSource(Protocol):
    """What the raster reads from the path image (see rostui.turtlesim.canvas.PathImage)."""

    @property
    def background(self) -> RGB:
        """The colour of the empty canvas."""
        ...

    @property
    def rows(self) -> Sequence[bytearray]:
        """One bytearray of RGB triples per pixel row."""
        ...

    @property
    def generation(self) -> int:
        """A number that changes with every drawing."""
        ...

    def changes_since(self, generation: int) -> tuple[int, list[tuple[int, int, int, int]] | None]:
        """The new generation and the pixel rectangles changed since ``generation`` (None: all)."""
        ...


def block_edges(size: int, pixels: int) -> list[int]:
    """Image-pixel boundaries of ``size`` blocks over ``pixels`` pixels (``size + 1`` edges).

    When there are more blocks than pixels, each block still covers one pixel.
    """
    edges = [i * pixels // size for i in range(size + 1)]
    if size > pixels:
        edges = [min(e, pixels - 1) for e in edges[:-1]] + [pixels]
    return edges


class Raster:
    """A ``size`` x ``size`` grid of cell-pixel colours kept in step with a path image.

    ``colors[row][col]`` is an RGB tuple.  :meth:`sync` folds in the image's
    changes since the last call and returns which rows of the grid changed.
    """

    def __init__(self, image: PixelSource, size: int) -> None:
        self.image = image
        self.size = size
        self.pixels = len(image.rows)
        self.edges = block_edges(size, self.pixels)
        self._first_block: list[int] = []
        self._last_block: list[int] = []
        self._map_pixels_to_blocks()
        self.colors: list[list[RGB]] = []
        self._generation = -1
        self._background: RGB = image.background
        self._bg_bytes = b""
        self.rebuild()

    def _map_pixels_to_blocks(self) -> None:
        first = [self.size] * self.pixels
        last = [-1] * self.pixels
        for block in range(self.size):
            lo = self.edges[block]
            hi = max(self.edges[block + 1], lo + 1)
            for px in range(lo, hi):
                first[px] = min(first[px], block)
                last[px] = max(last[px], block)
        self._first_block, self._last_block = first, last

    def blocks_of(self, lo: int, hi: int) -> range:
        """Grid indices whose blocks touch image pixels ``lo..hi`` (inclusive)."""
        lo = max(0, min(lo, self.pixels - 1))
        hi = max(0, min(hi, self.pixels - 1))
        return range(self._first_block[lo], self._last_block[hi] + 1)

    def rebuild(self) -> None:
        """Recompute every cell-pixel from the image."""
        self._generation = self.image.generation
        self._background = self.image.background
        bg = self._background
        self._bg_bytes = bytes(bg) * self.pixels
        self.colors = [[bg] * self.size for _ in range(self.size)]
        for row in range(self.size):
            self._update_row(row, range(self.size))

    def sync(self) -> set[int] | None:
        """Apply the image's changes; return the changed grid rows (None: all of them)."""
        if self.image.generation == self._generation:
            return set()
        generation, rects = self.image.changes_since(self._generation)
        if rects is None or self.image.background != self._background:
            self.rebuild()
            return None
        self._generation = generation
        changed: set[int] = set()
        for x0, y0, x1, y1 in rects:
            cols = self.blocks_of(min(x0, x1), max(x0, x1))
            for row in self.blocks_of(min(y0, y1), max(y0, y1)):
                if self._update_row(row, cols):
                    changed.add(row)
        return changed

    def _update_row(self, row: int, cols: range) -> bool:
        """Recompute ``cols`` of grid row ``row``; True if any colour changed."""
        rows = self.image.rows
        lo = self.edges[row]
        band = [rows[y] for y in range(lo, max(self.edges[row + 1], lo + 1))]
        bg = self._background
        bg_bytes = self._bg_bytes
        line = self.colors[row]
        changed = False
        busy = [r for r in band if r != bg_bytes]
        for col in cols:
            color = bg
            if busy:
                x0 = self.edges[col] * 3
                x1 = max(self.edges[col + 1], self.edges[col] + 1) * 3
                blank = bg_bytes[: x1 - x0]
                for r in busy:
                    chunk = r[x0:x1]
                    if chunk != blank:
                        color = _first_other(chunk, bg)
                        break
            if line[col] != color:
                line[col] = color
                changed = True
        return changed


def _first_other(chunk: bytes | bytearray, bg: RGB) -> RGB:
    """The first pixel of ``chunk`` (packed RGB) whose colour is not ``bg``."""
    for i in range(0, len(chunk), 3):
        pixel = (chunk[i], chunk[i + 1], chunk[i + 2])
        if pixel != bg:
            return pixel
    return bg
