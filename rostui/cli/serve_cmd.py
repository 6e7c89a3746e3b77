"""`rostui serve APP [ARGS]`: one of the terminal apps in a web browser, through textual-serve.

textual-serve (the optional extra ``rostui[web]``, wrapped by the package
rostui/apps/serve/, which only this command imports) runs a small web
server; each browser tab that opens it starts its own copy of the app as
``python -m rostui APP ARGS`` with this environment (so the same
``ROS_MASTER_URI``), drawn by Textual's web driver into xterm.js in the page.
Only a browser holding the token printed here gets in.  The app and its
arguments are checked here, before anything listens, so a typo is one line in
this terminal rather than an empty page.
"""

from __future__ import annotations

import sys
from typing import Any, Dict, List, Optional, Tuple

import typer

from rostui.cli.registry import app_of, served_apps

#: The apps `rostui serve` runs, as a user names them.
APPS = tuple(app.name for app in served_apps())

#: Port textual-serve (and `textual serve`) listen on by default.
DEFAULT_PORT = 8000

#: Tabs open at once unless --max-sessions says otherwise (each runs its own app, 50-150 MB).
DEFAULT_MAX_SESSIONS = 8

#: Seconds a viewing app has to quit when its tab closes, before SIGTERM and SIGKILL.
VIEWER_QUIT_GRACE = 2.0

#: Seconds a recording bag view has to finish its file when its tab closes.
RECORDER_QUIT_GRACE = 10.0

SERVE_CONTEXT = {
    "help_option_names": ["-h", "--help"],
    "allow_extra_args": True,
    "ignore_unknown_options": True,
    "allow_interspersed_args": False,
}


class NotAnApp(Exception):
    """The words after `rostui serve` do not name an app with arguments it accepts."""


def _app_path(words: List[str]) -> List[str]:
    """The command words of the app ``words`` start with (``["bag", "view"]``), or :class:`NotAnApp`."""
    choices = ", ".join(APPS)
    if not words:
        raise NotAnApp(f"name the app to serve: rostui serve APP [ARGS], APP one of {choices}")
    app = app_of(words)
    if app is None:
        named = " ".join(w for w in words[:2] if not w.startswith("-"))
        raise NotAnApp(f"`{named}` is not an app; serve one of {choices}")
    return list(app.words)


def _parse(ctx: typer.Context, path: List[str], args: List[str]) -> Tuple[Dict[str, Any], List[str]]:
    """The app's parameters and extra words as its own command parses ``args`` (nothing runs), or :class:`NotAnApp`."""
    root = ctx.find_root()
    command: Any = root.command
    for word in path:
        command = command.get_command(root, word)
    try:
        with command.make_context(" ".join(path), list(args), parent=root) as parsed:
            return dict(parsed.params), list(parsed.args)
    except Exception as exc:
        # Click's usage errors (Typer ships its own copy of Click) say what was wrong in format_message().
        explain = getattr(exc, "format_message", None)
        if explain is None:
            raise
        raise NotAnApp(f"{' '.join(path)}: {explain()}") from None


def check_app(ctx: typer.Context, words: List[str]) -> float:
    """Refuse (:class:`NotAnApp`) words that do not open an app: another command, a bad option, a form that prints.

    The app's own options are parsed by its command without running it.  Returns the seconds the app
    needs to quit when its tab closes (a launch gets what its own options give its nodes).
    """
    path = _app_path(words)
    name = " ".join(path)
    args = words[len(path):]
    if any(a in ("-h", "--help") for a in args):
        raise NotAnApp(f"serving runs the app, not its help: see `rostui {name} --help`")
    params, extra = _parse(ctx, path, args)
    if path == ["launch"]:
        _check_launch(params, extra)
    if path == ["graph"] and params.get("dot"):
        raise NotAnApp("graph --dot prints DOT and exits; serve `graph` without --dot")
    if path == ["loggers"] and params.get("node") is not None:
        raise NotAnApp("loggers NODE prints or sets levels without the app; serve `loggers` alone")
    recording = params.get("record") or params.get("all_topics") or params.get("regex")
    if path == ["bag", "view"] and not params.get("args") and not recording:
        raise NotAnApp("bag view needs a bag: rostui serve bag view FILE ... (or --record TOPIC ...)")
    if path == ["launch"]:
        return float(params.get("sigint_timeout") or 0) + float(params.get("sigterm_timeout") or 0) + 3.0
    return RECORDER_QUIT_GRACE if path == ["bag", "view"] and recording else VIEWER_QUIT_GRACE


def _check_launch(params: Dict[str, Any], extra: List[str]) -> None:
    """`launch --tui` with a file and without the options that only print."""
    usage = "rostui serve launch --tui [PACKAGE] FILE [ARG:=VALUE]..."
    if not params.get("tui"):
        raise NotAnApp(f"launch serves its monitor only: {usage}")
    printing = [flag for flag, key in (("--nodes", "nodes"), ("--args", "node_args"), ("--dump-params", "dump_params"),
                                       ("--files", "files"), ("--ros-args", "ros_args")) if params.get(key)]
    if printing:
        raise NotAnApp(f"launch {printing[0]} prints and exits: {usage}")
    words = [*(params.get("arguments") or []), *extra]  # the launch command's positionals, however it takes them
    if not [w for w in words if ":=" not in w]:
        raise NotAnApp(f"launch --tui needs a launch file: {usage}")


