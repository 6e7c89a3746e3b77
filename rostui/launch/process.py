"""One node process under the supervisor: start, output routing, state, exit, and stopping its whole tree.

Each node starts as the leader of its own session and process group (as
roslaunch's ``setsid``), so a terminal's Ctrl-C reaches only the launcher and a
stop signals the node's whole group at once: a wrapper script's children get
the SIGINT too, then SIGTERM and SIGKILL after the same timeouts as the leader.
"""

from __future__ import annotations

import asyncio
import os
import signal
import time
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import IO

import psutil

from rostui.launch.model import NodeSpec
from rostui.launch.output import OutputBuffer, pump


class NodeState(Enum):
    """Where a node of the launch stands."""

    STARTING = "starting"
    """Not started yet (the launch is still setting up, or earlier nodes are starting)."""
    RUNNING = "running"
    RESPAWNING = "respawning"
    """Died; it starts again when its respawn delay is over."""
    DIED = "died"
    """Ended with a non-zero exit code (or a signal) and is not restarted."""
    FINISHED = "finished"
    """Ended with exit code 0 and is not restarted."""
    STOPPING = "stopping"
    STOPPED = "stopped"
    """Stopped on request (from the monitor, or by the launch's shutdown)."""
    FAILED = "failed"
    """Could not be started (its program or launch-prefix cannot run)."""

    @property
    def ended(self) -> bool:
        """True for a node that ended by itself and will not come back on its own."""
        return self in (NodeState.DIED, NodeState.FINISHED, NodeState.FAILED)


@dataclass
class ProcessPlan:
    """How to start one node: argv, environment, cwd and where its stdout goes (None: the console)."""

    spec: NodeSpec
    label: str
    argv: list[str]
    env: dict[str, str]
    cwd: str
    stdout_log: Path | None
    capture: bool = False
    """True: stdout and stderr come through pipes into the process's :class:`OutputBuffer`."""


