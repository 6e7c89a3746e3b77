"""`rostui call`: rqt_service_caller in the terminal: a form of a service's request, its response shown."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from rostui.cli.common import examples
from rostui.cli.complete import complete_services


def call_command(
    service: str = typer.Argument("", metavar="[SERVICE]", help="Service to call.",
                                  autocompletion=complete_services),
    form: Optional[Path] = typer.Option(None, "--form", "-f", metavar="FILE",
                                        help="A form saved with ctrl+w: opened if it exists, written by ctrl+w."),
) -> None:
    """Call a service from a form of its request (like rqt_service_caller).

    The service's type is asked of the service itself. Each field is an
    expression (1.5, [1, 2], 'text', now, i: the call's number); Enter
    edits a field, left/right move a number's slider, ctrl+s calls the
    service and shows its response. Nothing is called before that.
    """
    from rostui.cli.form_options import checked_form

    path = checked_form("call", form)
    from rostui.apps.form.app import run_app

    raise typer.Exit(run_app("call", name=service, form_path=path))


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("call", context_settings={"help_option_names": ["-h", "--help"]}, epilog=examples(
        ("a form for turtlesim's spawn", "rostui call /spawn"),
        ("a form saved earlier with ctrl+w", "rostui call --form spawn.form.yaml"),
    ))(call_command)
