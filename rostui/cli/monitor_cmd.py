"""`rostui monitor [TOPIC...]`: every topic live in one table (rqt_topic + rostopic echo/hz/bw + rqt_plot).

Textual is imported only when the app opens.  Like `rostui graph`, no master
at ROS_MASTER_URI is not an error: the app opens, says so in red and keeps
trying until one answers.  A bad topic name or option is one line on stderr
and exit status 1 before any screen opens.
"""

from __future__ import annotations

from typing import List

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}


def monitor_command(
    topics: List[str] = typer.Argument(None, metavar="[TOPIC...]", help="Topics to open expanded (message trees)."),
    period: float = typer.Option(1.0, "--period", metavar="SECONDS", help="Seconds between master polls."),
) -> None:
    """Watch every topic live: type, publishers, subscribers, rate, bandwidth, message age (like rqt_topic).

    Only the topics on screen are subscribed.  Keys: / filter, s sort, S reverse,
    Enter expand a topic into its message tree, Tab into the tree, f plot a
    numeric field, p publish a message, x collapse, q quit.
    """
    from rostui.cli.common import fail
    from rostui.core.names import InvalidNameError, validate_name
    from rostui.tools.topic.common import resolve_topic

    if not period > 0:
        fail(f"ERROR: --period must be a positive number of seconds, not {period:g}")
    resolved = []
    for topic in topics or []:
        try:
            validate_name(topic, "topic")
        except InvalidNameError as exc:
            fail(f"ERROR: {exc}")
        if not topic.strip("/"):
            fail(f"ERROR: {topic!r} is not a topic name")
        resolved.append(resolve_topic(topic))
    from rostui.apps.monitor.app import run_app

    raise typer.Exit(run_app(resolved, period=period))


def register(app: typer.Typer) -> None:
    """Add ``rostui monitor``."""
    app.command("monitor", context_settings=CONTEXT)(monitor_command)
