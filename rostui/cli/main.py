"""The `rostui` command: a Typer app; each command group lives in its own module.

Every ``rostui/cli/<group>_cmd.py`` exposes ``register(app)``; its command
functions import their work lazily, so commands that only talk to the master
start fast and never import Textual.
"""

from __future__ import annotations

import typer

from rostui.cli import (
    bag_cmd, clean_cmd, console_cmd, graph_cmd, launch_cmd, loggers_cmd, monitor_cmd, msg_cmd, node_cmd, param_cmd,
    pkg_cmd, python_cmd, run_cmd, serve_cmd, service_cmd, tf_cmd, topic_cmd, turtlesim_cmd, view_cmd,
    wtf_cmd,
)
from rostui.cli.help_text import reflow_commands

CONTEXT = {"help_option_names": ["-h", "--help"]}

app = typer.Typer(
    name="rostui",
    help="The ROS 1 developer toolbox for the terminal.",
    no_args_is_help=True,
    add_completion=True,
    context_settings=CONTEXT,
)


def _print_version(value: bool) -> None:
    if value:
        from rostui import __version__

        typer.echo(f"rostui {__version__}")
        raise typer.Exit()


@app.callback()
def root(
    version: bool = typer.Option(False, "--version", callback=_print_version, is_eager=True,
                                 help="Print rostui's version and exit."),
) -> None:
    """rostui: roscore, rostopic, rosnode, rosservice, rosparam and friends, in one terminal tool."""


@app.command("core")
def core_command(
    port: int = typer.Option(11311, "-p", "--port", metavar="PORT", help="Port the master listens on."),
) -> None:
    """Start a ROS master, parameter server and rosout (like `roscore`)."""
    from rostui.cli.core_cmd import run_core

    raise typer.Exit(run_core(port))


for _module in (run_cmd, node_cmd, topic_cmd, msg_cmd, service_cmd, param_cmd, pkg_cmd, wtf_cmd, clean_cmd,
                turtlesim_cmd, graph_cmd, console_cmd, loggers_cmd, launch_cmd, bag_cmd, monitor_cmd, serve_cmd,
                python_cmd, tf_cmd, view_cmd):
    _module.register(app)
reflow_commands(app)


def main() -> None:
    """Console-script entry point: a bare negative number is refused with one line before Typer parses; a
    Ctrl-C that surfaced as another error (see :func:`interrupted`) exits 130 without a traceback."""
    import sys

    from rostui.cli.common import interrupted
    from rostui.cli.negative import looks_negative, refuse_bare_negatives

    if any(looks_negative(word) for word in sys.argv[1:]):
        refuse_bare_negatives(typer.main.get_command(app), sys.argv[1:])
    try:
        app()
    except Exception as exc:
        if not interrupted(exc):
            raise
        raise SystemExit(130) from None  # Ctrl-C during a lazy import: no traceback, the shell's code
