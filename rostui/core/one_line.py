"""Text of an error squeezed to one line of bounded length, for a status line or an ``ERROR:`` line."""

from __future__ import annotations

__all__ = ["one_line", "exception_line"]

#: Longest text said in one line; what is cut ends with an ellipsis.
LINE_LIMIT = 200


def one_line(text: str, limit: int | None = LINE_LIMIT) -> str:
    """``text`` with every run of whitespace (newlines too) as one space, cut to ``limit`` characters (None:
    whole)."""
    text = " ".join(str(text).split())
    if limit is None or len(text) <= limit:
        return text
    return text[: limit - 1] + "…"


def exception_line(exc: BaseException, limit: int | None = LINE_LIMIT) -> str:
    """What ``exc`` says, as :func:`one_line`."""
    return one_line(str(exc), limit)
