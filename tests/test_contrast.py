"""Colours chosen by contrast: the WCAG maths, the shown colour in each colour mode, and turtlesim's choices.

The acceptance table: on the book's backgrounds (turtlesim's default blue,
chapter 7's yellow, white, black) in 16 colours, 256 colours and truecolor,
the selected turtle, the other turtles and the trails of the default pen (and
other pens) keep a contrast ratio of at least 3 against the background, both
measured as the terminal shows them.  tests/test_turtlesim_app.py checks the
same on the cells the app really renders.
"""

from __future__ import annotations

import pytest
from rich.color import ColorSystem
from rich.style import Style

from rostui.apps.widgets.terminal_colors import color_system, readable, shown_in, shown_rgb, style_rgb
from rostui.models.contrast import (
    BLACK, MINIMUM, WHITE, RGB, contrast_ratio, keep_hue, least_contrast, mix, pick, relative_luminance, shades)
from rostui.turtlesim.render import SELECTED_COLORS, TURTLE_COLORS, trail_color, turtle_colors
from rostui.turtlesim.world import DEFAULT_BACKGROUND, DEFAULT_PEN

#: The book's backgrounds: turtlesim's default, chapter 7's yellow, and the two extremes.
BACKGROUNDS: dict[str, RGB] = {"blue": DEFAULT_BACKGROUND, "yellow": (255, 255, 0), "white": WHITE, "black": BLACK}
#: The default pen, and pens a reader tries with set_pen.
PENS: dict[str, RGB] = {"default": DEFAULT_PEN.rgb, "red": (255, 0, 0), "green": (0, 255, 0), "white": WHITE,
                        "black": BLACK, "yellow": (255, 255, 0)}
MODES = [ColorSystem.STANDARD, ColorSystem.EIGHT_BIT, ColorSystem.TRUECOLOR]


def test_luminance_and_contrast_follow_wcag() -> None:
    """WCAG 2's reference points: black 0, white 1, black on white 21, #777 on white about 4.48, symmetric."""
    assert relative_luminance(BLACK) == 0.0
    assert relative_luminance(WHITE) == pytest.approx(1.0)
    assert contrast_ratio(BLACK, WHITE) == pytest.approx(21.0)
    assert contrast_ratio(WHITE, BLACK) == pytest.approx(21.0)
    assert contrast_ratio((119, 119, 119), WHITE) == pytest.approx(4.48, abs=0.01)
    assert contrast_ratio((69, 86, 255), (69, 86, 255)) == 1.0
    # turtlesim's own default pen on its default background is below 3: why trails get a shade.
    assert contrast_ratio(DEFAULT_PEN.rgb, DEFAULT_BACKGROUND) == pytest.approx(2.78, abs=0.01)


def test_pick_takes_the_first_good_candidate_else_the_best() -> None:
    """Order is preference: the first with contrast >= 3 wins; if none has it, the highest least contrast."""
    grey = (128, 128, 128)
    assert pick([(255, 221, 0), BLACK, WHITE], [WHITE]) == BLACK
    assert pick([(255, 221, 0), WHITE, BLACK], [BLACK]) == (255, 221, 0)
    assert pick([(120, 120, 120), (140, 140, 140)], [grey]) == (140, 140, 140)
    assert pick([WHITE, BLACK], [WHITE, BLACK]) in (WHITE, BLACK)
    assert least_contrast(BLACK, []) == 21.0
    with pytest.raises(ValueError):
        pick([], [WHITE])


def test_pick_measures_shown_colours() -> None:
    """A candidate that is fine as it is but becomes the background's colour once shown loses."""
    def merge(rgb: RGB) -> RGB:
        """A terminal that shows every dark colour as black."""
        return BLACK if sum(rgb) < 300 else rgb

    assert pick([(200, 0, 0), WHITE], [BLACK]) == (200, 0, 0)
    assert pick([(200, 0, 0), WHITE], [BLACK], merge) == WHITE
    assert least_contrast((200, 0, 0), [BLACK], merge) == 1.0


def test_keep_hue_moves_only_lightness_and_only_as_far_as_needed() -> None:
    """A pen with enough contrast stays; else the nearest shade (toward white or black) with contrast >= 3."""
    assert keep_hue((255, 0, 0), [BLACK]) == (255, 0, 0)
    lighter = keep_hue(DEFAULT_PEN.rgb, [DEFAULT_BACKGROUND])
    assert contrast_ratio(lighter, DEFAULT_BACKGROUND) >= MINIMUM
    assert lighter in shades(DEFAULT_PEN.rgb)[:6]  # a few steps, not white
    assert relative_luminance(lighter) > relative_luminance(DEFAULT_PEN.rgb)
    darker = keep_hue(DEFAULT_PEN.rgb, [(255, 255, 0)])
    assert relative_luminance(darker) < relative_luminance(DEFAULT_PEN.rgb)
    assert darker[2] > darker[0] and darker[2] > darker[1]  # still bluish
    assert shades(DEFAULT_PEN.rgb)[-2:] == [WHITE, BLACK]
    assert mix(BLACK, WHITE, 0.5) == (128, 128, 128)


