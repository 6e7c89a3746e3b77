"""`rostui param`: Parameters: list, get, set, delete, dump, load (like `rosparam`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

param_app = typer.Typer(name="param", help="Parameters: list, get, set, delete, dump, load (like `rosparam`).", no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui param ...``."""
    app.add_typer(param_app, name="param")
