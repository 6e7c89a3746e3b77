"""Status bars that wrap between their parts, never inside one."""

from __future__ import annotations

from collections.abc import Sequence

from rich.cells import cell_len

__all__ = ["join_parts"]

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
