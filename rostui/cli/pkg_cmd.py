"""`rostui pkg`: Packages: list, find, ls (like `rospack` / `rosls`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

pkg_app = typer.Typer(name="pkg", help="Packages: list, find, ls (like `rospack` / `rosls`).", no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui pkg ...``."""
    app.add_typer(pkg_app, name="pkg")
