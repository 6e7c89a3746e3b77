"""`rostui monitor [TOPIC|FIELD...]`: every topic live in one table (rqt_topic + rostopic echo/hz/bw + rqt_plot).

Arguments are topics to expand or, as rqt_plot takes them, numeric fields
to plot: ``/turtle1/pose/x``, ``/turtle1/pose/x:y:theta``,
``/turtle1/cmd_vel/linear/x`` (or ``linear.x``).  Which is which is known
only once the master lists its topics, so the app decides.

Textual is imported only when the app opens.  Like `rostui graph`, no master
at ROS_MASTER_URI is not an error: the app opens, says so in red and keeps
trying until one answers.  A bad topic name or option is one line on stderr
and exit status 1 before any screen opens.
"""

from __future__ import annotations

import re
from typing import List

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}
#: A field name after rqt_plot's ``:`` (``theta``, ``linear.x``, ``ranges[0]``).
FIELD = re.compile(r"[A-Za-z_]\w*(\[\d+\])*([./][A-Za-z_]\w*(\[\d+\])*)*")


def checked_argument(arg: str) -> str:
    """``arg`` (a topic, or a field as rqt_plot takes it) resolved like a topic; ValueError says what is wrong."""
    from rostui.core.names import InvalidNameError, validate_name
    from rostui.tools.topic.common import resolve_topic

    base, *more = arg.split(":")
    try:
        validate_name(re.sub(r"\[\d+\]", "", base).replace(".", "/"), "topic")
    except InvalidNameError as exc:
        raise ValueError(str(exc)) from None
    if not base.strip("/"):
        raise ValueError(f"{arg!r} is not a topic name")
    for name in more:
        if not FIELD.fullmatch(name):
            raise ValueError(f"{arg!r}: {name!r} after ':' is not a field name (as in /turtle1/pose/x:y:theta)")
    return ":".join([resolve_topic(base), *more])


def monitor_command(
    topics: List[str] = typer.Argument(
        None, metavar="[TOPIC|FIELD...]",
        help="Topics to open expanded (message trees), or numeric fields to plot as rqt_plot takes them: "
             "/turtle1/pose/x, /turtle1/pose/x:y:theta, /turtle1/cmd_vel/linear/x."),
    period: float = typer.Option(1.0, "--period", metavar="SECONDS", help="Seconds between master polls."),
) -> None:
    """Watch every topic live: type, publishers, subscribers, rate, bandwidth, message age (like rqt_topic).

    Only the topics on screen are subscribed.  Keys: / filter, s sort, S reverse,
    Enter expand a topic into its message tree (an image: open its view,
    as rostui view shows it; Esc back), Tab into the tree, f plot
    numeric fields, v show/hide the plot, + and - its time window, space
    pause it, p publish a message, x collapse, q quit.

    Example: rostui monitor /turtle1/pose/x:y:theta
    """
    from rostui.cli.common import fail

    if not period > 0:
        fail(f"ERROR: --period must be a positive number of seconds, not {period:g}")
    resolved = []
    for topic in topics or []:
        try:
            resolved.append(checked_argument(topic))
        except ValueError as exc:
            fail(f"ERROR: {exc}")
    from rostui.apps.monitor.app import run_app

    raise typer.Exit(run_app(resolved, period=period))


def register(app: typer.Typer) -> None:
    """Add ``rostui monitor``."""
    app.command("monitor", context_settings=CONTEXT)(monitor_command)
