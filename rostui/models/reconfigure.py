"""What the reconfigure app knows without a screen: the reconfigure servers on the master, and the selected
one's groups and parameters (types, ranges, enums, descriptions) with their live values.

A :class:`ReconfigureSource` keeps one node through a :class:`~rostui.models.master_link.MasterLink`: it asks
the master for the servers every :data:`SERVER_PERIOD` seconds, follows the selected server's
``parameter_descriptions`` and ``parameter_updates`` (:class:`~rostui.tools.reconfigure.live.ServerLink`) and
sends changes through its ``set_parameters``. :func:`parameter_rows` turns a description and a configuration
into the rows the app shows; :class:`ParamRow` knows how its value steps, toggles and reads from text.
"""

from __future__ import annotations

import asyncio
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from rostui.core.node.node import AsyncNode
from rostui.core.node.services import ServiceException
from rostui.models.master_link import MASTER_ERRORS, LinkedSource, MasterLink, SourceState
from rostui.tools.reconfigure.live import ServerLink, find_servers
from rostui.tools.reconfigure.values import ParameterValueError, convert_value, enum_constants

__all__ = ["Change", "GroupRow", "ParamRow", "ReconfigureSource", "SERVER_PERIOD", "parameter_rows"]

SERVER_PERIOD = 1.0
"""Seconds between two readings of the master's reconfigure servers."""
STEPS_PER_RANGE = 100
"""A double parameter with a range moves by this part of it per arrow key (ten times as much with shift)."""
UNRANGED_STEP = 0.1
"""What a double parameter without finite bounds moves by per arrow key (ten times as much with shift)."""


INT_LIMITS = (-2**31, 2**31 - 1)
"""The bounds a .cfg file's int parameter gets when it names none (C++'s INT_MIN and INT_MAX)."""


def _bounded(value: Any) -> bool:
    """Whether a bound is a real one: a finite number that is not an int parameter's implicit limit."""
    return isinstance(value, (int, float)) and math.isfinite(value) and value not in INT_LIMITS


@dataclass(frozen=True)
class Choice:
    """One constant of an enum parameter: its name, value and description."""

    name: str
    value: Any
    description: str = ""


@dataclass(frozen=True)
class GroupRow:
    """A group of parameters, as a heading: its name, depth in the tree, type and open/closed state."""

    name: str
    depth: int
    kind: str = ""
    state: bool = True

    @property
    def key(self) -> str:
        """The row's key in the app's table."""
        return "group:" + "/" * self.depth + self.name


@dataclass(frozen=True)
class ParamRow:
    """A parameter: its declared type, value, range, default, description and (for an enum) its choices."""

    name: str
    type: str
    value: Any
    minimum: Any = None
    maximum: Any = None
    default: Any = None
    description: str = ""
    depth: int = 0
    choices: tuple[Choice, ...] = field(default=())

    @property
    def key(self) -> str:
        """The row's key in the app's table."""
        return "param:" + self.name

    @property
    def ranged(self) -> bool:
        """Whether the parameter is a number (not an enum) with finite bounds: shown as a bar, its step a part of
        its range."""
        return (self.type in ("int", "double") and not self.choices and _bounded(self.minimum)
                and _bounded(self.maximum) and self.maximum > self.minimum)

    def value_text(self) -> str:
        """The value as the app shows it (an enum's constant name beside its value)."""
        if self.choices:
            named = next((c.name for c in self.choices if c.value == self.value), None)
            if named is not None:
                return f"{named} ({self.value})"
        if self.type == "double" and isinstance(self.value, float):
            return f"{self.value:g}"
        return str(self.value)

    def range_text(self) -> str:
        """The bounds (``≥ 0`` with one only; nothing with none), or the enum's constant names."""
        if self.choices:
            return " | ".join(c.name for c in self.choices)
        if self.type not in ("int", "double"):
            return ""
        low, high = _bounded(self.minimum), _bounded(self.maximum)
        if low and high:
            return f"{_number(self.minimum)} … {_number(self.maximum)}"
        if low:
            return f"≥ {_number(self.minimum)}"
        if high:
            return f"≤ {_number(self.maximum)}"
        return ""

    def fraction(self) -> float | None:
        """Where the value sits in its range, 0 to 1; None when it has no finite range."""
        if not self.ranged or not isinstance(self.value, (int, float)):
            return None
        return min(1.0, max(0.0, (self.value - self.minimum) / (self.maximum - self.minimum)))

    def stepped(self, direction: int, coarse: bool = False) -> Any:
        """The value one step up (*direction* 1) or down (-1): an int by 1, a ranged double by a hundredth of its
        range, another double by :data:`UNRANGED_STEP` (*coarse*: ten steps), an enum to the next constant, a
        bool flipped; clamped to the bounds. None for a string (typed, not stepped)."""
        if self.type == "bool":
            return not self.value
        if self.choices:
            values = [c.value for c in self.choices]
            here = values.index(self.value) if self.value in values else -1
            return values[(here + direction) % len(values)]
        if self.type == "int":
            moved: Any = int(self.value) + direction * (10 if coarse else 1)
        elif self.type == "double":
            step = (self.maximum - self.minimum) / STEPS_PER_RANGE if self.ranged else UNRANGED_STEP
            step *= 10 if coarse else 1
            moved = round(float(self.value) + direction * step, 12)
        else:
            return None
        if self.ranged:
            moved = min(self.maximum, max(self.minimum, moved))
        return moved

    def parse(self, text: str) -> Any:
        """A value typed for this parameter, as its type (an enum by its constant's name too);
        ParameterValueError when it is not one."""
        description = {"name": self.name, "type": self.type,
                       "edit_method": repr({"enum": [{"name": c.name, "value": c.value, "type": self.type}
                                                     for c in self.choices]}) if self.choices else ""}
        return convert_value([description], self.name, text)


