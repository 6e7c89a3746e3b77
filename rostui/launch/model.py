"""The launch model: what a launch file declares once its XML is read and its substitutions resolved."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from rostui.core.names import join_names


@dataclass
class NodeSpec:
    """One ``<node>`` (or ``<test>``) to start."""

    package: str
    type: str
    name: str
    namespace: str = "/"
    args: str = ""
    remaps: list[tuple[str, str]] = field(default_factory=list)
    env: list[tuple[str, str]] = field(default_factory=list)
    machine: str | None = None
    respawn: bool = False
    respawn_delay: float = 0.0
    required: bool = False
    output: str | None = None
    cwd: str | None = None
    launch_prefix: str | None = None
    filename: str | None = None
    line: int | None = None
    test_name: str | None = None
    time_limit: float | None = None
    retry: int = 0
    remote: bool = False
    """True once :func:`rostui.launch.machines.assign_machines` finds the node's machine is another host."""

    @property
    def is_test(self) -> bool:
        """True for a ``<test>`` (listed, never started outside rostest)."""
        return self.test_name is not None

    @property
    def resolved_name(self) -> str:
        """The node's global name (``$(anon x)`` left as written stays as it is)."""
        if self.name.startswith("$"):
            return self.name
        return join_names(self.namespace, self.name)


@dataclass
class Machine:
    """A ``<machine>``: where nodes naming it would run."""

    name: str
    address: str
    env_loader: str | None = None
    ssh_port: int = 22
    user: str | None = None
    password: str | None = None
    timeout: float | None = None
    line: int | None = None
    filename: str | None = None
    assignable: bool = True
    """False for ``default="never"``: the machine is only used by nodes naming it."""
    local: bool | None = None
    """Whether the machine is this host (set by :func:`rostui.launch.machines.assign_machines`)."""

    def config_key(self) -> tuple[object, ...]:
        """What makes two machines the same host and login (roslaunch's equality, without the name)."""
        return (self.address, self.env_loader, self.ssh_port, self.user or None, self.password or None,
                self.timeout if self.timeout is not None else DEFAULT_MACHINE_TIMEOUT)

    def same_as(self, other: "Machine") -> bool:
        """True when ``other`` may be declared again under the same name (roslaunch's duplicate rule)."""
        return (self.name, self.assignable, self.config_key()) == (other.name, other.assignable, other.config_key())


#: roslaunch's wait for a remote launcher to register when ``<machine timeout>`` is not given.
DEFAULT_MACHINE_TIMEOUT = 10.0


@dataclass
class LaunchProblem:
    """An unknown element or attribute: roslaunch warns and goes on; ``--strict`` makes it an error."""

    message: str
    filename: str | None = None
    line: int | None = None

    def __str__(self) -> str:
        """``FILE:LINE: message``."""
        where = ":".join(str(p) for p in (self.filename, self.line) if p is not None)
        return f"{where}: {self.message}" if where else self.message


@dataclass
class RosparamCommand:
    """A ``<rosparam command="dump|delete">``: run against the master before params are set."""

    command: str
    param: str
    file: str | None = None


@dataclass
class LaunchConfig:
    """Everything a set of launch files declares."""

    nodes: list[NodeSpec] = field(default_factory=list)
    tests: list[NodeSpec] = field(default_factory=list)
    params: dict[str, Any] = field(default_factory=dict)
    clear_params: list[str] = field(default_factory=list)
    machines: dict[str, Machine] = field(default_factory=dict)
    rosparam_commands: list[RosparamCommand] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    arg_docs: dict[str, tuple[str | None, str | None]] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    problems: list[LaunchProblem] = field(default_factory=list)
    """Unknown elements and attributes (each is also one of :attr:`warnings`)."""

    def all_nodes(self) -> list[NodeSpec]:
        """Nodes, then tests, in declaration order."""
        return [*self.nodes, *self.tests]

    def machine_of(self, node: NodeSpec) -> Machine | None:
        """The ``<machine>`` a node is assigned to (None: this host, or a machine name never declared)."""
        return self.machines.get(node.machine) if node.machine else None

    def remote_nodes(self) -> list[NodeSpec]:
        """Nodes and tests :func:`rostui.launch.machines.assign_machines` placed on another host."""
        return [n for n in self.all_nodes() if n.remote]
