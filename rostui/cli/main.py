"""The `rostui` command: a Typer app; each command group lives in its own module.

Every ``rostui/cli/<group>_cmd.py`` named in :data:`rostui.cli.registry.COMMAND_GROUPS`
exposes ``register(app)``; its command
functions import their work lazily, so commands that only talk to the master
start fast and never import Textual.
"""

from __future__ import annotations

import importlib

import typer

from rostui.cli.help_text import reflow_commands
from rostui.cli.registry import COMMAND_GROUPS

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


for _group in COMMAND_GROUPS:
    importlib.import_module(f"rostui.cli.{_group}_cmd").register(app)
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
