"""`rostui service`: Services: list, info, node, type, find, args, uri, call (like `rosservice`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

service_app = typer.Typer(name="service", help="Services: list, info, node, type, find, args, uri, call (like `rosservice`).", no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui service ...``."""
    app.add_typer(service_app, name="service")
