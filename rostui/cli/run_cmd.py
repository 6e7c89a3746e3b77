"""`rostui run PACKAGE EXECUTABLE [ARGS]...`: run an executable of a package (like `rosrun`)."""

from __future__ import annotations

from typing import List, Optional

import typer

from rostui.cli.complete import complete_executables, complete_packages

RUN_CONTEXT = {
    "help_option_names": ["-h", "--help"],
    "allow_extra_args": True,
    "ignore_unknown_options": True,
    "allow_interspersed_args": False,
}


def run_command(
    ctx: typer.Context,
    package: str = typer.Argument(..., metavar="PACKAGE", help="Package holding the executable.", autocompletion=complete_packages),
    executable: str = typer.Argument(..., metavar="EXECUTABLE", help="Executable file name (or a path inside the package).",
                                     autocompletion=complete_executables),
    arguments: Optional[List[str]] = typer.Argument(
        None, metavar="[ARGS]...", help="Passed to the program as they are: name:=value, _param:=value, options."),
    prefix: Optional[str] = typer.Option(None, "--prefix", "-p", metavar="COMMAND",
                                         help="Command to put in front of the executable (e.g. 'gdb --args')."),
) -> None:
    """Run EXECUTABLE of PACKAGE with every further argument passed through (like `rosrun`).

    Remappings (`name:=value`), `__name:=`, `_param:=` and options such as `-x`
    reach the program untouched; the program replaces this process.
    """
    import sys

    from rostui.tools.run import RunError, choose_interactively, exec_argv, resolve

    args: List[str] = [*(arguments or []), *ctx.args]
    try:
        argv = resolve(package, executable, args, prefix=prefix, choose=choose_interactively)
    except RunError as exc:
        for line in exc.lines:
            print(line, file=sys.stderr)
        raise typer.Exit(exc.code)
    try:
        exec_argv(argv)
    except OSError as exc:
        print(f"[rosrun] Cannot run {argv[0]}: {exc.strerror or exc}", file=sys.stderr)
        raise typer.Exit(126)


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("run", context_settings=RUN_CONTEXT)(run_command)
