"""`rostui core`: a master, parameter server and rosout, as `roscore` starts them (the work is in core_run)."""

from __future__ import annotations

import typer


def core_command(
    port: int = typer.Option(11311, "-p", "--port", metavar="PORT", help="Port the master listens on."),
) -> None:
    """Start a ROS master, parameter server and rosout (like `roscore`)."""
    from rostui.cli.core_run import run_core

    raise typer.Exit(run_core(port))


def register(app: typer.Typer) -> None:
    """Add ``rostui core``."""
    app.command("core")(core_command)
