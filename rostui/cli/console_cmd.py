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
        None, help="A rosout.log (written by ROS or rostui) to browse instead of the live /rosout_agg."),
    min_level: str = typer.Option(
        "debug", "--min-level", "-l", help="Hide messages below this level (debug, info, warn, error, fatal)."),
    max_messages: int = typer.Option(
        DEFAULT_MAX, "--max", "-n", help="Messages kept in memory; the oldest are dropped (and counted)."),
    node: List[str] = typer.Option(
        [], "--node", help="Show only messages from this node (repeatable)."),
    exclude_node: List[str] = typer.Option(
        [], "--exclude-node", help="Hide messages from this node (repeatable)."),
    search: str = typer.Option("", "--search", "-s", help="Show only messages containing this text."),
    regex: bool = typer.Option(False, "--regex", "-r", help="Treat --search as a regular expression."),
) -> None:
    """Browse ROS log messages: live from /rosout_agg, or from a rosout.log file.

    Keys: 1-5 show/hide DEBUG..FATAL, / search (r: regular expression), h highlight,
    n / x only / hide the selected message's node (N: all nodes), p pause, c clear,
    Enter details, s save the shown messages (rosout.log format), End or F follow, q quit.
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
