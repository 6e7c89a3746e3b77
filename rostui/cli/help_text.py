"""Help text that wraps at the terminal's width, not at the docstring's line ends.

Typer keeps every line break of a command's docstring after its first paragraph, so at 80 columns a
docstring line of 95 characters wraps once by width and again at its own end: sentences break in two
places.  :func:`reflow_commands` joins each paragraph's lines before Typer reads them, except for
paragraphs that are lists or tables (lines starting with ``-``, ``*``, spaces or Click's ``\\b``).
"""

from __future__ import annotations

from typing import Any

__all__ = ["reflow", "reflow_commands"]


def _keeps_lines(paragraph: str) -> bool:
    """Whether a paragraph's lines are meant as lines (a list, an indented block, Click's no-rewrap mark)."""
    lines = paragraph.splitlines()
    return paragraph.startswith("\b") or any(line[:1] in (" ", "-", "*", "\t") for line in lines[1:])


def reflow(text: str) -> str:
    """``text`` (a docstring) with each paragraph's lines joined by spaces; list-like paragraphs kept."""
    import textwrap

    lines = text.expandtabs().splitlines()
    body = textwrap.dedent("\n".join(lines[1:]))
    cleaned = "\n".join([lines[0].strip(), body]).strip() if lines else ""
    paragraphs = cleaned.split("\n\n")
    return "\n\n".join(p if _keeps_lines(p) else " ".join(line.strip() for line in p.splitlines())
                       for p in paragraphs)


def reflow_commands(app: Any) -> None:
    """Reflow the help of every command and group registered on the Typer ``app``, recursively."""
    for info in app.registered_commands:
        text = info.help or (info.callback.__doc__ if info.callback is not None else None)
        if text:
            info.help = reflow(text)
    for group in app.registered_groups:
        typer_app = group.typer_instance
        if typer_app is not None:
            reflow_commands(typer_app)
