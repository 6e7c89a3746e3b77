"""`rostui dynparam`: a running node's reconfigurable parameters: list, get, set, set_from_parameters, dump, load
(like `dynparam`)."""

from __future__ import annotations

from typing import Any, Awaitable, Callable, List, NoReturn, Optional, TypeVar

import typer

from rostui.cli.common import examples
from rostui.core.one_line import exception_line

CONTEXT = {"help_option_names": ["-h", "--help"]}

dynparam_app = typer.Typer(
    name="dynparam", no_args_is_help=True, context_settings=CONTEXT,
    help="Reconfigurable parameters of running nodes: list, get, set, set_from_parameters, dump, load (like "
         "`dynparam`).",
    epilog=examples(("the nodes that can be reconfigured", "rostui dynparam list"),
                    ("one parameter", "rostui dynparam set /camera exposure 30"),
                    ("several at once", "rostui dynparam set /camera \"{'exposure': 30, 'auto': false}\"")),
)

CALLER = "/dynparam"
MAX_FILE_BYTES = 16 * 1024 * 1024
"""The largest configuration file `load` reads."""
T = TypeVar("T")

TIMEOUT_OPTION = typer.Option(None, "-t", "--timeout", metavar="SECONDS",
                              help="Seconds to wait for the node (default: wait for it).")


def _fail(message: str, hint: str | None = None) -> NoReturn:
    from rostui.cli.common import fail

    fail(message, hint=hint)


def _server_hint(node: str) -> str | None:
    """``did you mean …?`` among the reconfigure servers on the master."""
    from rostui.cli.common import master_caller, suggestion
    from rostui.tools.reconfigure.live import server_names

    def servers() -> list[str]:
        return server_names(name for name, _ in master_caller(CALLER)("getSystemState")[2])

    return suggestion(node, servers)


def _with_server(node: str, timeout: float | None, work: Callable[[Any], Awaitable[T]]) -> T:
    """Run ``work(link)`` on a followed reconfigure server *node*, with an anonymous, unannounced node.

    The server must be on the master (else one line, with ``did you mean``); *timeout* bounds the wait for its
    service and its first configuration (None waits for good, as dynparam does)."""
    import asyncio

    from rostui.cli.common import master_uri
    from rostui.core.master_errors import MasterRefusedError, MasterUnreachableError, unreachable_text
    from rostui.core.node import AsyncNode
    from rostui.tools.reconfigure.live import ServerLink

    async def run() -> T:
        ros = await AsyncNode("dynparam", anonymous=True, argv=[]).start(announce=False)
        try:
            link = ServerLink(ros, node)
            try:
                await ros.master_call("lookupService", link.name + "/set_parameters")
            except MasterRefusedError:
                _fail(f"ERROR: no reconfigure server [{link.name}]: no service {link.name}/set_parameters on the "
                      "master", hint=_server_hint(link.name))
            await link.open()
            await link.wait_for_service(timeout)
            return await work(link)
        finally:
            await ros.shutdown("dynparam done")

    try:
        return asyncio.run(run())
    except MasterUnreachableError:
        _fail(f"ERROR: {unreachable_text(master_uri())}")
    except TimeoutError:
        _fail(f"ERROR: node [{node}] did not answer within {timeout} s")


@dynparam_app.command("list")
def list_command() -> None:
    """Print the nodes that can be reconfigured (like `dynparam list`)."""
    from rostui.cli.common import master_caller
    from rostui.tools.reconfigure.live import server_names

    for name in server_names(name for name, _ in master_caller(CALLER)("getSystemState")[2]):
        print(name)


@dynparam_app.command("get")
def get_command(
    node: str = typer.Argument(..., metavar="NODE", help="The node (its reconfigure server's name)."),
    timeout: Optional[float] = TIMEOUT_OPTION,
) -> None:
    """Print NODE's configuration (like `dynparam get`)."""

    async def get(link: Any) -> Any:
        return await link.wait_config(timeout)

    print(_with_server(node, timeout, get))


def _set(node: str, values: dict[str, Any], timeout: float | None) -> None:
    from rostui.tools.reconfigure.values import ParameterValueError

    async def send(link: Any) -> None:
        await link.wait_config(timeout)
        await link.set(values)

    try:
        _with_server(node, timeout, send)
    except ParameterValueError as exc:
        _fail(f"error updating parameters: {exc}")
    except Exception as exc:
        from rostui.core.node.services import ServiceException

        if isinstance(exc, ServiceException):
            _fail(f"couldn't set parameters at node {node}: {exc}")
        raise


