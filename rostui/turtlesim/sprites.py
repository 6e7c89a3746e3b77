"""Turtles as small text-art sprites whose head shows the heading (8 directions); no Textual here.

Seen from above: a shell ``(@)``, four legs, and the head as an arrow on the
side the turtle faces.  Smaller worlds get a one-line ``(→)`` or a lone arrow.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Head glyphs by heading index: 0 east, then counter-clockwise in 45 degree steps.
ARROWS = "→↗↑↖←↙↓↘"

#: Where the head sits around a 5x3 turtle, by heading index (dx right, dy down).
_HEAD_OFFSETS = ((2, 0), (2, -1), (0, -1), (-2, -1), (-2, 0), (-2, 1), (0, 1), (2, 1))

_BODY = ((-1, -1, "\\"), (1, -1, "/"), (-1, 0, "("), (0, 0, "@"), (1, 0, ")"), (-1, 1, "/"), (1, 1, "\\"))

#: World widths (in cells) from which the larger sprites are used.
LARGE_FROM = 40
COMPACT_FROM = 12


@dataclass(frozen=True)
class Sprite:
    """Glyphs at offsets ``(dx, dy)`` from the turtle's cell; the rest of the box is see-through."""

    cells: tuple[tuple[int, int, str], ...]


def heading_index(theta: float) -> int:
    """The nearest of 8 compass directions to ``theta`` (radians, 0 = east, counter-clockwise)."""
    return round(theta / (math.pi / 4)) % 8


def sprite_size(world_cells: int) -> str:
    """``"large"`` (5x3), ``"compact"`` (3x1) or ``"tiny"`` (1x1) for a world this many cells wide."""
    if world_cells >= LARGE_FROM:
        return "large"
    if world_cells >= COMPACT_FROM:
        return "compact"
    return "tiny"


def turtle_sprite(theta: float, size: str) -> Sprite:
    """The sprite of a turtle heading ``theta`` at ``size`` (see :func:`sprite_size`)."""
    heading = heading_index(theta)
    arrow = ARROWS[heading]
    if size == "tiny":
        return Sprite(((0, 0, arrow),))
    if size == "compact":
        return Sprite(((-1, 0, "("), (0, 0, arrow), (1, 0, ")")))
    dx, dy = _HEAD_OFFSETS[heading]
    return Sprite((*_BODY, (dx, dy, arrow)))
