"""`rostui wtf`: check a ROS system for common problems (like `roswtf`)."""

from __future__ import annotations

import typer

from rostui.cli.common import JSON_OPTION_HELP


def wtf_command(
    timeout: float = typer.Option(1.0, "--timeout", "-t", metavar="SECONDS", help="Seconds each node may take to answer."),
    as_json: bool = typer.Option(False, "--json", help=JSON_OPTION_HELP),
) -> None:
    """Check environment, master, nodes, topics and log size; one line per finding (like `roswtf`).

    Exit status 1 when an ERROR was found; warnings alone exit 0.
    """
    import sys

    from rostui.cli.common import print_json
    from rostui.core.log.console import color_wanted
    from rostui.tools.wtf import format_finding, run_checks, summary_line

    report = run_checks(timeout=timeout)
    if as_json:
        print_json(report.as_json())
    else:
        color = color_wanted(sys.stdout)
        for finding in report.findings:
            print(format_finding(finding, color))
        print(summary_line(report))
    raise typer.Exit(1 if report.errors else 0)


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("wtf")(wtf_command)
