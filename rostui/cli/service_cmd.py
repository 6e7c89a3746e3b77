"""`rostui service`: Services: list, info, node, type, find, args, uri, call (like `rosservice`)."""

from __future__ import annotations

import sys
from typing import Any, List, NoReturn, Optional

import typer

from rostui.cli.common import JSON_OPTION_HELP as _JSON_HELP
from rostui.cli.common import examples, master_caller
from rostui.cli.complete import complete_services
from rostui.cli.complete import complete_srv_types as complete_service_types

CONTEXT = {"help_option_names": ["-h", "--help"]}

service_app = typer.Typer(name="service", help="Services: list, info, node, type, find, args, uri, call (like `rosservice`).", no_args_is_help=True, context_settings=CONTEXT)

CALLER = "/rosservice"


def _state() -> Any:
    from rostui.tools.node import system_state

    return system_state(master_caller(CALLER))


def _resolve(name: str) -> str:
    from rostui.tools.node import script_resolve

    return script_resolve(name)


def _fail(exc: Exception, hint: str | None = None) -> NoReturn:
    from rostui.cli.common import fail

    fail(str(exc), hint=hint)


def _print_hint(hint: str | None) -> None:
    if hint:
        print(hint, file=sys.stderr, flush=True)


def _service_hint(name: str) -> str | None:
    """``did you mean …?`` among the services the master knows (None when ``name`` is one of them)."""
    from rostui.cli.common import suggestion

    def services() -> list[str]:
        known = list(_state().services)
        return [] if name in known else known

    return suggestion(name, services)


@service_app.command("list")
def list_command(
    namespace: Optional[str] = typer.Argument(None, metavar="NAMESPACE", help="Only services under this namespace."),
    nodes: bool = typer.Option(False, "-n", "--nodes", help="Print the nodes that provide each service."),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List active services (like `rosservice list`)."""
    from rostui.tools.service import list_services

    items = list_services(_state(), _resolve(namespace) if namespace else None)
    if json_out:
        from rostui.cli.common import print_json

        print_json([{"service": s, "nodes": n} for s, n in items] if nodes else [s for s, _ in items])
        return
    for service, providers in items:
        print(f"{service} {' '.join(providers)}" if nodes else service)


@service_app.command("info")
def info_command(
    service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """Print a service's node, URI, type and arguments (like `rosservice info`)."""
    from rostui.tools.service import ServiceToolError, probe_type, request_fields, service_node, service_uri

    name = _resolve(service)
    call = master_caller(CALLER)
    node = service_node(_state(), name)
    uri = service_uri(call, name)
    if node is None or uri is None:
        _fail(ServiceToolError("ERROR: unknown service"), _service_hint(name))
    try:
        type_name = probe_type(uri, name)
        fields = request_fields(type_name)
    except ServiceToolError as exc:
        _fail(exc)
    if json_out:
        from rostui.cli.common import print_json

        print_json({"service": name, "node": node, "uri": uri, "type": type_name, "args": fields})
        return
    print(f"Node: {node}\nURI: {uri}\nType: {type_name}\nArgs: {' '.join(fields)}")


@service_app.command("node")
def node_command(service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services)) -> None:
    """Print the node that provides a service (like `rosservice node`)."""
    from rostui.tools.service import service_node

    name = _resolve(service)
    node = service_node(_state(), name)
    if node is None:
        from rostui.cli.common import fail

        fail(f"Unknown service: {name}", hint=_service_hint(name))
    print(node)


@service_app.command("uri")
def uri_command(service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services)) -> None:
    """Print a service's rosrpc URI (like `rosservice uri`)."""
    from rostui.tools.service import service_uri

    name = _resolve(service)
    uri = service_uri(master_caller(CALLER), name)
    if uri is None:
        from rostui.cli.common import fail

        fail(f"Unknown service: {name}", hint=_service_hint(name))
    print(uri)


@service_app.command("type")
def type_command(service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services)) -> None:
    """Print a service's type (like `rosservice type`)."""
    from rostui.tools.service import ServiceToolError, service_type

    name = _resolve(service)
    try:
        type_name = service_type(master_caller(CALLER), name)
    except ServiceToolError as exc:
        _fail(exc)
    if type_name is None:
        from rostui.cli.common import fail

        fail(f"Unknown service [{name}]", hint=_service_hint(name))
    print(type_name)


@service_app.command("args")
def args_command(service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services)) -> None:
    """Print a service's request fields (like `rosservice args`)."""
    from rostui.tools.service import ServiceToolError, service_args

    name = _resolve(service)
    try:
        print(" ".join(service_args(master_caller(CALLER), name)))
    except ServiceToolError as exc:
        _fail(exc, _service_hint(name))


@service_app.command("find")
def find_command(
    type_name: str = typer.Argument(..., metavar="TYPE", help="Service type, e.g. std_srvs/SetBool.",
                                    autocompletion=complete_service_types),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
) -> None:
    """List the services of a type (like `rosservice find`)."""
    from rostui.tools.service import find_services

    found = find_services(master_caller(CALLER), _state(), type_name)
    if json_out:
        from rostui.cli.common import print_json

        print_json(found)
        return
    print("\n".join(found))


CALL_EXAMPLES = examples(
    ("a service with an empty request (chapter 8)", "rostui service call /clear"),
    ("request fields in `rostui srv show` order", "rostui service call /spawn 3 3 0 Mikey"),
    ("or one YAML dictionary", "rostui service call /spawn '{x: 3, y: 3, theta: 0, name: Mikey}'"),
    ("a logger level (chapter 4)", "rostui service call /count_and_log/set_logger_level ros.agitr DEBUG"),
)


@service_app.command("call", context_settings={"ignore_unknown_options": True, "allow_interspersed_args": False},
                     epilog=CALL_EXAMPLES)
def call_command(
    service: str = typer.Argument(..., metavar="SERVICE", help="Service name.", autocompletion=complete_services),
    args: Optional[List[str]] = typer.Argument(None, metavar="[ARGS]...", help="Request fields in order, or one YAML dictionary."),
    verbose: bool = typer.Option(False, "-v", help="Also print the request."),
    wait: bool = typer.Option(False, "--wait", help="Wait for the service to be advertised."),
) -> None:
    """Call a service and print its response as YAML (like `rosservice call`).

    With no arguments and stdin not a terminal, the first YAML document on
    stdin is the request, as with rosservice (empty stdin: no call).
    """
    from rostui.core.msg.convert import message_to_yaml
    from rostui.tools.service import (
        ServiceToolError, build_request, build_request_from_value, call_service, parse_stdin_requests,
        resolve_call_type,
    )

    name = _resolve(service)
    argv = [a for a in (args or []) if ":=" not in a]  # ROS remapping arguments are not request fields
    try:
        srv_class = resolve_call_type(master_caller(CALLER), name, wait=wait,
                                      on_wait=lambda: _print_hint(_service_hint(name)))
        if argv or sys.stdin is None or sys.stdin.isatty() or not srv_class._request_class.__slots__:
            requests = [build_request(srv_class, argv)]
        else:
            docs = parse_stdin_requests(sys.stdin.read())
            requests = [build_request_from_value(srv_class, doc) for doc in docs[:1]]  # rosservice: first only
        for request, response in zip(requests, call_service(name, srv_class, requests)):
            if verbose:
                print(message_to_yaml(request))
                print("---")
            print(message_to_yaml(response))
    except ServiceToolError as exc:
        _fail(exc, _service_hint(name))


def register(app: typer.Typer) -> None:
    """Add ``rostui service ...``."""
    app.add_typer(service_app, name="service")
