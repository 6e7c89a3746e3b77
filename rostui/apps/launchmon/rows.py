"""What the launch monitor's table shows for each node: plain text, built from the supervisor's processes."""

from __future__ import annotations

import signal
import time
from dataclasses import dataclass

from rostui.launch.process import ManagedProcess, NodeState
from rostui.tools.usage import Usage, UsageSampler, tree_of

#: The table's columns: key, heading and fixed width (None: as wide as the widest cell now).
COLUMNS = (("node", "Node", None), ("state", "State", None), ("pid", "Pid", 7), ("cpu", "CPU %", 6),
           ("mem", "Memory", 9), ("restarts", "Restarts", 8), ("flags", "Flags", None))


@dataclass(frozen=True)
class NodeRow:
    """One row of the node table: every cell as text, and the state (which colours the row)."""

    key: str
    node: str
    state: str
    pid: str
    cpu: str
    mem: str
    restarts: str
    flags: str
    kind: NodeState

    def cells(self) -> tuple[str, ...]:
        """The cells in column order."""
        return (self.node, self.state, self.pid, self.cpu, self.mem, self.restarts, self.flags)


def exit_text(code: int | None) -> str:
    """``exit code 3``, or ``exit code -9, SIGKILL`` for a process ended by a signal."""
    if code is None:
        return "exit code ?"
    if code < 0:
        try:
            return f"exit code {code}, {signal.Signals(-code).name}"
        except ValueError:
            return f"exit code {code}"
    return f"exit code {code}"


def state_text(process: ManagedProcess, now: float | None = None) -> str:
    """How the state column reads: running, respawning in 1.5 s, died (exit code 3)..."""
    state = process.state
    if state is NodeState.RESPAWNING:
        left = max(0.0, (process.respawn_at or 0.0) - (time.monotonic() if now is None else now))
        return f"respawning in {left:.1f} s (died: {exit_text(process.exit_code)})"
    if state is NodeState.DIED:
        return f"died ({exit_text(process.exit_code)})"
    if state is NodeState.FINISHED:
        return "finished (exit code 0)"
    if state is NodeState.FAILED:
        return "cannot start"
    return state.value


def megabytes(rss: int) -> str:
    """Resident memory as ``24.1 MB``."""
    return f"{rss / 1e6:.1f} MB"


def flags_text(process: ManagedProcess) -> str:
    """``required``, ``respawn`` (with its delay when there is one), or empty."""
    spec = process.plan.spec
    if spec.required:
        return "required"
    if spec.respawn:
        return f"respawn {spec.respawn_delay:g} s" if spec.respawn_delay else "respawn"
    return ""


def node_row(process: ManagedProcess, usage: Usage | None, now: float | None = None) -> NodeRow:
    """The table row of ``process``; pid and usage only while it runs; ``/name @machine`` for a remote node."""
    running = process.running
    where = process.machine_name
    return NodeRow(
        key=process.label,
        node=process.name if where is None else f"{process.name} @{where}",
        state=state_text(process, now),
        pid=str(process.pid) if running and process.pid is not None else "-",
        cpu=f"{usage.cpu_percent:.1f}" if running and usage is not None else "-",
        mem=megabytes(usage.rss_bytes) if running and usage is not None else "-",
        restarts=str(process.restarts),
        flags=flags_text(process),
        kind=process.state,
    )


def measure(sampler: UsageSampler, process: ManagedProcess, children: dict[int, list[int]]) -> Usage | None:
    """CPU and memory of the node's whole process tree (None when it does not run).

    ``children`` is :func:`~rostui.tools.usage.children_map`, taken once for every node of a refresh.
    """
    if not process.running or process.pid is None or not process.local:
        return None  # a node on another machine is not measured here
    return sampler.measure(tree_of(process.pid, children))