def test_shown_colours_in_each_mode() -> None:
    """truecolor shows a colour as it is; 256 colours the nearest of xterm's cube; 16 the theme's ANSI colour."""
    gold = (255, 221, 0)
    assert shown_rgb(gold, ColorSystem.TRUECOLOR) == gold
    assert shown_rgb(gold, ColorSystem.EIGHT_BIT) == (255, 215, 0)
    assert shown_rgb(gold, ColorSystem.STANDARD) == (255, 255, 0)
    assert shown_rgb(DEFAULT_BACKGROUND, ColorSystem.STANDARD) == (0, 0, 255)
    assert color_system("standard") == ColorSystem.STANDARD
    assert color_system("256") == ColorSystem.EIGHT_BIT
    assert color_system(None) == ColorSystem.TRUECOLOR
    assert shown_in(ColorSystem.EIGHT_BIT)(gold) == (255, 215, 0)


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.name.lower())
@pytest.mark.parametrize("background", BACKGROUNDS.values(), ids=list(BACKGROUNDS))
def test_the_selected_turtle_keeps_contrast_3_on_the_books_backgrounds(mode: ColorSystem, background: RGB) -> None:
    """Selected and other turtles: contrast >= 3 against the background as shown, and not the same shown colour."""
    shown = shown_in(mode)
    selected, other = turtle_colors(background, shown)
    assert selected in SELECTED_COLORS and other in TURTLE_COLORS
    assert contrast_ratio(shown(selected), shown(background)) >= MINIMUM
    assert contrast_ratio(shown(other), shown(background)) >= MINIMUM
    assert shown(selected) != shown(other)


def test_the_selected_turtle_is_no_longer_yellow_on_yellow() -> None:
    """Chapter 7's yellow background: the gold selected turtle (contrast 1.25) is replaced; on blue it stays gold."""
    yellow = BACKGROUNDS["yellow"]
    assert contrast_ratio(SELECTED_COLORS[0], yellow) < 1.3
    for mode in MODES:
        assert turtle_colors(yellow, shown_in(mode))[0] != SELECTED_COLORS[0]
    assert turtle_colors(DEFAULT_BACKGROUND, shown_in(ColorSystem.TRUECOLOR))[0] == SELECTED_COLORS[0]


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.name.lower())
@pytest.mark.parametrize("background", BACKGROUNDS.values(), ids=list(BACKGROUNDS))
@pytest.mark.parametrize("pen", PENS.values(), ids=list(PENS))
def test_trails_keep_contrast_3_and_their_hue(mode: ColorSystem, background: RGB, pen: RGB) -> None:
    """A trail is shown in its pen colour or the nearest shade of it with contrast >= 3; an eraser stays invisible."""
    shown = shown_in(mode)
    trail = trail_color(pen, background, shown)
    if pen == background:
        assert trail == background
        return
    assert contrast_ratio(shown(trail), shown(background)) >= MINIMUM
    if contrast_ratio(shown(pen), shown(background)) >= MINIMUM:
        assert trail == pen
    else:
        assert trail in shades(pen)


def test_readable_fixes_only_text_that_would_fade_into_its_highlight() -> None:
    """A highlighted row's text colour is kept when readable, else a shade of it with contrast >= 3."""
    good = Style(color="#ffffff", bgcolor="#0178d4")
    assert readable(good, ColorSystem.TRUECOLOR) is good
    faint = Style(color="#4eb37a", bgcolor="#3a6e50", bold=True)
    fixed = readable(faint, ColorSystem.TRUECOLOR)
    fg, bg = style_rgb(fixed.color), style_rgb(fixed.bgcolor, foreground=False)
    assert fg is not None and bg is not None
    assert contrast_ratio(fg, bg) >= MINIMUM and fixed.bold
    for mode in MODES:
        again = readable(faint, mode)
        fg = style_rgb(again.color)
        assert fg is not None and bg is not None
        assert contrast_ratio(shown_rgb(fg, mode), shown_rgb(bg, mode)) >= MINIMUM
    no_background = Style(color="#4eb37a")
    assert readable(no_background, ColorSystem.STANDARD) is no_background