@dynparam_app.command("set", context_settings={"ignore_unknown_options": True})
def set_command(
    node: str = typer.Argument(..., metavar="NODE", help="The node (its reconfigure server's name)."),
    words: List[str] = typer.Argument(..., metavar="PARAMETER VALUE | VALUES",
                                      help="A parameter and its value, or a YAML mapping of several."),
    timeout: Optional[float] = TIMEOUT_OPTION,
) -> None:
    """Change NODE's parameters (like `dynparam set`): an enum by its constant's name, a bool as yes/no too."""
    from rostui.tools.reconfigure.files import parse_values

    if len(words) == 2:
        values: dict[str, Any] | None = {words[0]: words[1]}
    elif len(words) == 1:
        values = parse_values(words[0])
        if values is None:
            _fail("rostui dynparam set: give a parameter and its value, or a YAML mapping: "
                  "\"{'name': value, ...}\"")
    else:
        _fail("rostui dynparam set: too many arguments (a parameter and its value, or one YAML mapping)")
    assert values is not None
    _set(node, values, timeout)


@dynparam_app.command("set_from_parameters", context_settings={"ignore_unknown_options": True})
def set_from_parameters_command(
    node: str = typer.Argument(..., metavar="NODE", help="The node (its reconfigure server's name)."),
    words: Optional[List[str]] = typer.Argument(None, metavar="[ARGS]...",
                                                help="_name:=value private parameters; __name:=ME, this command's own "
                                                     "node name."),
    timeout: Optional[float] = TIMEOUT_OPTION,
) -> None:
    """Send NODE the parameters under this command's own private namespace (like `dynparam set_from_parameters`).

    They are the `_name:=value` words and what the parameter server holds
    under `~` (in a launch file, the param tags of the node that runs it,
    named with `__name:=`)."""
    from rostui.core.names import InvalidNameError, node_global_name, parse_argv
    from rostui.core.xmlrpc import RosApiError

    try:
        args = parse_argv(list(words or []))
        me = node_global_name("dynparam", args, anonymous=True, lenient=True)  # rospy takes `adjust-camera`
    except (InvalidNameError, ValueError) as exc:
        _fail(f"ERROR: {exception_line(exc, None)}")
    if args.args:
        _fail(f"rostui dynparam set_from_parameters: too many arguments: {' '.join(args.args)} (give NODE, then "
              "_name:=value words)")
    from rostui.cli.common import master_call

    try:
        stored = master_call(CALLER, "getParam", me)
    except RosApiError:  # nothing under ~
        stored = {}
    values = {**(stored if isinstance(stored, dict) else {}), **args.params}
    if not values:
        _fail("error updating parameters: no parameters found on parameter server")
    _set(node, values, timeout)


@dynparam_app.command("dump")
def dump_command(
    node: str = typer.Argument(..., metavar="NODE", help="The node (its reconfigure server's name)."),
    file: str = typer.Argument(..., metavar="FILE", help="The YAML file to write ('-' for stdout)."),
    timeout: Optional[float] = TIMEOUT_OPTION,
) -> None:
    """Write NODE's configuration to FILE (like `dynparam dump`)."""
    from rostui.tools.reconfigure.files import dump_text

    async def get(link: Any) -> Any:
        return await link.wait_config(timeout)

    from rostui.cli.common import write_output

    write_output(file, dump_text(_with_server(node, timeout, get)))


@dynparam_app.command("load")
def load_command(
    node: str = typer.Argument(..., metavar="NODE", help="The node (its reconfigure server's name)."),
    file: str = typer.Argument(..., metavar="FILE", help="A YAML file `dump` wrote ('-' for stdin)."),
    timeout: Optional[float] = TIMEOUT_OPTION,
) -> None:
    """Send the configuration in FILE to NODE (like `dynparam load`)."""
    import sys

    from rostui.tools.reconfigure.files import ConfigFileError, load_values

    try:
        if file == "-":
            text = sys.stdin.read(MAX_FILE_BYTES + 1)
        else:
            with open(file, encoding="utf-8", errors="replace") as source:
                text = source.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        _fail(f"ERROR: cannot read [{file}]: {exc.strerror or exc}")
    if len(text) > MAX_FILE_BYTES:
        _fail(f"ERROR: [{file}] is larger than {MAX_FILE_BYTES // (1024 * 1024)} MiB: not a configuration")
    try:
        values = load_values(text, file)
    except ConfigFileError as exc:
        _fail(f"ERROR: {exc}")
    _set(node, values, timeout)


def register(app: typer.Typer) -> None:
    """Add ``rostui dynparam ...``."""
    app.add_typer(dynparam_app, name="dynparam")
