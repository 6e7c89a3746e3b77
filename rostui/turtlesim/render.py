"""TurtleView: a Textual widget that draws a turtlesim world with half-block cell-pixels.

The world is kept square: each terminal cell shows two cell-pixels (upper and
lower half block), which are about square on screen, so the world takes
``min(width, 2 * height)`` cell-pixels a side.  Trails come from
:class:`rostui.turtlesim.raster.Raster`; turtles are drawn on top as sprites
(:mod:`rostui.turtlesim.sprites`).  The widget uses the Line API: each frame
rebuilds only the rows where the image changed or a sprite moved, and asks
Textual to repaint only the cells that differ, at most :attr:`TurtleView.FRAME_RATE`
times a second and only when the world changed.

Colours are chosen by contrast (:mod:`rostui.models.contrast`) as the terminal
will show them in its colour mode: turtles and trails keep a contrast ratio of
at least 3 against the background; a trail keeps its pen's hue.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Iterable

from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Region
from textual.strip import Strip
from textual.widget import Widget

from rostui.apps.widgets.terminal_colors import color_system, shown_in
from rostui.models.contrast import Shown, keep_hue, pick
from rostui.turtlesim.canvas import PIXELS
from rostui.turtlesim.raster import RGB, Raster
from rostui.turtlesim.sprites import sprite_size, turtle_sprite
from rostui.turtlesim.world import METER

if TYPE_CHECKING:
    from rostui.turtlesim.world import Turtle, TurtleWorld

#: One terminal cell: glyph, foreground, background (None: the widget's own), bold.
Cell = tuple[str, "RGB | None", "RGB | None", bool]

UPPER_HALF = "▀"
EMPTY: Cell = (" ", None, None, False)

#: Sprite colours, most wanted first: the first that keeps a contrast of 3 against the
#: background (as the terminal shows both) is used.  White and black are in both lists:
#: one of them always reaches 3 against a single colour.
SELECTED_COLORS: tuple[RGB, ...] = ((255, 221, 0), (0, 0, 0), (255, 255, 255))
TURTLE_COLORS: tuple[RGB, ...] = ((120, 230, 120), (0, 110, 0), (255, 255, 255), (0, 0, 0))


def turtle_colors(background: RGB, shown: Shown) -> tuple[RGB, RGB]:
    """The colours of the selected turtle and of the others on ``background``, as ``shown`` by the terminal.

    Each is the first of its list (:data:`SELECTED_COLORS`, :data:`TURTLE_COLORS`)
    with a contrast of at least 3 against the background; the others never take
    the selected turtle's shown colour, so the selected one stands out.
    """
    selected = pick(SELECTED_COLORS, [background], shown)
    others = [c for c in TURTLE_COLORS if shown(c) != shown(selected)] or list(TURTLE_COLORS)
    return selected, pick(others, [background], shown)


def trail_color(pen: RGB, background: RGB, shown: Shown) -> RGB:
    """The colour a trail drawn with ``pen`` is shown in: the pen, or its nearest shade with contrast 3.

    A pen of the background's own colour (an eraser) stays invisible.
    """
    return pen if pen == background else keep_hue(pen, [background], shown)


@dataclass(frozen=True)
class ViewLayout:
    """Where the square world sits in a widget of ``width`` x ``height`` cells."""

    width: int
    height: int
    size: int
    left: int
    top: int

    @classmethod
    def fit(cls, width: int, height: int) -> "ViewLayout":
        """The largest square world (in cell-pixels) that fits, centred."""
        size = max(0, min(width, 2 * height))
        rows = (size + 1) // 2
        return cls(width, height, size, (width - size) // 2, (height - rows) // 2)

    @property
    def rows(self) -> int:
        """Terminal rows the world occupies."""
        return (self.size + 1) // 2


@dataclass(frozen=True)
class PlacedSprite:
    """A turtle's sprite at widget cells: ``(x, y, glyph)`` each."""

    cells: tuple[tuple[int, int, str], ...]
    color: RGB
    bold: bool

    @property
    def rows(self) -> set[int]:
        """Widget rows the sprite touches."""
        return {y for _, y, _ in self.cells}


