"""`rostui topic`: Topics: list, info, type, find, echo, hz, bw, pub (like `rostopic`)."""

from __future__ import annotations

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

topic_app = typer.Typer(name="topic", help="Topics: list, info, type, find, echo, hz, bw, pub (like `rostopic`).", no_args_is_help=True, context_settings=CONTEXT)


def register(app: typer.Typer) -> None:
    """Add ``rostui topic ...``."""
    app.add_typer(topic_app, name="topic")
