"""Text bars: status bars that wrap between their parts, never inside one, and a value's bar in its range."""

from __future__ import annotations

from collections.abc import Sequence

from rich.cells import cell_len

__all__ = ["BAR_CELLS", "bar_text", "join_parts"]

BAR_CELLS = 10
"""How many cells wide a ranged number's bar is."""
_FULL, _EMPTY = "█", "░"

SEPARATOR = " │ "


def join_parts(parts: Sequence[str], width: int) -> str:
    """``parts`` joined by `` │ ``, a line break before each part that would cross ``width`` columns (0: none)."""
    lines: list[str] = []
    for part in parts:
        if lines and (width <= 0 or cell_len(lines[-1] + SEPARATOR + part) <= width):
            lines[-1] += SEPARATOR + part
        else:
            lines.append(part)
    return "\n".join(lines)


def bar_text(fraction: float) -> str:
    """A bar *fraction* (0 to 1, clamped) full, :data:`BAR_CELLS` cells wide."""
    filled = round(min(max(fraction, 0.0), 1.0) * BAR_CELLS)
    return _FULL * filled + _EMPTY * (BAR_CELLS - filled)
