"""`rostui tf`: tf in the terminal: `tf echo SOURCE TARGET` (tf_echo) and `tf tree` (rqt_tf_tree)."""

from __future__ import annotations

from typing import Optional

import typer

from rostui.cli.common import examples

CONTEXT = {"help_option_names": ["-h", "--help"]}

tf_app = typer.Typer(name="tf", help="Transforms: echo one (like `rosrun tf tf_echo`), or show the tree of frames.",
                     no_args_is_help=True, context_settings=CONTEXT)


@tf_app.command("echo", epilog=examples(
    ("laser's pose in map, once a second", "rostui tf echo map laser"),
    ("ten times a second, nine decimals", "rostui tf echo map laser 10 --precision 9"),
))
def echo_command(
    source: str = typer.Argument(..., metavar="SOURCE", help="The frame the transform is expressed in."),
    target: str = typer.Argument(..., metavar="TARGET", help="The frame whose pose is printed."),
    echo_rate: Optional[float] = typer.Argument(None, metavar="[RATE]", help="Prints per second (as tf_echo's third "
                                                                             "argument)."),
    rate: Optional[float] = typer.Option(None, "--rate", "-r", metavar="HZ", help="Prints per second (default 1)."),
    precision: int = typer.Option(3, "--precision", "-p", metavar="DIGITS", help="Decimals printed (tf_echo: 3)."),
) -> None:
    """Print the transform from TARGET into SOURCE at a rate, as `rosrun tf tf_echo SOURCE TARGET`.

    Listens to /tf and /tf_static; each print is the latest transform the
    chain between the two frames allows.  Ctrl-C ends it.
    """
    import asyncio
    import sys

    from rostui.cli.common import fail, master_call, master_uri

    hz = rate if rate is not None else echo_rate if echo_rate is not None else 1.0
    if not hz > 0.0 or hz != hz:
        fail("Echo rate must be > 0.0")
    if not 0 <= precision <= 17:
        fail(f"ERROR: --precision must be between 0 and 17, got {precision}")
    master_call("/tf_echo", "getPid")
    from rostui.models.tf.echo import run_echo

    try:
        asyncio.run(run_echo(master_uri(), source, target, sys.stdout, rate=hz, precision=precision))
    except KeyboardInterrupt:
        raise typer.Exit(0) from None


@tf_app.command("tree")
def tree_command() -> None:
    """Show the frames of /tf and /tf_static as a tree (like rqt_tf_tree or `rosrun tf view_frames`).

    Each frame sits under its parent with the node that broadcasts it, its
    rate, the age of its newest stamp, or "static"; the frame under the
    cursor is spelled out below (in its parent and in its tree's root).
    The same view is `rostui view /tf`.
    """
    from rostui.apps.view.tf_tree_app import run_app

    raise typer.Exit(run_app())


def register(app: typer.Typer) -> None:
    """Add ``rostui tf ...``."""
    app.add_typer(tf_app, name="tf")
