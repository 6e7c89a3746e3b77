"""`rostui wtf`: check a ROS system for common problems (like `roswtf`)."""

from __future__ import annotations

import typer


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
