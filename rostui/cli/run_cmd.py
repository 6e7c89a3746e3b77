"""`rostui run PKG EXE [args...]`: run an executable of a package (like `rosrun`)."""

from __future__ import annotations

import typer


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
