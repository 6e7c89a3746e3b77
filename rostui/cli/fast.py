"""The `rostui` entry point: the commonest master-only queries answered before Typer loads.

Scripts call `rostui topic list` or `rostui param get NAME` in loops; loading
Typer costs more than the query itself.  Exactly these plain forms (no
options) run here, through the same ``rostui.tools`` functions the Typer
commands use; anything else, including ``--help``, goes to the full CLI.
`rostui core [-p PORT]`, `rostui python SCRIPT ...` (:mod:`rostui.cli.python_fast`) and
`rostui bag play` (:mod:`rostui.cli.bag_play_fast`) start here too: launches and test suites start
them by the hundred, and a player's start is part of what it costs beside `rosbag play`.
"""

from __future__ import annotations

import sys

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Callable, Sequence


def _topic_list(args: Sequence[str]) -> int:
    from rostui.cli.common import master_call
    from rostui.tools.topic.listing import format_list, topic_list

    pubs, subs = topic_list(lambda method, *a: master_call("/rostopic", method, *a))
    sys.stdout.write(format_list(pubs, subs, verbose=False, publishers_only=False,
                                 subscribers_only=False, namespace=None))
    return 0


def _param_get(args: Sequence[str]) -> int:
    """``param get NAME`` over :func:`quick_call`; PyYAML loads only for values it must format."""
    from rostui.cli.common import fail, master_uri
    from rostui.core.xmlrpc import RosApiError, XmlRpcConnectionError, ros_result
    from rostui.core.xmlrpc.quick import quick_call
    from rostui.tools.param_quick import script_resolve, simple_value_text

    key = script_resolve(args[0])
    uri = master_uri()
    try:
        value = ros_result(quick_call(uri, "getParam", "/rosparam", key, timeout=10.0))
    except XmlRpcConnectionError:
        from rostui.core.master_errors import unreachable_text

        fail(f"ERROR: {unreachable_text(uri)}")
    except RosApiError:
        from rostui.cli.common import suggestion
        from rostui.tools.suggest import with_namespaces

        hint = suggestion(key, lambda: with_namespaces(
            ros_result(quick_call(uri, "getParamNames", "/rosparam", timeout=10.0))))
        fail(f"ERROR: Parameter [{key}] is not set", hint=hint)
    text = simple_value_text(value)
    if text is None:
        from rostui.tools.param import format_get

        text = format_get(value)
    print(text)
    return 0


FAST: dict[tuple[str, str], tuple[int, Callable[[Sequence[str]], int]]] = {
    ("topic", "list"): (0, _topic_list),
    ("param", "get"): (1, _param_get),
}


def _core(argv: Sequence[str]) -> int | None:
    """``core`` or ``core -p PORT``: the master started by every launch and every test, without Typer."""
    if len(argv) == 1:
        port = 11311
    elif len(argv) == 3 and argv[1] in ("-p", "--port") and argv[2].isdigit():
        port = int(argv[2])
    else:
        return None
    from rostui.cli.core_run import run_core

    return run_core(port)


def main() -> None:
    """Console-script entry point."""
    argv = sys.argv[1:]
    if argv == ["--version"]:
        from rostui import __version__

        print(f"rostui {__version__}")
        raise SystemExit(0)
    if argv[:1] == ["core"]:
        code = _core(argv)
        if code is not None:
            raise SystemExit(code)
    if argv[:1] == ["python"]:
        from rostui.cli.python_fast import run_plain

        code = run_plain(argv[1:])
        if code is not None:
            raise SystemExit(code)
    else:  # a user's script keeps numpy as its user set it up
        from rostui.cli.blas_threads import single_threaded_blas

        single_threaded_blas()
    if argv[:2] == ["bag", "play"]:
        from rostui.cli.bag_play_fast import run_plain as play_plain

        code = play_plain(argv[2:])
        if code is not None:
            raise SystemExit(code)
    entry = FAST.get((argv[0], argv[1])) if len(argv) >= 2 else None
    rest = argv[2:]
    if entry is not None and len(rest) == entry[0] and not any(a.startswith("-") for a in rest):
        sys.stdout.flush()
        raise SystemExit(entry[1](rest))
    from rostui.compat.deferred import import_lean
    from rostui.core.startup_gc import collect_rarely

    collect_rarely()  # until the command's node has started (27 ms of a small bag's play)
    import_lean()  # no OpenSSL or http.client until a command uses them (15-35 ms of every node's start)
    from rostui.cli.tree import main as full_cli

    full_cli()