class TurtleView(Widget):
    """Draws a :class:`~rostui.turtlesim.world.TurtleWorld`: trails in pen colours, turtles as sprites.

    ``selected`` names the highlighted turtle.  :meth:`draw_frame` runs on a
    timer at :attr:`FRAME_RATE`; :attr:`frames` counts the frames that drew
    something.
    """

    DEFAULT_CSS = """
    TurtleView {
        width: 1fr;
        height: 1fr;
    }
    """

    FRAME_RATE = 30.0

    def __init__(self, world: "TurtleWorld | None" = None, *, name: str | None = None,
                 id: str | None = None, classes: str | None = None) -> None:
        super().__init__(name=name, id=id, classes=classes)
        self._world = world
        self._selected = ""
        self._layout: ViewLayout | None = None
        self._raster: Raster | None = None
        self._cells: list[list[Cell]] = []
        self._strips: list[Strip] = []
        self._sprites: dict[str, PlacedSprite] = {}
        self._seen_generation = -1
        self._styles: dict[tuple[RGB | None, RGB | None, bool], Style] = {}
        self._palette: dict[RGB, RGB] = {}
        self._shown: Shown = shown_in(color_system(None))
        self._stale = True
        self.frames = 0

    # -- public ----------------------------------------------------------------
    @property
    def world(self) -> "TurtleWorld | None":
        """The world drawn (None: nothing yet)."""
        return self._world

    @world.setter
    def world(self, world: "TurtleWorld | None") -> None:
        self._world = world
        self._invalidate()

    @property
    def selected(self) -> str:
        """Name of the highlighted turtle ("" for none)."""
        return self._selected

    @selected.setter
    def selected(self, name: str) -> None:
        if name != self._selected:
            self._selected = name
            self._seen_generation = -1  # sprites must be redrawn even if the world is unchanged

    def draw_frame(self) -> bool:
        """Bring the picture up to date with the world; True if anything was redrawn."""
        world = self._world
        if world is None or not self.is_mounted:
            return False
        if self._stale or self._layout is None or self._layout.width != self.size.width \
                or self._layout.height != self.size.height:
            self._rebuild()
            return True
        if world.generation == self._seen_generation or self._raster is None:
            return False
        self._seen_generation = world.generation
        layout = self._layout
        dirty: set[int] = set()
        grid_rows = self._raster.sync()
        if grid_rows is None:
            self._palette.clear()
            self._styles.clear()
            dirty.update(range(layout.top, layout.top + layout.rows))
        else:
            dirty.update(layout.top + row // 2 for row in grid_rows)
        sprites = self._place_sprites()
        for name in self._sprites.keys() | sprites.keys():
            old, new = self._sprites.get(name), sprites.get(name)
            if old != new:
                if old is not None:
                    dirty.update(old.rows)
                if new is not None:
                    dirty.update(new.rows)
        self._sprites = sprites
        drew = False
        for y in sorted(dirty):
            if 0 <= y < layout.height:
                drew |= self._redraw_row(y)
        if drew:
            self.frames += 1
        return drew

    def cells(self, y: int) -> list[Cell]:
        """The cells of row ``y`` as last drawn (for tests and tools)."""
        return list(self._cells[y]) if 0 <= y < len(self._cells) else []

    def shown_color(self, rgb: RGB) -> RGB:
        """The colour the view draws for a world colour ``rgb`` (before the terminal reduces it to its mode)."""
        return self._display(rgb)

    # -- Textual hooks -------------------------------------------------------------
    def on_mount(self) -> None:
        """Start the frame timer."""
        self.set_interval(1.0 / self.FRAME_RATE, self.draw_frame)

    def on_resize(self) -> None:
        """Re-fit the world to the new size at once."""
        self._invalidate()
        self.draw_frame()

    def render_line(self, y: int) -> Strip:
        """Line API: the stored strip of row ``y``."""
        if self._stale or self._layout is None or self._layout.width != self.size.width:
            self._rebuild()
        if 0 <= y < len(self._strips):
            return self._strips[y]
        return Strip.blank(self.size.width)

    # -- drawing -------------------------------------------------------------------
    def _invalidate(self) -> None:
        self._stale = True
        self._seen_generation = -1

    def _rebuild(self) -> None:
        """Lay out, rasterise and draw everything; one full refresh."""
        self._stale = False
        width, height = self.size.width, self.size.height
        self._layout = ViewLayout.fit(width, height)
        self._shown = shown_in(color_system(self.app.console.color_system))
        self._palette.clear()
        self._styles.clear()
        world = self._world
        if world is not None and self._layout.size > 0:
            self._raster = Raster(world.image, self._layout.size)
            self._seen_generation = world.generation
            self._sprites = self._place_sprites()
        else:
            self._raster = None
            self._sprites = {}
        self._cells = [self._build_row(y) for y in range(height)]
        self._strips = [self._strip(row) for row in self._cells]
        self.frames += 1
        self.refresh()

    def _redraw_row(self, y: int) -> bool:
        """Rebuild row ``y``; repaint only the span of cells that changed."""
        new = self._build_row(y)
        old = self._cells[y]
        first = next((i for i, (a, b) in enumerate(zip(old, new)) if a != b), None)
        if first is None:
            return False
        last = next(i for i in range(len(new) - 1, -1, -1) if old[i] != new[i])
        self._cells[y] = new
        self._strips[y] = self._strip(new)
        self.refresh(Region(first, y, last - first + 1, 1))
        return True

    def _build_row(self, y: int) -> list[Cell]:
        layout = self._layout
        assert layout is not None
        row: list[Cell] = [EMPTY] * layout.width
        raster = self._raster
        if raster is None or not layout.top <= y < layout.top + layout.rows:
            return row
        grid_row = 2 * (y - layout.top)
        upper = raster.colors[grid_row]
        lower = raster.colors[grid_row + 1] if grid_row + 1 < layout.size else None
        left = layout.left
        for col in range(layout.size):
            top_color = upper[col]
            if lower is None:
                row[left + col] = (UPPER_HALF, top_color, None, False)
            elif lower[col] == top_color:
                row[left + col] = (" ", None, top_color, False)
            else:
                row[left + col] = (UPPER_HALF, top_color, lower[col], False)
        background = raster.image.background
        for sprite in self._sprites.values():
            for x, sy, glyph in sprite.cells:
                if sy == y:
                    row[x] = (glyph, sprite.color, background, sprite.bold)
        return row

    def _place_sprites(self) -> dict[str, PlacedSprite]:
        """Sprites of every turtle, the selected one last (drawn on top)."""
        world, layout = self._world, self._layout
        if world is None or layout is None or layout.size == 0:
            return {}
        kind = sprite_size(layout.size)
        selected_color, other_color = turtle_colors(world.background, self._shown)
        turtles: Iterable[Turtle] = list(world.turtles.values())
        ordered = sorted(turtles, key=lambda t: t.name == self._selected)
        placed: dict[str, PlacedSprite] = {}
        for turtle in ordered:
            col, row = self._cell_of(turtle)
            selected = turtle.name == self._selected
            cells = tuple(
                (col + dx, row + dy, glyph) for dx, dy, glyph in turtle_sprite(turtle.theta, kind).cells
                if layout.left <= col + dx < layout.left + layout.size
                and layout.top <= row + dy < layout.top + layout.rows
            )
            placed[turtle.name] = PlacedSprite(cells, selected_color if selected else other_color, selected)
        return placed

    def _cell_of(self, turtle: "Turtle") -> tuple[int, int]:
        """The widget cell under the turtle's centre (the image pixel it stands on)."""
        layout = self._layout
        assert layout is not None
        px = turtle.x * METER if math.isfinite(turtle.x) else 0.0
        py = turtle.down * METER if math.isfinite(turtle.down) else 0.0
        gx = min(layout.size - 1, max(0, math.floor(px * layout.size / PIXELS)))
        gy = min(layout.size - 1, max(0, math.floor(py * layout.size / PIXELS)))
        return layout.left + gx, layout.top + gy // 2

    def _display(self, rgb: RGB) -> RGB:
        shown = self._palette.get(rgb)
        if shown is None:
            background = self._raster.image.background if self._raster is not None else rgb
            shown = trail_color(rgb, background, self._shown)
            self._palette[rgb] = shown
        return shown

    def _style(self, fg: RGB | None, bg: RGB | None, bold: bool) -> Style:
        key = (fg, bg, bold)
        style = self._styles.get(key)
        if style is None:
            style = Style(
                color=Color.from_rgb(*self._display(fg)) if fg is not None else None,
                bgcolor=Color.from_rgb(*self._display(bg)) if bg is not None else None,
                bold=bold or None,
            )
            self._styles[key] = style
        return style

    def _strip(self, cells: list[Cell]) -> Strip:
        segments: list[Segment] = []
        text: list[str] = []
        key: tuple[RGB | None, RGB | None, bool] | None = None
        for glyph, fg, bg, bold in cells:
            if fg is not None and glyph == " ":
                fg = None
            cell_key = (fg, bg, bold)
            if cell_key != key:
                if text and key is not None:
                    segments.append(Segment("".join(text), self._style(*key)))
                text = []
                key = cell_key
            text.append(glyph)
        if text and key is not None:
            segments.append(Segment("".join(text), self._style(*key)))
        return Strip(segments, len(cells))