def public_url(host: str, port: int) -> str:
    """The address a browser on this machine (or at the near end of an ``ssh -L`` tunnel) opens."""
    import socket

    from rostui.apps.serve.access import EVERYWHERE, LOOPBACK_NAMES as LOOPBACK

    if host in LOOPBACK:
        name = "localhost"
    elif host in EVERYWHERE:
        name = socket.gethostname()
    else:
        name = f"[{host}]" if ":" in host else host
    return f"http://{name}:{port}"


def announcement(app: str, host: str, port: int, url: str, token: str, max_sessions: int) -> List[str]:
    """The lines printed once the server listens: where, the address with its token, how to reach it from elsewhere."""
    import socket

    from urllib.parse import urlsplit

    from rostui.apps.serve.access import LOOPBACK_NAMES as LOOPBACK

    opened = f"{url}/?token={token}"
    listening = f"[{host}]:{port}" if ":" in host else f"{host or '*'}:{port}"
    lines = [f"rostui serve: {app} listening on {listening}; open {opened}",
             f"The token is required: a page or websocket without it is refused. Each browser tab runs its own copy "
             f"(at most {max_sessions}: --max-sessions); Ctrl-C stops the server."]
    if host in LOOPBACK:
        near = urlsplit(url).port or port
        lines.append(f"From another machine: ssh -L {near}:localhost:{port} {socket.gethostname()}, "
                     f"then open {opened} there")
    else:
        lines.append(f"Anyone who can reach {listening} and has the token can use the app; plain http carries "
                     "the token in the clear")
    return lines


def _port_taken(host: str, port: int) -> Optional[str]:
    """Why ``host:port`` cannot be listened on right now, or None when it can."""
    import socket

    try:
        infos = socket.getaddrinfo(host or None, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
    except socket.gaierror as exc:
        return f"cannot resolve --host {host}: {exc.strerror}"
    family, kind, proto, _name, address = infos[0]
    with socket.socket(family, kind, proto) as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            probe.bind(address)
        except OSError as exc:
            return f"cannot listen on {host}:{port}: {exc.strerror}"
    return None


def serve_command(
    ctx: typer.Context,
    host: str = typer.Option("127.0.0.1", "--host", metavar="ADDRESS",
                             help="Address to listen on (default: this machine only; use ssh -L to reach it)."),
    port: int = typer.Option(DEFAULT_PORT, "--port", "-p", metavar="PORT", help="Port to listen on."),
    url: Optional[str] = typer.Option(None, "--public-url", metavar="URL",
                                      help="The address browsers open, when not http://HOST:PORT "
                                           "(a tunnel to another port, a proxy)."),
    max_sessions: int = typer.Option(DEFAULT_MAX_SESSIONS, "--max-sessions", metavar="N",
                                     help="Tabs open at once (each runs its own app); more are refused."),
) -> None:
    """Serve a terminal app to web browsers: {apps}.

    The words after `serve` are the app's command; each browser tab runs its own
    copy with this terminal's environment (ROS_MASTER_URI too).  Options of serve
    go before the app: `rostui serve --port 8080 bag view run.bag`.

    Listens on 127.0.0.1:8000, this machine only, and prints the address to open with
    its token (http://localhost:8000/?token=...): a page or websocket without the token,
    or from another site, is refused.  From a laptop: `ssh -L 8000:localhost:8000 ROBOT`,
    then open that address.

    Needs the web extra: pip install 'rostui\\[web]'.
    """
    from rostui.cli.common import fail

    words: List[str] = list(ctx.args)
    try:
        quit_grace = check_app(ctx, words)
    except NotAnApp as exc:
        fail(f"rostui serve: {exc}")
    if not 0 < port < 65536:
        fail(f"rostui serve: --port must be 1-65535, not {port}")
    if max_sessions < 1:
        fail(f"rostui serve: --max-sessions must be 1 or more, not {max_sessions}")
    try:
        from rostui.apps.serve.access import Access
        from rostui.apps.serve.server import AppServer
    except ImportError as exc:
        fail(f"rostui serve: the web extra is missing ({exc}): pip install 'rostui[web]'")
    taken = _port_taken(host, port)
    if taken is not None:
        fail(f"rostui serve: {taken}")
    app = " ".join(words)
    address = (url or public_url(host, port)).rstrip("/")
    access = Access.for_server(host, port, address)
    server = AppServer([sys.executable, "-m", "rostui", *words], host=host, port=port, public_url=address,
                       title=f"rostui {app}", access=access, max_sessions=max_sessions, quit_grace=quit_grace,
                       announce=announcement(app, host, port, address, access.token, max_sessions))
    try:
        server.serve()
    except OSError as exc:
        fail(f"rostui serve: cannot listen on {host}:{port}: {exc.strerror or exc}")


def register(app: typer.Typer) -> None:
    """Add `rostui serve` to the rostui app; its help names the apps of the registry."""
    serve_command.__doc__ = (serve_command.__doc__ or "").format(apps=", ".join(APPS))
    app.command("serve", context_settings=SERVE_CONTEXT, options_metavar="[OPTIONS] APP [ARGS]...")(serve_command)
