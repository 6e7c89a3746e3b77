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
    real_ros: bool = typer.Option(False, "--real-ros",
                                  help="Run a Python script as rosrun would, with the real ROS installed."),
    use_rostui: bool = typer.Option(False, "--rostui",
                                    help="Give a Python script rostui's rospy and message modules even if a "
                                         "real ROS is installed."),
) -> None:
    """Run EXECUTABLE of PACKAGE with every further argument passed through (like `rosrun`).

    Remappings (`name:=value`), `__name:=`, `_param:=` and options such as `-x`
    reach the program untouched; the program replaces this process. A ROS
    Python script gets what `rostui python` gives it: rostui's rospy, genpy,
    roslib, rosbag and message modules, or the real ROS where one is installed.
    """
    import os
    import shlex
    import sys

    from rostui.cli.python_cmd import mode_name, run_script
    from rostui.compat.choice import Mode
    from rostui.compat.launcher import Plan, plan
    from rostui.tools.run import RunError, argv_for, choose_interactively, exec_argv, locate, ros_python_script

    mode = Mode(mode_name(real_ros, use_rostui, "rostui run"))
    args: List[str] = [*(arguments or []), *ctx.args]
    try:
        path = locate(package, executable, choose=choose_interactively)
    except RunError as exc:
        for line in exc.lines:
            print(line, file=sys.stderr)
        raise typer.Exit(exc.code)
    script = ros_python_script(path, os.environ.get("PATH"))
    if script is not None:
        how = plan(mode, str(path), args, os.environ, interpreter=script.interpreter)
        if prefix:
            how = Plan(shlex.split(prefix) + how.argv, how.env, how.notice)
        run_script(how, "rostui run")
        return
    argv = argv_for(path, args, prefix)
    try:
        exec_argv(argv)
    except OSError as exc:
        print(f"[rosrun] Cannot run {argv[0]}: {exc.strerror or exc}", file=sys.stderr)
        raise typer.Exit(126)


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("run", context_settings=RUN_CONTEXT)(run_command)
