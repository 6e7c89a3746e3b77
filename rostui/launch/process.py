"""One node process under the supervisor: start, output routing, exit, and stopping its whole tree."""

from __future__ import annotations

import asyncio
import os
import signal
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

import psutil

from rostui.launch.model import NodeSpec


@dataclass
class ProcessPlan:
    """How to start one node: argv, environment, cwd and where its stdout goes (None: the console)."""

    spec: NodeSpec
    label: str
    argv: list[str]
    env: dict[str, str]
    cwd: str
    stdout_log: Path | None


@dataclass
class ManagedProcess:
    """A started node; its process runs in its own session so a terminal's Ctrl-C reaches only the launcher."""

    plan: ProcessPlan
    proc: asyncio.subprocess.Process | None = None
    started_at: float = 0.0
    starts: int = 0
    known_tree: set[int] = field(default_factory=set)
    _log: IO[bytes] | None = None

    @property
    def pid(self) -> int | None:
        """The node's pid while it has a process."""
        return self.proc.pid if self.proc is not None else None

    async def start(self) -> None:
        """Start (or restart) the process; raises OSError when it cannot be executed."""
        plan = self.plan
        if plan.stdout_log is not None and self._log is None:
            plan.stdout_log.parent.mkdir(parents=True, exist_ok=True)
            self._log = open(plan.stdout_log, "ab")  # noqa: SIM115 (kept open across respawns)
        stdout = self._log if self._log is not None else None
        self.proc = await asyncio.create_subprocess_exec(
            *plan.argv, env=plan.env, cwd=plan.cwd, stdin=asyncio.subprocess.DEVNULL, stdout=stdout,
            stderr=None, start_new_session=True)
        self.started_at = time.monotonic()
        self.starts += 1
        self.known_tree = {self.proc.pid}

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

    def signal_tree(self, signum: int) -> None:
        """Send ``signum`` to every live process of the node's tree."""
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
        """SIGINT, then SIGTERM, then SIGKILL (whole tree); returns which signal ended it."""
        self.remember_tree()
        how = "exited"
        if self.proc is not None and self.proc.returncode is None:
            self.signal_leader(signal.SIGINT)
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

    def close_log(self) -> None:
        """Close the stdout log file."""
        if self._log is not None:
            self._log.close()
            self._log = None
