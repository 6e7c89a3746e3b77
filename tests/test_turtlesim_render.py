"""The renderer's pure parts: shrinking the path image to cell-pixels, turtle sprites (colours: test_contrast.py)."""

from __future__ import annotations

import math

import pytest

from rostui.turtlesim.canvas import PIXELS, PathImage
from rostui.turtlesim.raster import Raster, block_edges
from rostui.turtlesim.render import ViewLayout
from rostui.turtlesim.sprites import ARROWS, heading_index, sprite_size, turtle_sprite
from rostui.turtlesim.world import DEFAULT_BACKGROUND, DEFAULT_PEN

PEN = DEFAULT_PEN.rgb


@pytest.mark.parametrize("size", [7, 20, 44, 61, 140, 499, 500, 640])
def test_blocks_cover_every_pixel_once_in_order(size: int) -> None:
    """Block edges start at 0, end at 500 and never go backwards; each block has at least one pixel."""
    edges = block_edges(size, PIXELS)
    assert len(edges) == size + 1 and edges[0] == 0 and edges[-1] == PIXELS
    assert all(b >= a for a, b in zip(edges, edges[1:]))
    covered = set()
    for i in range(size):
        covered.update(range(edges[i], max(edges[i + 1], edges[i] + 1)))
    assert covered == set(range(PIXELS))


@pytest.mark.parametrize("size", [20, 44, 61, 140])
@pytest.mark.parametrize("angle", [0.0, 0.3, math.pi / 4, 1.2, math.pi / 2, 2.9])
def test_a_three_pixel_trail_survives_shrinking(size: int, angle: float) -> None:
    """Every cell-pixel whose block holds a pen pixel shows the pen colour; the others the background."""
    image = PathImage(DEFAULT_BACKGROUND)
    raster = Raster(image, size)
    x0, y0 = 250.0, 250.0
    x1, y1 = x0 + 200 * math.cos(angle), y0 - 200 * math.sin(angle)
    image.draw_line(x0, y0, x1, y1, PEN, 3)
    raster.sync()
    edges = block_edges(size, PIXELS)
    for row in range(size):
        for col in range(size):
            inked = any(
                image.pixel(px, py) == PEN
                for py in range(edges[row], max(edges[row + 1], edges[row] + 1))
                for px in range(edges[col], max(edges[col + 1], edges[col] + 1))
            )
            assert raster.colors[row][col] == (PEN if inked else DEFAULT_BACKGROUND), (row, col)


def test_sync_reports_only_the_changed_rows_and_everything_after_clear() -> None:
    """A short stroke changes a row or two; a clear (new background) changes all of them (None)."""
    image = PathImage(DEFAULT_BACKGROUND)
    raster = Raster(image, 44)
    assert raster.sync() == set()
    image.draw_line(100, 300, 110, 300, PEN, 3)
    changed = raster.sync()
    assert changed == {300 * 44 // PIXELS}
    assert raster.sync() == set()
    image.clear((0, 0, 0))
    assert raster.sync() is None
    assert all(color == (0, 0, 0) for line in raster.colors for color in line)


def test_world_layout_is_square_centred_and_uses_half_blocks() -> None:
    """80x22 cells hold a 44-pixel world: 44 columns by 22 rows, centred horizontally."""
    layout = ViewLayout.fit(80, 22)
    assert (layout.size, layout.rows, layout.left, layout.top) == (44, 22, 18, 0)
    tall = ViewLayout.fit(30, 40)
    assert (tall.size, tall.rows, tall.left, tall.top) == (30, 15, 0, 12)
    assert ViewLayout.fit(0, 10).size == 0


def test_eight_headings_each_with_its_own_arrow() -> None:
    """Headings round to the nearest 45 degrees; east is 0, counter-clockwise like ROS."""
    for i in range(8):
        theta = i * math.pi / 4
        assert heading_index(theta) == i
        assert heading_index(theta + 0.3) == i
        assert heading_index(theta - 0.3 - 2 * math.pi) == i
    assert [ARROWS[heading_index(t)] for t in (0, math.pi / 2, math.pi, -math.pi / 2)] == ["→", "↑", "←", "↓"]


def test_large_sprite_puts_the_head_on_the_heading_side() -> None:
    """The 5x3 turtle: shell at the centre, legs at the corners, head one step further out where it faces."""
    for i in range(8):
        cells = {(dx, dy): glyph for dx, dy, glyph in turtle_sprite(i * math.pi / 4, "large").cells}
        assert cells[(0, 0)] == "@" and cells[(-1, 0)] == "(" and cells[(1, 0)] == ")"
        head = [(dx, dy) for (dx, dy), glyph in cells.items() if glyph == ARROWS[i]]
        assert len(head) == 1
        dx, dy = head[0]
        assert (round(math.copysign(1, dx)) if dx else 0, -round(math.copysign(1, dy)) if dy else 0) == (
            round(math.cos(i * math.pi / 4)), round(math.sin(i * math.pi / 4)))
    assert [glyph for _, _, glyph in turtle_sprite(math.pi / 2, "compact").cells] == ["(", "↑", ")"]
    assert [glyph for _, _, glyph in turtle_sprite(math.pi, "tiny").cells] == ["←"]
    assert (sprite_size(44), sprite_size(20), sprite_size(8)) == ("large", "compact", "tiny")
