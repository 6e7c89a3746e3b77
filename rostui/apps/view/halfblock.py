"""HalfBlock: RGB pixels as half-block characters (``▀``: the upper pixel in the foreground, the lower in the background).

textual-image draws half blocks too, but builds a Rich style per cell on
every repaint (about 100 ms of CPU for a 100x40 panel), too slow for a 30 fps
camera.  This widget turns a frame into lines once, when it arrives, and
reuses one style object per colour pair, so repeated colours cost a lookup
and Textual's compositor finds their escape codes cached.  Colours are kept
to 16 levels a channel (0 and 255 stay exact), which makes repeats common
and neighbouring cells of one colour merge into one run of text.
"""

from __future__ import annotations

import numpy as np
from rich.color import Color, ColorType
from rich.color_triplet import ColorTriplet
from rich.segment import Segment
from rich.style import Style
from textual.strip import Strip
from textual.widget import Widget

__all__ = ["HalfBlock"]

#: Styles kept for reuse; past this many the cache starts again (a noisy camera has many colour pairs).
MAX_STYLES = 65536
UPPER_HALF = "▀"
#: Bits kept of each channel.
BITS = 4
_LEVELS = (1 << BITS) - 1
#: Each kept level as 0-255 (0 -> 0, the top level -> 255).
_EXPAND = [round(level * 255 / _LEVELS) for level in range(_LEVELS + 1)]


def _colour(code: int) -> Color:
    """The truecolor of a packed colour (``BITS`` bits a channel, red highest)."""
    r, g, b = _EXPAND[code >> (2 * BITS)], _EXPAND[(code >> BITS) & _LEVELS], _EXPAND[code & _LEVELS]
    return Color(f"#{r:02x}{g:02x}{b:02x}", ColorType.TRUECOLOR, triplet=ColorTriplet(r, g, b))


class HalfBlock(Widget):
    """A picture of ``w`` x ``h`` pixels drawn in ``w`` x ``ceil(h / 2)`` cells; :meth:`set_pixels` replaces it."""

    DEFAULT_CSS = """
    HalfBlock { width: auto; height: auto; }
    """

    def __init__(self, *, id: str | None = None, classes: str | None = None) -> None:
        super().__init__(id=id, classes=classes)
        self._strips: list[Strip] = []
        self._styles: dict[int, Style] = {}
        self._width = 0

    def set_pixels(self, rgb: np.ndarray) -> None:
        """Show ``rgb`` (H x W x 3 uint8); an odd last row gets black below it."""
        height, width = rgb.shape[:2]
        if height % 2:
            rgb = np.concatenate([rgb, np.zeros((1, width, 3), dtype=np.uint8)])
        levels = ((rgb.astype(np.uint32) * _LEVELS + 127) // 255)
        packed = (levels[..., 0] << (2 * BITS)) | (levels[..., 1] << BITS) | levels[..., 2]
        pairs = (packed[0::2] << (3 * BITS)) | packed[1::2]  # upper colour, lower colour
        styles = self._styles
        if len(styles) > MAX_STYLES:
            styles.clear()
        mask = (1 << (3 * BITS)) - 1
        strips = []
        for row in pairs.tolist():
            segments = []
            run_key, run = -1, 0
            for key in row + [-2]:
                if key == run_key:
                    run += 1
                    continue
                if run:
                    style = styles.get(run_key)
                    if style is None:
                        style = Style(color=_colour(run_key >> (3 * BITS)), bgcolor=_colour(run_key & mask))
                        styles[run_key] = style
                    segments.append(Segment(UPPER_HALF * run, style))
                run_key, run = key, 1
            strips.append(Strip(segments, width))
        resized = width != self._width or len(strips) != len(self._strips)
        self._strips, self._width = strips, width
        self.refresh(layout=resized)

    def get_content_width(self, container: object, viewport: object) -> int:
        """The picture's width in cells."""
        return self._width

    def get_content_height(self, container: object, viewport: object, width: int) -> int:
        """The picture's height in cells."""
        return len(self._strips)

    def render_line(self, y: int) -> Strip:
        """Line ``y`` of the picture (blank below it)."""
        if 0 <= y < len(self._strips):
            return self._strips[y]
        return Strip.blank(self.size.width)
