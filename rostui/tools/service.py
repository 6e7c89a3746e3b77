"""What `rostui service` does, as plain functions: rosservice's listing, probing and calls.

Master calls go through ``call(method, *args)`` (bound by the CLI).  A
service's type is learnt by probing its server (a rosrpc header with
``probe=1``), as rosservice does; a call runs an anonymous, unannounced
AsyncNode for the duration of one request.
"""

from __future__ import annotations

import asyncio
from typing import Any, Callable, Iterable, Sequence

from rostui.core import names
from rostui.core.one_line import exception_line

__all__ = [
    "ServiceToolError",
    "list_services",
    "service_node",
    "service_uri",
    "service_type",
    "service_args",
    "find_services",
    "call_service",
]

Call = Callable[..., Any]
CALLER = "/rosservice"


class ServiceToolError(Exception):
    """A one-line, user-facing reason a service command failed."""


def list_services(state: Any, namespace: str | None) -> list[tuple[str, list[str]]]:
    """(service, providers) pairs, sorted, under ``namespace`` when given."""
    items = sorted(state.services.items())
    if namespace:
        prefix = names.make_global_ns(namespace)
        items = [(s, n) for s, n in items if s == namespace or s.startswith(prefix)]
    return [(s, sorted(n)) for s, n in items]


def service_node(state: Any, service: str) -> str | None:
    """The node that provides ``service`` (None when nothing does)."""
    nodes = state.services.get(service)
    return nodes[0] if nodes else None


def service_uri(call: Call, service: str) -> str | None:
    """The ``rosrpc://`` URI of ``service`` (None when unknown)."""
    from rostui.core.xmlrpc import RosApiError

    try:
        return call("lookupService", service)
    except RosApiError:
        return None


def probe_type(uri: str, service: str, timeout: float = 5.0) -> str:
    """Ask the server of ``service`` for its type (ServiceToolError if it does not answer)."""
    from rostui.core.node.services import ServiceException, probe_service

    try:
        header = asyncio.run(probe_service(uri, service, CALLER, timeout=timeout))
    except (OSError, asyncio.TimeoutError, asyncio.IncompleteReadError, ServiceException) as exc:
        raise ServiceToolError(f"ERROR: Unable to communicate with service [{service}], address [{uri}]"
                               + (f": {exc}" if str(exc) else "")) from None
    type_name = header.get("type")
    if not type_name:
        raise ServiceToolError(f"ERROR: service [{service}] did not report its type")
    return type_name


def service_type(call: Call, service: str) -> str | None:
    """The type of ``service``, probed from its server (None when the service is unknown)."""
    uri = service_uri(call, service)
    if uri is None:
        return None
    return probe_type(uri, service)


def request_fields(type_name: str) -> list[str]:
    """Top-level request field names of a service type (``rosservice args``)."""
    from rostui.core.msg import get_service_class

    try:
        cls = get_service_class(type_name)
    except Exception as exc:  # unknown or broken type definitions
        raise ServiceToolError(f"ERROR: Unable to load type [{type_name}]: {exc}") from None
    return list(cls._request_class.__slots__)


def service_args(call: Call, service: str) -> list[str]:
    """``rosservice args``: the request's field names."""
    type_name = service_type(call, service)
    if type_name is None:
        raise ServiceToolError(f"ERROR: Service [{service}] is not available.")
    return request_fields(type_name)


def find_services(call: Call, state: Any, type_name: str) -> list[str]:
    """Services whose servers report ``type_name`` (sorted); unreachable servers are skipped."""
    found = []
    for service in sorted(state.services):
        uri = service_uri(call, service)
        if uri is None:
            continue
        try:
            if probe_type(uri, service, timeout=2.0) == type_name:
                found.append(service)
        except ServiceToolError:
            continue
    return found


def parse_stdin_requests(text: str) -> list[Any]:
    """YAML documents read from stdin (``rosservice call SRV < file``), one request each."""
    import yaml

    try:
        return [doc for doc in yaml.safe_load_all(text) if doc is not None]
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"<stdin>:{mark.line + 1}:{mark.column + 1}: " if mark else "<stdin>: "
        raise ServiceToolError(f"ERROR: invalid YAML {where}{getattr(exc, 'problem', exc)}") from None


def build_request(srv_class: Any, args: Sequence[str]) -> Any:
    """A request from command-line arguments, with rosservice's rules (each argument is YAML)."""
    from rostui.core.msg import MessageError
    from rostui.core.msg.convert import message_from_yaml_args

    try:
        return message_from_yaml_args(srv_class._request_class, list(args))
    except (MessageError, ValueError, TypeError, KeyError) as exc:
        raise ServiceToolError(
            f"ERROR: Incompatible arguments to call service: {exception_line(exc, None)}") from None


def build_request_from_value(srv_class: Any, value: Any) -> Any:
    """A request from one already-parsed YAML value (stdin documents)."""
    from rostui.core.msg import MessageError
    from rostui.core.msg.convert import fill_message_args

    try:
        return fill_message_args(srv_class._request_class(), [value])
    except (MessageError, ValueError, TypeError, KeyError) as exc:
        raise ServiceToolError(
            f"ERROR: Incompatible arguments to call service: {exception_line(exc, None)}") from None


def resolve_call_type(call: Call, service: str, wait: bool = False,
                      on_wait: Callable[[], None] | None = None) -> Any:
    """The service class of ``service``, waiting for it to appear with ``wait`` (``on_wait()`` once, when it starts)."""
    import time

    from rostui.core.msg import get_service_class

    waiting = False
    while True:
        uri = service_uri(call, service)
        if uri is not None:
            break
        if not wait:
            raise ServiceToolError(f"ERROR: Service [{service}] is not available.")
        if not waiting and on_wait is not None:
            on_wait()
        waiting = True
        time.sleep(0.2)
    type_name = probe_type(uri, service)
    try:
        return get_service_class(type_name)
    except Exception as exc:
        raise ServiceToolError(f"ERROR: Unable to load type [{type_name}] of service [{service}]: {exc}") from None


def call_service(service: str, srv_class: Any, requests: Iterable[Any]) -> Iterable[Any]:
    """Call ``service`` once per request, yielding each response (ServiceToolError on failure)."""
    from rostui.core.node import AsyncNode
    from rostui.core.node.services import ServiceException

    async def run(requests: list[Any]) -> list[Any]:
        node = await AsyncNode("rosservice", anonymous=True, argv=[]).start(announce=False)
        results: list[Any] = []
        try:
            proxy = node.service_proxy(service, srv_class)
            for request in requests:
                try:
                    results.append(await proxy.call(request))
                except ServiceException as exc:
                    results.append(ServiceToolError(f"ERROR: {exc}"))
                    break
        finally:
            await node.shutdown("rosservice call done")
        return results

    for result in asyncio.run(run(list(requests))):
        if isinstance(result, ServiceToolError):
            raise result
        yield result
