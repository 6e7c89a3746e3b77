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


def main() -> None:
    """Console-script entry point."""
    app()
