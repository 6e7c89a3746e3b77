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

    def all_nodes(self) -> list[NodeSpec]:
        """Nodes, then tests, in declaration order."""
        return [*self.nodes, *self.tests]
