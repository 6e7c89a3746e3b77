"""`rostui node`: Nodes: list, info, kill, cleanup, ping, machine (like `rosnode`)."""

from __future__ import annotations

import sys
from typing import Callable, Iterable, List, Optional

import typer

from rostui.cli.common import JSON_OPTION_HELP as _JSON_HELP
from rostui.cli.common import master_caller
from rostui.cli.complete import complete_nodes

CONTEXT = {"help_option_names": ["-h", "--help"]}

node_app = typer.Typer(name="node", help="Nodes: list, info, kill, cleanup, ping, machine (like `rosnode`).", no_args_is_help=True, context_settings=CONTEXT)

CALLER = "/rosnode"


def _echo(text: str, err: bool = False) -> None:
    stream = sys.stderr if err else sys.stdout
    print(text, file=stream, flush=True)


def _hint(name: str, candidates: Callable[[], Iterable[str]]) -> None:
    """``did you mean …?`` on stderr when a registered node's name is close to ``name``."""
    from rostui.cli.common import suggestion

    line = suggestion(name, candidates)
    if line:
        _echo(line, err=True)


@node_app.command("list")
def list_command(
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Only nodes in this namespace."),
    uri: bool = typer.Option(False, "-u", help="List XML-RPC URIs."),
    all_: bool = typer.Option(False, "-a", "--all", help="List URIs and names."),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List active nodes (like `rosnode list`)."""
    from rostui.tools.node import filter_namespace, format_list, lookup_uris, script_resolve, system_state

    call = master_caller(CALLER)
    nodes = filter_namespace(system_state(call).nodes(), script_resolve(namespace) if namespace else None)
    uris = lookup_uris(call, nodes) if (uri or all_ or json_out) else None
    if json_out:
        from rostui.cli.common import print_json

        print_json([{"node": n, "uri": uris.get(n) if uris else None} for n in nodes])
        return
    print(format_list(nodes, uris, show_uri=uri, show_all=all_))


@node_app.command("info")
def info_command(
    nodes: List[str] = typer.Argument(..., metavar="NODE...", help="Node names.", autocompletion=complete_nodes),
    quiet: bool = typer.Option(False, "-q", "--quiet", help="Only registrations; do not contact the node."),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """Print a node's publications, subscriptions, services, pid and connections (like `rosnode info`)."""
    from rostui.tools.node import format_info, node_info, script_resolve, system_state

    call = master_caller(CALLER)
    infos = [node_info(call, script_resolve(n), quiet=quiet) for n in nodes]
    if json_out:
        from rostui.cli.common import print_json

        print_json([i.to_json() for i in infos] if len(infos) > 1 else infos[0].to_json())
        return
    failed = False
    for info in infos:
        text, error = format_info(info, quiet=quiet)
        sys.stdout.write(text)
        sys.stdout.flush()
        if error:
            _echo(error, err=True)
            if info.uri is not None:
                failed = True
            else:
                _hint(info.name, lambda: system_state(call).nodes())
    if failed:
        raise typer.Exit(1)


@node_app.command("ping")
def ping_command(
    node: Optional[str] = typer.Argument(None, metavar="NODE", help="Node to ping.", autocompletion=complete_nodes),
    count: Optional[int] = typer.Option(None, "-c", metavar="COUNT", help="Number of pings to send (not with --all)."),
    all_: bool = typer.Option(False, "-a", "--all", help="Ping all nodes once."),
) -> None:
    """Test connectivity to a node over XML-RPC (like `rosnode ping`)."""
    from rostui.cli.common import fail
    from rostui.tools.node import PING_TIMEOUT, PingError, lookup_uris, ping_node, script_resolve, system_state

    call = master_caller(CALLER)
    if all_:
        if count is not None:
            fail("ERROR: -c is not available with --all")
        nodes = system_state(call).nodes()
        _echo("Will ping the following nodes: \n" + "".join(f" * {n}\n" for n in nodes))
        uris = lookup_uris(call, nodes)
        dead = []
        for n in nodes:
            _echo(f"pinging {n} with a timeout of {PING_TIMEOUT:.1f}s")
            uri = uris.get(n)
            if uri is None:
                _echo(f"cannot ping [{n}]: unknown node", err=True)  # listed a moment ago: no hint
                continue
            try:
                ms = ping_node(uri)
                _echo(f"xmlrpc reply from {uri}\ttime={ms:f}ms")
            except PingError as exc:
                _echo(str(exc), err=True)
                dead.append(n)
        if dead:
            _echo("ERROR: The following nodes are unreachable:\n" + "\n".join(f" * {n}" for n in dead), err=True)
        return
    if node is None:
        fail("ERROR: please specify a node name (or -a to ping all nodes)")
    name = script_resolve(node)
    _echo(f"rosnode: node is [{name}]")
    uri = lookup_uris(call, [name]).get(name)
    if uri is None:
        _echo(f"cannot ping [{name}]: unknown node", err=True)
        _hint(name, lambda: system_state(call).nodes())
        return
    _echo(f"pinging {name} with a timeout of {PING_TIMEOUT:.1f}s")
    import time

    times: list[float] = []
    try:
        while count is None or len(times) < count:
            if times:
                time.sleep(1.0)
            try:
                ms = ping_node(uri)
            except PingError as exc:
                _echo(str(exc), err=True)
                break
            times.append(ms)
            _echo(f"xmlrpc reply from {uri}\ttime={ms:f}ms")
    except KeyboardInterrupt:
        pass
    if times:
        _echo(f"ping average: {sum(times) / len(times):f}ms")


@node_app.command("kill")
def kill_command(
    nodes: Optional[List[str]] = typer.Argument(None, metavar="[NODE]...", help="Nodes to kill.", autocompletion=complete_nodes),
    all_: bool = typer.Option(False, "-a", "--all", help="Kill all nodes."),
) -> None:
    """Ask nodes to shut down (like `rosnode kill`)."""
    from rostui.cli.common import fail
    from rostui.tools.node import kill_nodes, script_resolve, system_state

    call = master_caller(CALLER)
    if all_:
        targets = system_state(call).nodes()
    elif nodes:
        targets = [script_resolve(n) for n in nodes]
    else:
        fail("ERROR: please specify the nodes to kill (or -a to kill all nodes)")
    from rostui.tools.node import lookup_uris

    uris = lookup_uris(call, targets)
    unknown = [n for n in targets if uris.get(n) is None]
    if unknown and not all_:
        _echo("ERROR: Unknown node(s):\n" + "\n".join(f" * {n}" for n in unknown), err=True)
        for n in unknown:
            _hint(n, lambda: system_state(call).nodes())
        raise typer.Exit(1)
    for n in targets:
        if uris.get(n) is not None:
            _echo(f"killing {n}")
    kill_nodes(call, [n for n in targets if uris.get(n) is not None])
    _echo("killed")


@node_app.command("machine")
def machine_command(
    machine: Optional[str] = typer.Argument(None, metavar="[HOST]", help="List the nodes running on this host."),
) -> None:
    """List the hosts nodes run on, or the nodes on HOST (like `rosnode machine`)."""
    from rostui.tools.node_machine import MachineError, machines, nodes_on

    call = master_caller(CALLER)
    if machine is None:
        print("\n".join(machines(call)))
        return
    try:
        print("\n".join(nodes_on(call, machine)))
    except MachineError as exc:
        _echo(f"ERROR: {exc}", err=True)
        raise typer.Exit(1)


@node_app.command("cleanup")
def cleanup_command(
    yes: bool = typer.Option(False, "-y", "--yes", help="Purge without asking (for scripts)."),
) -> None:
    """Purge the registrations of unreachable nodes from the master (like `rosnode cleanup`).

    Asks for confirmation like rosnode does; answer y or n.  If stdin ends
    without an answer (e.g. not a terminal), nothing is purged ("aborting").
    """
    from rostui.tools.node import cleanup_nodes, system_state, unreachable_nodes

    call = master_caller(CALLER)
    dead = unreachable_nodes(call, system_state(call).nodes(), on_error=lambda line: _echo(line, err=True))
    if not dead:
        return
    _echo("Unable to contact the following nodes:\n" + "\n".join(f" * {n}" for n in dead))
    _echo("Warning: these might include alive and functioning nodes, e.g. in unstable networks.")
    _echo("Cleanup will purge all information about these nodes from the master.")
    if not yes:
        _echo("Please type y or n to continue:")
        answer = ""
        while answer not in ("y", "n"):
            line = sys.stdin.readline()
            if not line:
                answer = "n"
                break
            answer = line.strip()
        if answer != "y":
            _echo("aborting")
            return
    for n in dead:
        _echo(f"Unregistering {n}")
    cleanup_nodes(call, dead)
    _echo("done")


def register(app: typer.Typer) -> None:
    """Add ``rostui node ...``."""
    app.add_typer(node_app, name="node")
