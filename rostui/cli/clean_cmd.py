"""`rostui clean check|purge`: rosclean's commands over rostui.core.log.clean."""

from __future__ import annotations

import sys

import typer


def run_check() -> int:
    """Print ``<size> ROS node logs`` for the log directory (nothing when it does not exist)."""
    from rostui.core.log import clean

    for line in clean.check_lines():
        print(line)
    return 0


def _ask() -> bool:
    """Read answers until y or n; end of input counts as no."""
    while True:
        answer = sys.stdin.readline()
        if not answer:
            return False
        answer = answer.strip().lower()
        if answer in ("y", "n"):
            return answer == "y"


def run_purge(yes: bool, size_mb: int | None = None) -> int:
    """Remove old runs from the log directory, keeping the current one; 1 on refusal or failure."""
    from rostui.core.log import clean

    limit = None if size_mb is None else size_mb * 1024 * 1024
    plan = clean.plan_purge(size_limit=limit)
    print(f"Purging {clean.LOG_LABEL}.")
    for kept in plan.kept:
        print(f"Keeping the current run [{kept}].")
    if not plan.targets:
        if limit is not None and plan.size_before:
            print(f"Directory size of {clean.LOG_LABEL} is {plan.size_before // 1048576} MB, "
                  f"already at most {size_mb} MB.")
        else:
            print(f"Nothing to purge in [{plan.root}].")
        return 0
    if not yes:
        if not sys.stdin or not sys.stdin.isatty():
            print("rostui clean purge: stdin is not a terminal, cannot ask for confirmation; "
                  "pass -y to purge without asking", file=sys.stderr)
            return 1
        print(clean.confirmation_text(plan), flush=True)
        if not _ask():
            print("Nothing deleted.")
            return 0
    result = clean.execute_purge(plan)
    for path, reason in result.failed:
        print(f"rostui clean purge: cannot remove {path}: {reason}", file=sys.stderr)
    print(f"Freed {clean.human_size(result.freed)} from {clean.LOG_LABEL} "
          f"({len(result.removed)} of {len(plan.targets)} entries removed).")
    return 1 if result.failed else 0


clean_app = typer.Typer(name="clean", help="Check and purge ROS log files (like `rosclean`).",
                        no_args_is_help=True, context_settings={"help_option_names": ["-h", "--help"]})


@clean_app.command("check")
def clean_check_command() -> None:
    """Print the disk usage of the ROS log directory (like `rosclean check`)."""
    raise typer.Exit(run_check())


@clean_app.command("purge")
def clean_purge_command(
    yes: bool = typer.Option(False, "-y", "--yes", help="Do not ask for confirmation."),
    size: int | None = typer.Option(None, "--size", metavar="MB",
                                    help="Remove oldest logs until at most this many MB remain."),
) -> None:
    """Delete old ROS logs, keeping the current run (like `rosclean purge`)."""
    raise typer.Exit(run_purge(yes, size))


def register(app: typer.Typer) -> None:
    """Add ``rostui clean check|purge``."""
    app.add_typer(clean_app, name="clean")
