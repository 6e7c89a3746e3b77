"""`rostui reconfigure`: rqt_reconfigure in the terminal."""

from __future__ import annotations

from typing import Optional

import typer


def reconfigure_command(
    node: Optional[str] = typer.Argument(None, metavar="[NODE]", help="The server to show first (its node's name)."),
) -> None:
    """Change running nodes' parameters live (like rqt_reconfigure).

    Left, every reconfigure server on the master; right, the selected one's
    groups and parameters with their live values, ranges, enums and
    descriptions. ←/→ step a number (shift: ten steps), space flips a bool or
    an enum, Enter edits a value, d sets the default; each change is sent at
    once and the server's answer is shown. `rostui dynparam` does the same
    from the command line.
    """
    from rostui.apps.reconfigure.app import run_app
    from rostui.tools.node import script_resolve

    raise typer.Exit(run_app(script_resolve(node) if node else None))


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("reconfigure", context_settings={"help_option_names": ["-h", "--help"]})(reconfigure_command)
