"""The three colour modes a terminal may have, forced the way a terminal sets them, and what it then shows."""

from __future__ import annotations

import pytest
from rich.color import Color, ColorSystem
from rich.terminal_theme import DEFAULT_TERMINAL_THEME

from rostui.models.contrast import RGB

#: How each colour mode is forced (TERM, COLORTERM) and the name the app's console then reports.
MODES = {
    ColorSystem.STANDARD: ("xterm", None, "standard"),
    ColorSystem.EIGHT_BIT: ("xterm-256color", None, "256"),
    ColorSystem.TRUECOLOR: ("xterm-256color", "truecolor", "truecolor"),
}


def force_mode(monkeypatch: pytest.MonkeyPatch, system: ColorSystem) -> str:
    """Make the next app's console detect ``system`` as a terminal would; return the name it will report."""
    term, colorterm, name = MODES[system]
    monkeypatch.setenv("TERM", term)
    if colorterm is None:
        monkeypatch.delenv("COLORTERM", raising=False)
    else:
        monkeypatch.setenv("COLORTERM", colorterm)
    monkeypatch.delenv("NO_COLOR", raising=False)
    return name


def shown(color: Color | None, system: ColorSystem, foreground: bool) -> RGB | None:
    """What a terminal in ``system`` shows for a rendered Rich colour: Rich reduces it, the default theme paints it."""
    if color is None or color.is_default:
        return None
    triplet = color.downgrade(system).get_truecolor(DEFAULT_TERMINAL_THEME, foreground)
    return triplet.red, triplet.green, triplet.blue
