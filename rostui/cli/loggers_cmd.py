"""`rostui loggers`: rqt_logger_level in the terminal; with arguments, list or set levels without the app."""

from __future__ import annotations

import sys
from typing import Optional

import typer


def loggers_command(
    node: Optional[str] = typer.Argument(None, metavar="[NODE]", help="Print this node's loggers and levels instead of opening "
                                                    "the app."),
    logger: Optional[str] = typer.Argument(None, metavar="[LOGGER]", help="With NODE and LEVEL: the logger to set (e.g. ros.agitr)."),
    level: Optional[str] = typer.Argument(None, metavar="[LEVEL]", help="DEBUG, INFO, WARN, ERROR or FATAL (any case)."),
    timeout: float = typer.Option(3.0, "--timeout", metavar="SECONDS", help="Seconds to wait for the master and each node."),
) -> None:
    """Show and set the logger levels of running nodes (like rqt_logger_level).

    Without arguments, opens the app: nodes that serve get_loggers on the left,
    the selected node's loggers in the middle, levels on the right; d/i/w/e/f
    or Enter on a level sets it.  `rostui loggers NODE` prints NODE's loggers;
    `rostui loggers NODE LOGGER LEVEL` sets one.
    """
    from rostui.cli.common import fail

    if timeout <= 0:
        fail(f"ERROR: --timeout must be positive, got {timeout:g}")
    if node is None:
        from rostui.apps.loggers.app import run_app

        raise typer.Exit(run_app(timeout=timeout))
    if logger is not None and level is None:
        fail(f"ERROR: rostui loggers {node} {logger}: give a LEVEL too (DEBUG, INFO, WARN, ERROR or FATAL)")
    from rostui.models import loggers as tools

    target = tools.resolve_node_name(node)
    try:
        if logger is None:
            sys.stdout.write(tools.format_loggers(tools.fetch_loggers(target, timeout=timeout)))
        else:
            assert level is not None
            tools.change_level(target, logger, level, timeout=timeout)
    except tools.LOGGER_ERRORS + (ValueError,) as exc:
        fail(f"ERROR: {exc}")


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("loggers", context_settings={"help_option_names": ["-h", "--help"]})(loggers_command)
