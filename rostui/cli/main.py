"""The `rostui` command: a Typer app whose subcommands import their work lazily."""

from __future__ import annotations

import typer

app = typer.Typer(
    name="rostui",
    help="The ROS 1 developer toolbox for the terminal.",
    no_args_is_help=True,
    add_completion=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)


@app.callback()
def root() -> None:
    """rostui: roscore, rostopic, rosnode, rosservice, rosparam and friends, in one terminal tool."""


@app.command("core")
def core_command(
    port: int = typer.Option(11311, "-p", "--port", help="Port the master listens on."),
) -> None:
    """Start a ROS master, parameter server and rosout (like `roscore`)."""
    from rostui.cli.core_cmd import run_core

    raise typer.Exit(run_core(port))


clean_app = typer.Typer(
    name="clean", help="Check and purge ROS log files (like `rosclean`).", no_args_is_help=True,
    context_settings={"help_option_names": ["-h", "--help"]},
)
app.add_typer(clean_app, name="clean")


@clean_app.command("check")
def clean_check_command() -> None:
    """Print the disk usage of the ROS log directory (like `rosclean check`)."""
    from rostui.cli.clean_cmd import run_check

    raise typer.Exit(run_check())


@clean_app.command("purge")
def clean_purge_command(
    yes: bool = typer.Option(False, "-y", "--yes", help="Do not ask for confirmation."),
    size: int | None = typer.Option(None, "--size", help="Remove oldest logs until at most this many MB remain."),
) -> None:
    """Delete old ROS logs, keeping the current run (like `rosclean purge`)."""
    from rostui.cli.clean_cmd import run_purge

    raise typer.Exit(run_purge(yes, size))


def main() -> None:
    """Console-script entry point."""
    app()