@dataclass
class ManagedProcess:
    """A started node; its process runs in its own session so a terminal's Ctrl-C reaches only the launcher."""

    plan: ProcessPlan
    proc: asyncio.subprocess.Process | None = None
    started_at: float = 0.0
    starts: int = 0
    known_tree: set[int] = field(default_factory=set)
    state: NodeState = NodeState.STARTING
    exit_code: int | None = None
    respawn_at: float | None = None
    """When (time.monotonic) a respawning node starts again."""
    problem: str = ""
    """Why the node could not be started (state FAILED)."""
    output: OutputBuffer = field(default_factory=OutputBuffer)
    """Its captured lines (with ``plan.capture``) and the launcher's notes about it."""
    lock: asyncio.Lock = field(default_factory=asyncio.Lock)
    """Held while the process is started or stopped, so a respawn and a request never overlap."""
    _log: IO[bytes] | None = None
    _pumps: list[asyncio.Task[None]] = field(default_factory=list)

    @property
    def label(self) -> str:
        """The process name of roslaunch (``ns-name-N``)."""
        return self.plan.label

    @property
    def name(self) -> str:
        """The node's global name."""
        return self.plan.spec.resolved_name

    @property
    def restarts(self) -> int:
        """How many times the node was started again after its first start."""
        return max(0, self.starts - 1)

    @property
    def running(self) -> bool:
        """True while its process has not exited."""
        return self.proc is not None and self.proc.returncode is None

    @property
    def pid(self) -> int | None:
        """The node's pid while it has a process."""
        return self.proc.pid if self.proc is not None else None

    @property
    def local(self) -> bool:
        """True when the pid is a process of this machine (a node on another machine has one of its own)."""
        return True

    @property
    def machine_name(self) -> str | None:
        """The ``<machine>`` the node runs on when that is another host; None here."""
        return None

    async def start(self) -> None:
        """Start (or restart) the process; raises OSError when it cannot be executed."""
        plan = self.plan
        if plan.stdout_log is not None and self._log is None:
            plan.stdout_log.parent.mkdir(parents=True, exist_ok=True)
            self._log = open(plan.stdout_log, "ab")  # noqa: SIM115 (kept open across respawns)
        if plan.capture:
            stdout: int | IO[bytes] | None = asyncio.subprocess.PIPE
            stderr: int | None = asyncio.subprocess.PIPE
        else:
            stdout, stderr = self._log, None
        self.proc = await asyncio.create_subprocess_exec(
            *plan.argv, env=plan.env, cwd=plan.cwd, stdin=asyncio.subprocess.DEVNULL, stdout=stdout,
            stderr=stderr, start_new_session=True)
        self.started_at = time.monotonic()
        self.starts += 1
        self.known_tree = {self.proc.pid}
        self.state = NodeState.RUNNING
        self.exit_code = None
        self.respawn_at = None
        if plan.capture:
            assert self.proc.stdout is not None and self.proc.stderr is not None
            loop = asyncio.get_running_loop()
            self._pumps = [task for task in self._pumps if not task.done()]
            self._pumps.append(loop.create_task(pump(self.proc.stdout, self.output, "stdout", self._log)))
            self._pumps.append(loop.create_task(pump(self.proc.stderr, self.output, "stderr")))

    def note(self, text: str, error: bool = False) -> None:
        """Add a line of the launcher's own (started, died, restarting...) to the node's output."""
        self.output.append("error" if error else "launch", text)

    def remember_tree(self) -> None:
        """Record the pids of the node's descendants (so they can be reaped even after the leader exits)."""
        if self.proc is None:
            return
        try:
            children = psutil.Process(self.proc.pid).children(recursive=True)
        except psutil.Error:
            return
        self.known_tree.update(child.pid for child in children)

    def alive_tree(self) -> list[psutil.Process]:
        """The node's processes (leader and every remembered or current descendant) still running."""
        self.remember_tree()
        alive: list[psutil.Process] = []
        for pid in sorted(self.known_tree):
            try:
                process = psutil.Process(pid)
                if process.status() != psutil.STATUS_ZOMBIE:
                    alive.append(process)
            except psutil.Error:
                continue
        return alive

    def signal_leader(self, signum: int) -> None:
        """Send ``signum`` to the node's process (the launch-prefix program when there is one)."""
        if self.proc is not None and self.proc.returncode is None:
            try:
                os.kill(self.proc.pid, signum)
            except ProcessLookupError:
                pass

    def signal_group(self, signum: int) -> None:
        """Send ``signum`` to the node's process group (its leader and every child that stayed in it).

        Only while the leader has not been reaped: its pid, which is the group's id, cannot be reused before.
        """
        if self.proc is None or self.proc.returncode is not None:
            return
        try:
            os.killpg(self.proc.pid, signum)
        except (ProcessLookupError, PermissionError):
            self.signal_leader(signum)

    def signal_tree(self, signum: int) -> None:
        """Send ``signum`` to the node's group and to every live process of its tree (children that left the group)."""
        self.signal_group(signum)
        for process in self.alive_tree():
            try:
                process.send_signal(signum)
            except psutil.Error:
                continue

    async def wait(self, timeout: float) -> bool:
        """Wait up to ``timeout`` s for the leader to exit; True when it has."""
        if self.proc is None or self.proc.returncode is not None:
            return True
        try:
            await asyncio.wait_for(asyncio.shield(self.proc.wait()), timeout)
        except asyncio.TimeoutError:
            return False
        return True

    async def stop(self, sigint_timeout: float, sigterm_timeout: float) -> str:
        """SIGINT to the node's process group, then SIGTERM, then SIGKILL (group and whole tree), as roslaunch.

        Returns which signal ended it.
        """
        self.remember_tree()
        how = "exited"
        if self.proc is not None and self.proc.returncode is None:
            self.signal_group(signal.SIGINT)
            how = "SIGINT"
            if not await self.wait(sigint_timeout):
                self.signal_tree(signal.SIGTERM)
                how = "SIGTERM"
                if not await self.wait(sigterm_timeout):
                    self.signal_tree(signal.SIGKILL)
                    how = "SIGKILL"
                    await self.wait(5.0)
        self.reap_orphans()
        return how

    def reap_orphans(self) -> None:
        """SIGKILL whatever is left of the node's tree (children its leader left behind)."""
        leftovers = self.alive_tree()
        for process in leftovers:
            try:
                process.kill()
            except psutil.Error:
                continue
        psutil.wait_procs(leftovers, timeout=3)

    async def drain(self, timeout: float = 2.0, *, give_up: bool = True) -> None:
        """Wait (up to ``timeout`` s) until the pipes' last lines are read (with ``plan.capture``).

        With ``give_up`` the pipes still open after ``timeout`` (held by a
        child the node left behind) stop being read.
        """
        pending = [task for task in self._pumps if not task.done()]
        if pending:
            _, late = await asyncio.wait(pending, timeout=timeout)
            if give_up:
                for task in late:
                    task.cancel()

    def close_log(self) -> None:
        """Close the stdout log file."""
        if self._log is not None:
            self._log.close()
            self._log = None
