"""`rostui diagnostics`: rqt_robot_monitor in the terminal, and with `--once` what rosdiagnostic prints."""

from __future__ import annotations

from typing import Optional

import typer

from rostui.cli.common import examples

FORMATS = ("tree", "rosdiagnostic")


def diagnostics_command(
    once: bool = typer.Option(False, "--once", help="Print the diagnostics once and exit (for scripts)."),
    level: Optional[str] = typer.Option(None, "--level", "-l", metavar="LEVEL",
                                        help="Show statuses at least this bad: ok, warn, error, stale or 0-3 "
                                             "(default: all; rosdiagnostic's format: warn)."),
    filter_text: str = typer.Option("", "--filter", metavar="REGEX",
                                    help="Only statuses whose name this expression matches (ignores case unless it "
                                         "holds a capital)."),
    topic: Optional[str] = typer.Option(None, "--topic", metavar="TOPIC",
                                        help="With --once: read this topic (default: /diagnostics_agg when an "
                                             "aggregator publishes it, else /diagnostics)."),
    detail: bool = typer.Option(False, "--detail", "-d", help="With --once: each status's hardware id and values."),
    output_format: str = typer.Option("tree", "--format", metavar="FORMAT",
                                      help="With --once: `tree` (every group under its parent) or `rosdiagnostic` "
                                           "(its leaves, the worst first, as rosdiagnostic prints them)."),
    nocolor: bool = typer.Option(False, "--nocolor", help="With --format rosdiagnostic: no colour codes."),
    wait: float = typer.Option(10.0, "--wait", metavar="SECONDS", help="With --once: how long to wait for news."),
) -> None:
    """Watch the robot's diagnostics (like rqt_robot_monitor and rqt_runtime_monitor).

    The aggregator's /diagnostics_agg as its tree, or /diagnostics as a flat
    list when no aggregator runs; each status coloured by level, stale when
    nothing came for 5 s, its key/values and history beside it. l cycles the
    least level shown, / filters by name. `--once` prints the picture once.
    """
    import re

    from rostui.cli.common import fail
    from rostui.models.diagnostics.levels import parse_level

    if output_format not in FORMATS:
        fail(f"unknown format {output_format!r}: choose tree or rosdiagnostic")
    try:
        least = parse_level(level) if level is not None else (1 if output_format == "rosdiagnostic" else 0)
    except ValueError as exc:
        fail(str(exc))
    if once:
        try:
            re.compile(filter_text)
        except re.error as exc:
            fail(f"--filter {filter_text!r} is not a regular expression: {exc}")
        if not wait > 0:
            fail("--wait must be more than 0 seconds")
        raise typer.Exit(_print_once(least, filter_text, topic, detail, output_format, not nocolor, wait))
    from rostui.apps.diagnostics.app import run_app

    raise typer.Exit(run_app(level=least, text=filter_text))


def _print_once(least: int, text: str, topic: str | None, detail: bool, output_format: str, color: bool,
                wait: float) -> int:
    """Print one picture of the diagnostics; the exit status."""
    import asyncio
    import time

    from rostui.cli.common import fail, master_call, master_uri
    from rostui.models.diagnostics.once import NothingHeard, read_once
    from rostui.models.diagnostics.source import DiagnosticsSource
    from rostui.models.diagnostics.store import FLAT
    from rostui.models.diagnostics.tree import Filter, flat_rows, format_rosdiagnostic, format_tree, tree_rows

    master_call("/rostui_diagnostics", "getPid")
    source = DiagnosticsSource(master_uri(), topics=(topic,) if topic else None)
    try:
        heard = asyncio.run(read_once(source, wait))
    except NothingHeard as exc:
        fail(str(exc))
    except KeyboardInterrupt:
        return 130
    store, only = source.store, Filter(least, text)
    table = store.table(heard)
    if output_format == "rosdiagnostic":
        print(format_rosdiagnostic(table, only, detail=detail, color=color))
        return 0
    now = time.time()
    rows = (flat_rows if heard == FLAT else tree_rows)(table, now, store.stale_after, only)
    print(format_tree(rows, values=detail) if rows else f"no status on {heard} matches")
    return 0


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("diagnostics", context_settings={"help_option_names": ["-h", "--help"]}, epilog=examples(
        ("the aggregator's tree, live", "rostui diagnostics"),
        ("only warnings and worse", "rostui diagnostics -l warn"),
        ("print it once, for a script", "rostui diagnostics --once"),
        ("as rosdiagnostic prints it", "rostui diagnostics --once --format rosdiagnostic --nocolor"),
    ))(diagnostics_command)