def _number(value: Any) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def _choices(edit_method: str) -> tuple[Choice, ...]:
    return tuple(Choice(str(c.get("name", "")), c.get("value"), str(c.get("description", "")))
                 for c in enum_constants(edit_method))


def _group_states(tree: Any) -> dict[str, bool]:
    """Each group's open/closed state in a configuration's groups tree (the server keeps them there)."""
    states: dict[str, bool] = {}
    pending = [tree] if isinstance(tree, Mapping) else []
    while pending:
        node = pending.pop()
        children = node.get("groups", {})
        for child in children.values() if isinstance(children, Mapping) else ():
            if isinstance(child, Mapping):
                states[str(child.get("name", ""))] = bool(child.get("state", True))
                pending.append(child)
    return states


def parameter_rows(description: Mapping[str, Any] | None, config: Mapping[str, Any] | None) \
        -> list[GroupRow | ParamRow]:
    """The rows of a server: each group's parameters after its heading, subgroups after them, depth first (the
    top group has no heading); a value not yet known is None."""
    rows: list[GroupRow | ParamRow] = []
    if not description:
        return rows
    values = config or {}
    states = _group_states(values.get("groups"))

    def visit(group: Mapping[str, Any], depth: int) -> None:
        if depth:
            name = str(group.get("name", ""))
            rows.append(GroupRow(name, depth, str(group.get("type", "")), states.get(name, True)))
        for param in group.get("parameters", []):
            name = str(param.get("name", ""))
            rows.append(ParamRow(name, str(param.get("type", "")), values.get(name), param.get("min"),
                                 param.get("max"), param.get("default"), str(param.get("description", "")), depth,
                                 _choices(str(param.get("edit_method", "")))))
        children = group.get("groups", {})
        for child in children.values() if isinstance(children, Mapping) else children:
            visit(child, depth + 1)

    visit(description, 0)
    return rows


@dataclass(frozen=True)
class Change:
    """A change sent to a server and what came of it: the value asked, the value the server kept (it may clamp
    or refuse), the seconds from sending to its answer, or the error."""

    server: str
    name: str
    asked: Any
    kept: Any = None
    seconds: float = 0.0
    error: str = ""


class ReconfigureSource(LinkedSource):
    """The reconfigure servers of the master at *master_uri* and the selected one's parameters; run
    :meth:`run` as a task. *on_change* runs (on the caller's loop) after the server list, the selected server's
    description or its values change."""

    def __init__(self, master_uri: str, *, node_name: str = "rostui_reconfigure",
                 on_change: Callable[[], None] | None = None,
                 on_state: Callable[[SourceState], None] | None = None,
                 server_period: float = SERVER_PERIOD) -> None:
        self.on_change = on_change or (lambda: None)
        self.server_period = server_period
        self.servers: list[str] = []
        self.servers_read = False
        self.selected: str | None = None
        self.server: ServerLink | None = None
        self.link = MasterLink(node_name, master_uri, session=self._watch_servers, on_state=on_state,
                               on_drop=self._forget_server)

    async def run(self) -> None:
        """Keep the node with the master and the server list fresh until :meth:`stop`."""
        await self.link.run()

    async def stop(self) -> None:
        """Stop following the server and shut the node down."""
        await self.link.stop()

    async def _watch_servers(self, node: AsyncNode) -> None:
        while True:
            servers = await asyncio.wait_for(find_servers(node), self.link.call_timeout)
            if servers != self.servers or not self.servers_read:
                self.servers, self.servers_read = servers, True
                self.on_change()
            if self.selected is not None and self.server is None:
                await self._follow(node, self.selected)
            await asyncio.sleep(self.server_period)

    def _forget_server(self) -> None:
        self.server = None

    async def select(self, name: str | None) -> None:
        """Follow server *name* (None: none) instead of the one followed now."""
        if name == self.selected and self.server is not None:
            return
        old, self.server, self.selected = self.server, None, name
        if old is not None:
            try:
                await old.close()
            except MASTER_ERRORS:  # the master is gone: the node's subscription goes with the node
                pass
        node = self.node
        if name is not None and node is not None:
            await self._follow(node, name)
        self.on_change()

    async def _follow(self, node: AsyncNode, name: str) -> None:
        server = ServerLink(node, name, on_change=self._server_changed)
        await server.open()
        if self.selected == name:
            self.server = server
        else:
            await server.close()

    def _server_changed(self) -> None:
        self.on_change()

    def rows(self) -> list[GroupRow | ParamRow]:
        """The selected server's rows (none before its description came)."""
        server = self.server
        if server is None:
            return []
        return parameter_rows(server.description, server.config)

    async def set_value(self, name: str, value: Any) -> Change:
        """Send parameter *name* = *value* to the selected server and say what came of it."""
        server = self.server
        if server is None:
            return Change(self.selected or "", name, value, error="no server selected")
        started = time.perf_counter()
        try:
            config = await asyncio.wait_for(server.set({name: value}), self.link.call_timeout)
        except ParameterValueError as exc:
            return Change(server.name, name, value, error=str(exc))
        except asyncio.TimeoutError:
            return Change(server.name, name, value, error=f"{server.name} did not answer within "
                                                               f"{self.link.call_timeout:g} s")
        except MASTER_ERRORS + (ServiceException,) as exc:  # the server's refusal, a node gone: said, never fatal
            return Change(server.name, name, value, error=str(exc) or type(exc).__name__)
        return Change(server.name, name, value, kept=config.get(name), seconds=time.perf_counter() - started)
