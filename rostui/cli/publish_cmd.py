"""`rostui publish`: rqt_publisher in the terminal: a form of a message's fields, sent once or at a rate."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from rostui.cli.common import examples
from rostui.cli.complete import complete_msg_types, complete_topics


def publish_command(
    topic: str = typer.Argument("", metavar="[TOPIC]", help="Topic to publish on.", autocompletion=complete_topics),
    msg_type: str = typer.Argument("", metavar="[TYPE]", help="Message type (pkg/Type); the topic's when left out.",
                                   autocompletion=complete_msg_types),
    rate: Optional[float] = typer.Option(None, "--rate", "-r", metavar="HZ",
                                         help="Rate for ctrl+r (publishing repeatedly)."),
    form: Optional[Path] = typer.Option(None, "--form", "-f", metavar="FILE",
                                        help="A form saved with ctrl+w: opened if it exists, written by ctrl+w."),
) -> None:
    """Publish a message from a form of its fields (like rqt_publisher).

    Each field is an expression: 1.5, [1, 2], 'text', now, and per message
    i (the message's number, 1 first) and t (seconds since the first), as in
    sin(t). Enter edits a field, left/right move a number's slider, ctrl+s
    publishes one message (latched), ctrl+r publishes at the rate until
    pressed again. Nothing is published before that.
    """
    from rostui.cli.common import fail
    from rostui.cli.form_options import checked_form

    if rate is not None and not (rate > 0 and rate != float("inf")):
        fail(f"ERROR: --rate must be a positive number of Hz, not {rate:g}")
    if msg_type:
        from rostui.models.monitor.publish import PublishError, message_template

        try:
            message_template(msg_type)
        except PublishError as exc:
            fail(f"ERROR: {exc}")
    path = checked_form("publish", form)
    from rostui.apps.form.app import run_app

    raise typer.Exit(run_app("publish", name=topic, type_name=msg_type, rate=rate, form_path=path))


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("publish", context_settings={"help_option_names": ["-h", "--help"]}, epilog=examples(
        ("a form for a turtle's velocity", "rostui publish /turtle1/cmd_vel geometry_msgs/Twist"),
        ("at 10 Hz once ctrl+r is pressed", "rostui publish /turtle1/cmd_vel -r 10"),
        ("a form saved earlier with ctrl+w", "rostui publish --form drive.form.yaml"),
    ))(publish_command)
