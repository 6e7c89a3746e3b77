"""`rostui launch [PACKAGE] FILE [ARG:=VALUE]...`: run roslaunch XML files (like `roslaunch`)."""

from __future__ import annotations

from typing import List, Optional

import typer

from rostui.cli.common import examples

LAUNCH_CONTEXT = {
    "help_option_names": ["-h", "--help"],
    "allow_extra_args": True,
    "ignore_unknown_options": True,
}


def launch_command(
    ctx: typer.Context,
    arguments: Optional[List[str]] = typer.Argument(
        None, metavar="[PACKAGE] FILE [ARG:=VALUE]...",
        help="A launch file (a path, or a file name found below PACKAGE), then ARG:=VALUE for its args."),
    nodes: bool = typer.Option(False, "--nodes", help="Print the names of the nodes the files would start."),
    node_args: Optional[str] = typer.Option(None, "--args", metavar="NODE",
                                            help="Print the command line that would start NODE."),
    dump_params: bool = typer.Option(False, "--dump-params", help="Print the params the files would set, as YAML."),
    files: bool = typer.Option(False, "--files", help="Print every launch file the files read."),
    ros_args: bool = typer.Option(False, "--ros-args", help="Print the args the launch file takes."),
    port: Optional[int] = typer.Option(None, "-p", "--port", metavar="PORT", help="Master port (when a master must be started)."),
    screen: bool = typer.Option(False, "--screen", help="Every node's output to the screen."),
    verbose: bool = typer.Option(False, "-v", help="Print what is loaded and started."),
    wait: bool = typer.Option(False, "--wait", help="Wait for a master instead of starting one."),
    sigint_timeout: float = typer.Option(15.0, "--sigint-timeout", metavar="SECONDS",
                                         help="Seconds a node gets after SIGINT before SIGTERM."),
    sigterm_timeout: float = typer.Option(2.0, "--sigterm-timeout", metavar="SECONDS",
                                          help="Seconds a node gets after SIGTERM before SIGKILL."),
    strict: bool = typer.Option(False, "--strict", help="Unknown elements and attributes are errors, "
                                                        "not warnings (one FILE:LINE line each)."),
    tui: bool = typer.Option(False, "--tui", help="Run the launch inside a live monitor of its nodes "
                                                  "(state, pid, CPU, memory, restarts, output; start/stop/restart)."),
    child: Optional[str] = typer.Option(None, "-c", "--child", metavar="NAME",
                                        help="Run as child NAME of a parent launcher on another machine "
                                             "(roslaunch's remote protocol; needs -u and --run_id)."),
    server_uri: Optional[str] = typer.Option(None, "-u", "--server_uri", metavar="URI",
                                             help="The parent launcher's XML-RPC URI (with --child)."),
    run_id: Optional[str] = typer.Option(None, "--run_id", metavar="RUN_ID",
                                         help="The parent's run id (with --child)."),
) -> None:
    """Start the nodes of a launch file (like `roslaunch`).

    FILE is a path, or a file name found below package PACKAGE; ARG:=VALUE
    sets the file's arg ARG.  A master (with rosout) starts when none answers
    at ROS_MASTER_URI; Ctrl-C stops every node (SIGINT, then SIGTERM, then
    SIGKILL).

    --tui shows the nodes live (keys: s start, k stop, r restart, l launcher's output, f follow, q quit).

    `rostui launch check [PACKAGE] FILE` reports, one FILE:LINE line each,
    unknown elements and attributes, unknown machines and missing executables.
    """
    import os
    import sys

    from rostui.launch import inspect
    from rostui.launch.errors import LaunchError
    from rostui.launch.files import resolve_request

    words: List[str] = [*(arguments or []), *ctx.args]
    checking = bool(words) and words[0] == "check"
    if checking:
        words = words[1:]
    unknown = [w for w in words if w.startswith("-") and ":=" not in w]
    if unknown:
        print(f"rostui launch: unknown option {unknown[0]}", file=sys.stderr)
        raise typer.Exit(2)
    modes = [m for m in (nodes, node_args is not None, ros_args) if m]
    if len(modes) > 1:
        print("rostui launch: only one of --nodes, --args, --ros-args may be given", file=sys.stderr)
        raise typer.Exit(2)
    if tui and (modes or dump_params or files):
        print("rostui launch: --tui runs a launch; it cannot be combined with --nodes, --args, --dump-params, "
              "--files or --ros-args", file=sys.stderr)
        raise typer.Exit(2)
    if checking and (modes or dump_params or files or tui):
        print("rostui launch: check reports problems; it cannot be combined with --nodes, --args, --dump-params, "
              "--files, --ros-args or --tui", file=sys.stderr)
        raise typer.Exit(2)
    if child is not None or server_uri is not None or run_id is not None:
        if child is None or server_uri is None or run_id is None:
            print("rostui launch: --child, -u and --run_id go together", file=sys.stderr)
            raise typer.Exit(2)
        if words or modes or dump_params or files or tui:
            print("rostui launch: --child takes no launch files and no other mode: its parent sends the nodes",
                  file=sys.stderr)
            raise typer.Exit(2)
        from rostui.launch.remote_child import run_child
        from rostui.launch.supervisor import SupervisorOptions

        options = SupervisorOptions(screen=screen, verbose=verbose, sigint_timeout=sigint_timeout,
                                    sigterm_timeout=sigterm_timeout)
        raise typer.Exit(run_child(child, server_uri, run_id, options))
    if tui:
        from rostui.apps.terminal import terminal_missing

        if terminal_missing("rostui launch --tui", "run without --tui to launch without the monitor"):
            raise typer.Exit(1)
    try:
        request = resolve_request(words)
        request.strict = strict
        if checking:
            from rostui.launch.check import check_request

            problems = check_request(request)
            for line in problems:
                print(f"rostui launch: {line}", file=sys.stderr)
            raise typer.Exit(1 if problems else 0)
        if node_args is not None:
            print(inspect.node_args_line(request, node_args, inspect.default_master_uri()))
        elif nodes:
            listing = inspect.node_list(request)
            print(listing)
        elif dump_params:
            sys.stdout.write(inspect.dump_params(request) + "\n")
        elif files:
            print("\n".join(inspect.file_list(request)))
        elif ros_args:
            print(inspect.args_doc(request))
        elif tui:
            from rostui.launch.supervisor import SupervisorOptions, keep_quiet, load_supervisor

            options = SupervisorOptions(screen=screen, verbose=verbose, wait=wait, port=port,
                                        sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout,
                                        capture=True, handle_signals=False, stay_when_all_ended=True)
            supervisor = load_supervisor(request, options, reporter=keep_quiet)
            from rostui.apps.launchmon.app import run_app

            title = " ".join(os.path.basename(w) for w in words if ":=" not in w)
            raise typer.Exit(run_app(supervisor, title))
        else:
            from rostui.launch.supervisor import SupervisorOptions, run_launch

            options = SupervisorOptions(screen=screen, verbose=verbose, wait=wait, port=port,
                                        sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout)
            raise typer.Exit(run_launch(request, options))
    except LaunchError as exc:
        for line in str(exc).splitlines():
            print(f"rostui launch: {line}", file=sys.stderr)
        raise typer.Exit(1)


LAUNCH_EXAMPLES = examples(
    ("a launch file of a package; Ctrl-C stops its nodes (chapter 6)", "rostui launch agitr example.launch"),
    ("set the file's arg use_sim3", "rostui launch agitr triplesim.launch use_sim3:=1"),
    ("a file by its path, every node's output on the terminal", "rostui launch --screen ./my.launch"),
    ("the nodes in a live monitor (start, stop, restart, output)", "rostui launch --tui agitr doublesim.launch"),
    ("report unknown elements/attributes, machines and executables", "rostui launch check ./my.launch"),
)


def register(app: typer.Typer) -> None:
    """Add the command to the rostui app."""
    app.command("launch", context_settings=LAUNCH_CONTEXT, epilog=LAUNCH_EXAMPLES)(launch_command)
