"""Reconfigure servers seen from outside, on an :class:`~rostui.core.node.AsyncNode`: found on the master,
followed through their topics, changed through their service, as dynamic_reconfigure's client does.

A server ``NAME`` offers the service ``NAME/set_parameters`` (``dynamic_reconfigure/Reconfigure``) and
publishes, latched, its description on ``NAME/parameter_descriptions`` and its configuration on
``NAME/parameter_updates``.
"""

from __future__ import annotations

import asyncio
import copy
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from rostui.core.msg import get_service_class

from .encoding import Config, ConfigDescrMsg, ConfigMsg, decode_config, decode_description, encode_config, \
    extract_params
from .values import convert_value

__all__ = ["ServerLink", "find_servers", "server_names", "set_group_states"]

SET_PARAMETERS = "/set_parameters"
"""The suffix of a reconfigure server's service name."""
ReconfigureSrv = get_service_class("dynamic_reconfigure/Reconfigure")


def server_names(services: Iterable[str]) -> list[str]:
    """The reconfigure servers among a master's service names (each ``NAME/set_parameters``), sorted."""
    return sorted(name[: -len(SET_PARAMETERS)] for name in services if name.endswith(SET_PARAMETERS))


async def find_servers(node: Any) -> list[str]:
    """The reconfigure servers registered with *node*'s master, sorted (``dynparam list``)."""
    _publishers, _subscribers, services = await node.master_call("getSystemState")
    return server_names(name for name, _providers in services)


def set_group_states(tree: Any, states: Mapping[str, Any]) -> Any:
    """Give each group of a description *tree* named in *states* that state, in place; the tree is returned.

    Names that are no group's change nothing (a dumped configuration's ``groups`` entry holds the tree's own
    keys, ``id``, ``name``..., and ``dynparam load`` passes them so)."""

    def visit(group: str, node: Any) -> None:
        for key, child in node["groups"].items():
            if child["name"] == group:
                node["groups"][key]["state"] = states[group]
            else:
                visit(group, child)

    for group in states:
        visit(group, tree)
    return tree


class ServerLink:
    """One reconfigure server followed through its topics: its description, its configuration as it changes,
    and changes sent to it. *on_change* runs (on the node's loop) after each new description or configuration."""

    def __init__(self, node: Any, name: str, on_change: Callable[[], None] | None = None) -> None:
        self.node = node
        self.name = node.resolve(name)
        self.description: Config | None = None
        self.parameters: list[dict[str, Any]] | None = None
        self.config: Config | None = None
        self._last_config: Any = None
        self._on_change = on_change
        self._described = asyncio.Event()
        self._configured = asyncio.Event()
        self._subscribers: list[Any] = []

    async def open(self) -> ServerLink:
        """Subscribe to the server's description and configuration topics."""
        self._subscribers = [
            await self.node.subscribe(self.name + "/parameter_descriptions", ConfigDescrMsg, self._on_description),
            await self.node.subscribe(self.name + "/parameter_updates", ConfigMsg, self._on_config),
        ]
        return self

    async def close(self) -> None:
        """Stop following the server."""
        for subscriber in self._subscribers:
            await subscriber.unregister()
        self._subscribers = []

    async def wait_for_service(self, timeout: float | None = None) -> None:
        """Wait until the server's ``set_parameters`` service answers (TimeoutError after *timeout* seconds)."""
        await self.node.wait_for_service(self.name + SET_PARAMETERS, timeout)

    async def wait_config(self, timeout: float | None = None) -> Config:
        """The server's configuration once its description and a configuration have come (TimeoutError after
        *timeout* seconds; None waits for good)."""
        await asyncio.wait_for(asyncio.gather(self._described.wait(), self._configured.wait()), timeout)
        assert self.config is not None
        return self.config

    async def set(self, changes: Mapping[str, Any]) -> Config:
        """Send *changes* (name to value, converted to each parameter's declared type; ``groups`` to open or
        close groups) and return the configuration the server answers with.

        :class:`~rostui.tools.reconfigure.values.ParameterValueError` for an unknown name or a value of the
        wrong kind; the service's own errors as the node raises them."""
        await self._described.wait()
        assert self.parameters is not None and self.description is not None
        message: dict[str, Any] = {}
        for name, value in changes.items():
            if name == "groups":
                message[name] = set_group_states(copy.deepcopy(self.description), value)
            else:
                message[name] = convert_value(self.parameters, name, value)
        reply = await self.node.service_proxy(self.name + SET_PARAMETERS, ReconfigureSrv).call(encode_config(message))
        return decode_config(reply.config, self.description)

    def _on_description(self, msg: Any) -> None:
        self.description = decode_description(msg)
        self.parameters = extract_params(self.description)
        if self.config is not None:
            self.config = decode_config(self._last_config, self.description)
        self._described.set()
        self._changed()

    def _on_config(self, msg: Any) -> None:
        self._last_config = msg
        self.config = decode_config(msg, self.description)
        self._configured.set()
        self._changed()

    def _changed(self) -> None:
        if self._on_change is not None:
            self._on_change()
