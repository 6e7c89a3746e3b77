"""Colours chosen by contrast: WCAG 2 relative luminance and contrast ratio, and picking a readable colour.

Pure maths on ``(r, g, b)`` tuples of 0..255, with no terminal library: the
apps and turtlesim pass a ``shown`` function that says what the terminal will
really show for a colour (after reducing it to 256 or 16 colours), and every
comparison here is made on shown colours.

The rule the apps follow: a colour drawn on top of another (a turtle on the
background, a pen trail on the background, the text of a highlighted row on
its highlight) must have a contrast ratio of at least :data:`MINIMUM` against
what is under it, once both are reduced to the terminal's colours.
"""

from __future__ import annotations

from typing import Callable, Iterable, Sequence

RGB = tuple[int, int, int]
"""A colour as red, green and blue, each 0..255."""

Shown = Callable[[RGB], RGB]
"""What a terminal shows for a colour (for example after reducing it to 16 colours)."""

MINIMUM = 3.0
"""The least contrast ratio a drawn colour keeps against what is under it (WCAG's level for large text and graphics)."""

WHITE: RGB = (255, 255, 255)
BLACK: RGB = (0, 0, 0)

#: How many steps :func:`shades` takes from a colour to white and to black.
SHADE_STEPS = 20


def as_is(rgb: RGB) -> RGB:
    """The identity ``shown`` function: a truecolor terminal shows every colour as it is."""
    return rgb


def _linear(channel: int) -> float:
    """An sRGB channel (0..255) as linear light (0..1), per WCAG 2."""
    c = channel / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def relative_luminance(rgb: RGB) -> float:
    """WCAG 2 relative luminance of ``rgb``: 0.0 for black up to 1.0 for white."""
    r, g, b = rgb
    return 0.2126 * _linear(r) + 0.7152 * _linear(g) + 0.0722 * _linear(b)


def contrast_ratio(a: RGB, b: RGB) -> float:
    """WCAG 2 contrast ratio of two colours: 1.0 (the same luminance) up to 21.0 (black on white)."""
    la, lb = relative_luminance(a), relative_luminance(b)
    return (max(la, lb) + 0.05) / (min(la, lb) + 0.05)


def least_contrast(rgb: RGB, under: Iterable[RGB], shown: Shown = as_is) -> float:
    """The lowest contrast ratio of ``rgb`` against any colour of ``under``, all as ``shown`` (21.0 if none)."""
    seen = shown(rgb)
    return min((contrast_ratio(seen, shown(u)) for u in under), default=21.0)


def pick(candidates: Sequence[RGB], under: Sequence[RGB], shown: Shown = as_is,
         minimum: float = MINIMUM) -> RGB:
    """The first of ``candidates`` that keeps ``minimum`` contrast against every colour of ``under``.

    Contrast is measured between shown colours (``shown``).  When no candidate
    reaches ``minimum``, the one whose least contrast is highest wins (the
    first of equals).  The candidate itself is returned, not its shown colour.
    """
    if not candidates:
        raise ValueError("pick needs at least one candidate colour")
    best, best_contrast = candidates[0], -1.0
    for candidate in candidates:
        value = least_contrast(candidate, under, shown)
        if value >= minimum:
            return candidate
        if value > best_contrast:
            best, best_contrast = candidate, value
    return best


def mix(a: RGB, b: RGB, amount: float) -> RGB:
    """``a`` moved ``amount`` (0..1) of the way to ``b``, channel by channel, rounded."""
    return (round(a[0] + (b[0] - a[0]) * amount), round(a[1] + (b[1] - a[1]) * amount),
            round(a[2] + (b[2] - a[2]) * amount))


def shades(rgb: RGB, steps: int = SHADE_STEPS) -> list[RGB]:
    """``rgb`` lightened and darkened in ``steps`` even steps, nearest first: lighter, darker, lighter, ...

    The list ends with white and black, so some shade always has a contrast of
    at least 4.58 against any single colour.
    """
    out: list[RGB] = []
    for step in range(1, steps + 1):
        amount = step / steps
        out += [mix(rgb, WHITE, amount), mix(rgb, BLACK, amount)]
    return out


def keep_hue(rgb: RGB, under: Sequence[RGB], shown: Shown = as_is, minimum: float = MINIMUM) -> RGB:
    """``rgb`` if it keeps ``minimum`` contrast against ``under``, else its nearest shade that does.

    For colours the user chose (a pen): the hue stays, only lightness moves,
    and only as far as needed.  Among shades the same distance away, the one
    with more contrast wins.
    """
    if least_contrast(rgb, under, shown) >= minimum:
        return rgb
    candidates = shades(rgb)
    for i in range(0, len(candidates), 2):
        pair = sorted(candidates[i:i + 2], key=lambda c: -least_contrast(c, under, shown))
        if least_contrast(pair[0], under, shown) >= minimum:
            return pair[0]
    return pick(candidates, under, shown, minimum)
