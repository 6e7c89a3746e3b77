"""`rostui python SCRIPT [ARGS]...` and `rostui shell-env`: run unmodified ROS 1 Python scripts."""

from __future__ import annotations

from typing import TYPE_CHECKING, List, Optional

import typer

if TYPE_CHECKING:
    from rostui.compat.launcher import Plan

PYTHON_CONTEXT = {
    "help_option_names": ["-h", "--help"],
    "allow_extra_args": True,
    "ignore_unknown_options": True,
    "allow_interspersed_args": False,
}


def mode_name(real_ros: bool, use_rostui: bool, who: str = "rostui python") -> str:
    """The :class:`~rostui.compat.choice.Mode` value --real-ros / --rostui ask for; exit 2 for both."""
    if real_ros and use_rostui:
        import sys

        print(f"{who}: --real-ros and --rostui exclude each other", file=sys.stderr)
        raise typer.Exit(2)
    return "real" if real_ros else "rostui" if use_rostui else "auto"


def python_command(
    ctx: typer.Context,
    script: Optional[str] = typer.Argument(None, metavar="SCRIPT", help="The Python script to run."),
    arguments: Optional[List[str]] = typer.Argument(
        None, metavar="[ARGS]...", help="The script's own arguments, untouched (name:=value, __name:=x, options)."),
    which: bool = typer.Option(False, "--which", help="Say which ROS a script would get, and exit."),
    real_ros: bool = typer.Option(False, "--real-ros", help="Give the script the real ROS installed, not rostui's."),
    use_rostui: bool = typer.Option(False, "--rostui",
                                    help="Give the script rostui's modules even if a real ROS is installed."),
) -> None:
    """Run SCRIPT with rostui's genpy, roslib, rosbag and message modules (PACKAGE.msg, PACKAGE.srv) on its import path.

    The script replaces this process in the same Python, so its argv, exit status
    and signals are its own. Where a real ROS is importable the script gets it
    (one line on stderr says so) unless --rostui is given.
    """
    import os
    import sys

    from rostui.compat.choice import Mode, choose
    from rostui.compat.launcher import plan

    mode = Mode(mode_name(real_ros, use_rostui))
    if which:
        print(choose(mode, sys.path).describe())
        return
    if script is None:
        print("rostui python: give the SCRIPT to run (or --which)", file=sys.stderr)
        raise typer.Exit(2)
    run_script(plan(mode, script, [*(arguments or []), *ctx.args], os.environ), "rostui python")


def run_script(how: "Plan", who: str) -> None:
    """Print *how*'s notice, then replace this process with its command; *who* names the command in errors."""
    from rostui.cli.python_fast import exec_plan

    raise typer.Exit(exec_plan(how, who))


def shell_env_command(
    real_ros: bool = typer.Option(False, "--real-ros", help="Choose the real ROS installed, not rostui's."),
    use_rostui: bool = typer.Option(False, "--rostui", help="Choose rostui's modules even if a real ROS is installed."),
) -> None:
    """Print `export` lines that give a plain `python3 script.py` rostui's ROS modules (eval them)."""
    import os
    import shlex

    from rostui.compat.choice import ENV_MODE, pythonpath_for

    print(f"export PYTHONPATH={shlex.quote(pythonpath_for(os.environ.get('PYTHONPATH')))}")
    print(f"export {ENV_MODE}={mode_name(real_ros, use_rostui)}")


def register(app: typer.Typer) -> None:
    """Add the commands to the rostui app."""
    app.command("python", context_settings=PYTHON_CONTEXT)(python_command)
    app.command("shell-env")(shell_env_command)
