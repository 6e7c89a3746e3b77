"""`rostui msg`: Message types: show, list, md5, package (like `rosmsg`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

msg_app = typer.Typer(name="msg", help="Message types: show, list, md5, package (like `rosmsg`).", no_args_is_help=True, context_settings=CONTEXT)


srv_app = typer.Typer(name="srv", help="Service types: show, list, md5, package (like `rossrv`).",
                      no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui msg ...`` and ``rostui srv ...``."""
    app.add_typer(msg_app, name="msg")
    app.add_typer(srv_app, name="srv")
