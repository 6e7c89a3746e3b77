"""What a terminal shows for a colour in each colour mode, and styles whose text stays readable on it.

The maths is in :mod:`rostui.models.contrast`; this module adds what Rich
knows: a 16- or 256-colour terminal gets each colour reduced by Rich
(:meth:`rich.color.Color.downgrade`), and a reduced colour is shown as Rich's
default terminal theme paints it (:meth:`rich.color.Color.get_truecolor`).
"""

from __future__ import annotations

from functools import lru_cache

from rich.color import Color, ColorSystem
from rich.style import Style
from rich.terminal_theme import DEFAULT_TERMINAL_THEME

from rostui.models.contrast import MINIMUM, RGB, Shown, contrast_ratio, keep_hue

_SYSTEMS = {"truecolor": ColorSystem.TRUECOLOR, "256": ColorSystem.EIGHT_BIT,
            "standard": ColorSystem.STANDARD, "windows": ColorSystem.WINDOWS}


def color_system(name: str | None) -> ColorSystem:
    """Rich's colour system for a console's ``color_system`` name ("standard", "256", ...); truecolor if none."""
    return _SYSTEMS.get(name or "", ColorSystem.TRUECOLOR)


@lru_cache(maxsize=4096)
def shown_rgb(rgb: RGB, system: ColorSystem) -> RGB:
    """The colour a terminal in ``system`` shows for ``rgb`` (reduced by Rich, painted in the default theme)."""
    triplet = Color.from_rgb(*rgb).downgrade(system).get_truecolor(DEFAULT_TERMINAL_THEME)
    return triplet.red, triplet.green, triplet.blue


def shown_in(system: ColorSystem) -> Shown:
    """A ``shown`` function (see :mod:`rostui.models.contrast`) for a terminal in ``system``."""
    return lambda rgb: shown_rgb(rgb, system)


def style_rgb(color: Color | None, *, foreground: bool = True) -> RGB | None:
    """The RGB a Rich colour stands for in the default theme (None for no colour or the terminal's default)."""
    if color is None or color.is_default:
        return None
    triplet = color.get_truecolor(DEFAULT_TERMINAL_THEME, foreground)
    return triplet.red, triplet.green, triplet.blue


def readable(style: Style, system: ColorSystem, minimum: float = MINIMUM) -> Style:
    """``style``, its text colour lightened or darkened if it had less than ``minimum`` contrast on its background.

    Both colours are compared as ``system`` shows them; a style without a
    text or background colour is returned unchanged.
    """
    fg, bg = style_rgb(style.color), style_rgb(style.bgcolor, foreground=False)
    if fg is None or bg is None:
        return style
    shown = shown_in(system)
    if contrast_ratio(shown(fg), shown(bg)) >= minimum:
        return style
    better = keep_hue(fg, [bg], shown, minimum)
    return style + Style(color=Color.from_rgb(*better))
