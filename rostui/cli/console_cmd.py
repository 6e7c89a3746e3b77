"""`rostui console [PATH]`: rqt_console in the terminal (live /rosout_agg or a rosout.log file).

Textual is imported only inside the command; an unreadable PATH or a bad
option is one line on stderr and exit status 1 before any screen opens.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import List, Optional

import typer

CONTEXT = {"help_option_names": ["-h", "--help"]}

#: Messages kept when --max is not given.
DEFAULT_MAX = 100_000

#: Files at least this big get a "reading..." line before the screen opens.
BIG_FILE_BYTES = 20_000_000


def console_command(
    path: Optional[Path] = typer.Argument(
        None, metavar="[PATH]",
        help="A rosout.log (written by ROS or rostui) to browse instead of the live /rosout_agg."),
    min_level: str = typer.Option(
        "debug", "--min-level", "-l", metavar="LEVEL",
        help="Keep only messages at or above LEVEL (debug, info, warn, error, fatal); the others are not stored."),
    max_messages: int = typer.Option(
        DEFAULT_MAX, "--max", "-n", metavar="N", help="Messages kept; the oldest are dropped and counted."),
    node: List[str] = typer.Option(
        [], "--node", metavar="NODE", help="Show only messages from NODE (repeatable)."),
    exclude_node: List[str] = typer.Option(
        [], "--exclude-node", metavar="NODE", help="Hide messages from NODE (repeatable)."),
    search: str = typer.Option(
        "", "--search", "-s", metavar="TEXT", help="Show only messages containing TEXT (any case)."),
    regex: bool = typer.Option(False, "--regex", "-r", help="TEXT is a regular expression."),
) -> None:
    """Browse ROS log messages like rqt_console: live from /rosout_agg, or from a rosout.log file.

    Keys: 1-5 levels, / search, r regex, h highlight, n/x/N nodes, p pause, c clear, q quit.

    Enter details, s save the shown messages (rosout.log format), Up leaves follow mode, End or F follows.
    """
    from rostui.cli.common import fail
    from rostui.core.log import Level
    from rostui.core.log.rosout_read import RosoutLogError, read_rosout_log

    try:
        level = Level.parse(min_level)
    except ValueError as exc:
        fail(f"ERROR: --min-level: {exc}")
    if max_messages < 1:
        fail(f"ERROR: --max must be at least 1, got {max_messages}")
    loaded = None
    if path is not None:
        _announce_big_file(path)
        try:
            loaded = read_rosout_log(path, min_level=level, keep=max_messages)
        except RosoutLogError as exc:
            fail(f"ERROR: {exc}")
    from rostui.apps.console.app import ConsoleOptions, run_app

    options = ConsoleOptions(min_level=level, max_messages=max_messages, include_nodes=tuple(node),
                             exclude_nodes=tuple(exclude_node), search=search, regex=regex)
    raise typer.Exit(run_app(options, loaded, log_name=str(path) if path is not None else None))


def _announce_big_file(path: Path) -> None:
    """Say on stderr that a big file is being read (100 MB, a full rotated rosout.log, takes seconds)."""
    try:
        size = path.stat().st_size
    except OSError:
        return
    if size >= BIG_FILE_BYTES and path.is_file():
        print(f"reading {path} ({size / 1e6:.0f} MB)...", file=sys.stderr, flush=True)


def register(app: typer.Typer) -> None:
    """Add ``rostui console``."""
    app.command("console", context_settings=CONTEXT)(console_command)
