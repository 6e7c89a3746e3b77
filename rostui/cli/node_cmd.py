"""`rostui node`: Nodes: list, info, kill, cleanup, ping (like `rosnode`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

node_app = typer.Typer(name="node", help="Nodes: list, info, kill, cleanup, ping (like `rosnode`).", no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui node ...``."""
    app.add_typer(node_app, name="node")
