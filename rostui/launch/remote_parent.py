"""The parent side of remote launch: one child launcher per remote machine, started over SSH and driven.

For each remote machine (its address, user, port and env-loader) the parent
runs a child with ``ssh`` (:mod:`rostui.launch.ssh`), waits for it to
``register`` (at most the machine's ``timeout``, 10 s by default), sends it
the machine's nodes with ``launch``, and keeps the state of those nodes from
what the child reports (``log``, ``process_died``) and from the output lines
on the SSH connection.  :mod:`rostui.launch.remote_protocol` describes the
exchange.  A machine that cannot be reached, refuses the login or does not
register is one error naming the machine, and no node starts anywhere (as
roslaunch).  On shutdown each child is asked to stop its nodes (it sends
SIGINT, then SIGTERM and SIGKILL after the launch's timeouts); a child that
does not answer loses its SSH connection, which makes a rostui child stop
its nodes too.
"""

from __future__ import annotations

import asyncio
import re
import sys
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Protocol

from rostui.core.xmlrpc import XmlRpcClient, XmlRpcError
from rostui.launch.errors import LaunchError
from rostui.launch.model import Machine
from rostui.launch.options import SupervisorOptions
from rostui.launch.process import ManagedProcess, NodeState
from rostui.launch.remote_protocol import (
    LOG_ERROR, child_command, label_matches, nodes_xml, output_line, started_pid,
)
from rostui.launch.ssh import DEFAULT_TIMEOUT, SshTarget, ssh_argv, ssh_failure



class LaunchHost(Protocol):
    """What a remote launch needs of the launch that owns it (:class:`~rostui.launch.supervisor.Supervisor`)."""

    anons: dict[str, str]
    master_uri: str
    options: SupervisorOptions
    stopping: asyncio.Event

    def say(self, message: str) -> None:
        """A line of the launcher's output."""

    def complain(self, message: str) -> None:
        """A line of the launcher's errors."""

    def node_ended(self, process: ManagedProcess, code: int | None) -> bool:
        """A node died; True when it will not be restarted."""

#: Seconds a child gets, beyond the launch's own timeouts, to answer ``shutdown``.
SHUTDOWN_GRACE = 10.0
#: Seconds the ``ssh`` client gets to exit once its child has been stopped.
SSH_EXIT_GRACE = 5.0


#: The longest line of a child's ``log`` shown; the rest is cut.
MAX_LOG_LINE = 16384
_CONTROL = {c: None for c in range(32) if c not in (9, 10)} | {127: None}
_CSI = re.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]")


def printable(text: str) -> str:
    """A peer's text without terminal escapes and control characters (nothing reaches the console raw), bounded."""
    return _CSI.sub("", text[:MAX_LOG_LINE]).translate(_CONTROL)


@dataclass
class RemoteProcess(ManagedProcess):
    """A node that runs on another machine: its state, pid and output come from that machine's child."""

    machine: Machine = field(default_factory=lambda: Machine("", ""))
    remote_pid: int | None = None
    child_label: str | None = None
    """The child's name for the process (``ns-name-N``), once it has started it."""

    @property
    def running(self) -> bool:
        """True while the child reports the node running."""
        return self.state in (NodeState.RUNNING, NodeState.STOPPING)

    @property
    def pid(self) -> int | None:
        """The node's pid on its machine."""
        return self.remote_pid

    @property
    def local(self) -> bool:
        """False: its pid is a process of another machine."""
        return False

    @property
    def machine_name(self) -> str | None:
        """The name of its ``<machine>``."""
        return self.machine.name

    async def stop(self, sigint_timeout: float, sigterm_timeout: float) -> str:
        """Nothing to do here: the machine's child stops its nodes when the launch shuts down."""
        return "exited"

    def remember_tree(self) -> None:
        """A remote node's processes are not on this machine."""

    def reap_orphans(self) -> None:
        """A remote node's processes are not on this machine."""


def machine_key(machine: Machine) -> tuple[str, int, str | None, str | None]:
    """Nodes whose machines share address, port, user and env-loader share one child (as roslaunch)."""
    return machine.address, machine.ssh_port, machine.user, machine.env_loader


@dataclass
class RemoteChild:
    """One child launcher on a remote machine and the nodes it runs."""

    name: str
    machine: Machine
    processes: list[RemoteProcess]
    ssh: asyncio.subprocess.Process | None = None
    uri: str | None = None
    registered: asyncio.Event = field(default_factory=asyncio.Event)
    ssh_lines: deque[str] = field(default_factory=lambda: deque(maxlen=20))
    """ssh's (and the remote shell's) own last lines: why a connection failed."""
    pumps: list[asyncio.Task[None]] = field(default_factory=list)

    @property
    def target(self) -> SshTarget:
        """Where to log in."""
        m = self.machine
        return SshTarget(m.address, m.ssh_port, m.user, m.timeout or DEFAULT_TIMEOUT)

    def process(self, label: str) -> RemoteProcess | None:
        """The node the child calls ``label``."""
        for process in self.processes:
            if process.child_label == label:
                return process
        for process in self.processes:
            if label_matches(label, process.plan.spec):
                process.child_label = label
                return process
        return None


class RemoteLaunch:
    """Every child of a launch; also answers roslaunch's parent API (through the launch's XML-RPC server)."""

    def __init__(self, supervisor: LaunchHost) -> None:
        """No children until :meth:`add` gives them nodes."""
        self._supervisor = supervisor
        self.children: list[RemoteChild] = []
        self._by_key: dict[tuple[str, int, str | None, str | None], RemoteChild] = {}

    def add(self, process: RemoteProcess) -> RemoteProcess:
        """Put a remote node with the child of its machine (made on first use, named ``address-N``)."""
        key = machine_key(process.machine)
        child = self._by_key.get(key)
        if child is None:
            child = RemoteChild(f"{process.machine.address}-{len(self.children)}", process.machine, [])
            self._by_key[key] = child
            self.children.append(child)
        child.processes.append(process)
        return process

    def _child(self, name: str) -> RemoteChild | None:
        return next((c for c in self.children if c.name == name), None)

    # -- roslaunch's parent API --------------------------------------------------------------------------------

    def register(self, client: str, uri: str) -> list[Any]:
        """A child announces its XML-RPC URI."""
        child = self._child(str(client))
        if child is None:
            return [-1, f"unknown child [{client}]", 0]
        child.uri = str(uri)
        child.registered.set()
        return [1, "registered", 1]

    def list_children(self) -> list[Any]:
        """The registered children's URIs."""
        return [1, "roslaunch children", [c.uri for c in self.children if c.uri]]

    def log(self, client: str, level: int, message: str) -> list[Any]:
        """A line of a child's own: shown as the launcher's, and a start updates the node's pid."""
        child = self._child(str(client))
        text = printable(f"[{client}]: {message}")
        if isinstance(level, int) and level >= LOG_ERROR:
            self._supervisor.complain(text)
        else:
            self._supervisor.say(text)
        started = started_pid(str(message))
        process = child.process(started[0]) if child is not None and started else None
        if process is not None and started is not None:
            if process.remote_pid is not None and process.remote_pid != started[1]:
                process.starts += 1
            process.starts = max(process.starts, 1)
            process.remote_pid = started[1]
            process.state = NodeState.RUNNING
            process.exit_code = None
            process.respawn_at = None
            process.note(text)
        return [1, "", 1]

    def process_died(self, label: str, exit_code: int) -> list[Any]:
        """A node on a remote machine has ended: died or finished, then respawned by its child or not."""
        supervisor = self._supervisor
        process = next((p for c in self.children if (p := c.process(str(label))) is not None), None)
        if process is None or supervisor.stopping.is_set():
            return [1, "", 0]
        code = exit_code if isinstance(exit_code, int) else None
        process.exit_code = code
        where = f"on machine [{process.machine.name}]"
        if code == 0:
            message = f"[{label}] process has finished cleanly {where}"
            process.state = NodeState.FINISHED
            supervisor.say(message)
        else:
            message = f"[{label}] process has died [pid {process.remote_pid}, exit code {code}] {where}"
            process.state = NodeState.DIED
            supervisor.complain(message)
        process.note(message, error=code != 0)
        if not supervisor.node_ended(process, code):
            process.state = NodeState.RESPAWNING
        return [1, "", 0]

    # -- starting ------------------------------------------------------------------------------------------------

    async def start_children(self, parent_uri: str, run_id: str) -> None:
        """Start every child over SSH and wait until each has registered; LaunchError names a machine that did not."""
        if not self.children:
            return
        supervisor = self._supervisor
        await asyncio.gather(*(self._start(child, parent_uri, run_id) for child in self.children))
        failures = await asyncio.gather(*(self._registered(child) for child in self.children))
        for child, failure in zip(self.children, failures):
            if failure:
                m = child.machine
                raise LaunchError(f"cannot start nodes on machine [{m.name}] ({child.target.describe()}): {failure}",
                                  m.filename, m.line)
        for child in self.children:
            supervisor.say(f"remote[{child.name}]: child launcher registered at {child.uri}")

    async def _start(self, child: RemoteChild, parent_uri: str, run_id: str) -> None:
        supervisor = self._supervisor
        options = supervisor.options
        command = child_command(child.name, parent_uri, run_id, supervisor.master_uri, options.sigint_timeout,
                                options.sigterm_timeout, child.machine.env_loader)
        supervisor.say(f"remote[{child.name}]: starting the child launcher on machine [{child.machine.name}] "
                       f"over ssh ({child.target.describe()})")
        try:
            child.ssh = await asyncio.create_subprocess_exec(
                *ssh_argv(child.target, command), stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE,
                stderr=asyncio.subprocess.PIPE, start_new_session=True)
        except OSError as exc:
            child.ssh_lines.append(f"cannot run ssh: {exc.strerror or exc}")
            return
        assert child.ssh.stdout is not None and child.ssh.stderr is not None
        loop = asyncio.get_running_loop()
        child.pumps = [loop.create_task(self._pump(child, child.ssh.stdout, "stdout")),
                       loop.create_task(self._pump(child, child.ssh.stderr, "stderr"))]

    async def _registered(self, child: RemoteChild) -> str | None:
        """None once ``child`` has registered, else why it did not (ssh's complaint, or the timeout)."""
        if child.ssh is None:
            return ssh_failure(list(child.ssh_lines))
        timeout = child.target.timeout
        registered = asyncio.ensure_future(child.registered.wait())
        ended = asyncio.ensure_future(child.ssh.wait())
        try:
            await asyncio.wait([registered, ended], timeout=timeout, return_when=asyncio.FIRST_COMPLETED)
        finally:
            registered.cancel()
        if child.registered.is_set():
            ended.cancel()
            return None
        if ended.done():
            await asyncio.wait(child.pumps, timeout=2.0)
            return ssh_failure(list(child.ssh_lines))
        ended.cancel()
        return (f"its child launcher did not register within {timeout:g} s (<machine timeout=\"...\"> "
                "allows more)")

    async def _pump(self, child: RemoteChild, reader: asyncio.StreamReader, stream: str) -> None:
        """Route a child's output lines: ``[LABEL]<TAB>TEXT`` to that node, anything else to the launcher's output."""
        supervisor = self._supervisor
        while True:
            try:
                raw = await reader.readline()
            except ValueError:  # a line longer than the reader's limit: drop what is buffered
                continue
            if not raw:
                break
            line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
            parsed = output_line(line)
            process = child.process(parsed[0]) if parsed else None
            if process is not None and parsed is not None:
                self._node_line(process, stream, parsed[1])
                continue
            child.ssh_lines.append(line)
            # A child's other stdout lines repeat what it says through ``log`` (roslaunch's parent drops them too).
            if stream == "stderr" and child.registered.is_set() and line.strip():
                supervisor.complain(printable(f"remote[{child.name}]: {line}"))
        if stream == "stderr":
            await self._connection_closed(child)

    def _node_line(self, process: RemoteProcess, stream: str, text: str) -> None:
        if self._supervisor.options.capture:
            process.output.append(stream, text)
        else:
            print(text, file=sys.stderr if stream == "stderr" else sys.stdout, flush=True)

    async def _connection_closed(self, child: RemoteChild) -> None:
        """The SSH connection ended: outside a shutdown, its running nodes are gone with it."""
        supervisor = self._supervisor
        alive = (NodeState.RUNNING, NodeState.RESPAWNING, NodeState.STARTING)
        if supervisor.stopping.is_set() or not child.registered.is_set() \
                or not any(p.state in alive for p in child.processes):
            return  # a shutdown, or a child that ended with its last node (as roslaunch's does)
        supervisor.complain(f"remote[{child.name}]: the connection to machine [{child.machine.name}] closed: "
                            f"{ssh_failure(list(child.ssh_lines))}")
        for process in child.processes:
            if process.state in alive:
                process.state = NodeState.DIED
                process.note(f"[{process.label}] lost with the connection to machine [{child.machine.name}]",
                             error=True)
                supervisor.node_ended(process, None)

    async def launch_nodes(self) -> None:
        """Send each child its machine's nodes; a node the child could not start is marked as failed."""
        supervisor = self._supervisor
        for child in self.children:
            if supervisor.stopping.is_set() or child.uri is None:
                return
            xml = nodes_xml([p.plan.spec for p in child.processes], supervisor.anons, screen=supervisor.options.screen)
            client = XmlRpcClient(child.uri, timeout=60.0)
            try:
                reply = await client.call("launch", xml)
            except (XmlRpcError, OSError) as exc:
                reply = [0, f"{exc}", [[], []]]
            finally:
                await client.close()
            code, message, value = (list(reply) + [None, None, None])[:3] if isinstance(reply, list) else (0, "", None)
            started: list[str] = []
            failed: list[str] = []
            if code == 1 and isinstance(value, list) and len(value) == 2:
                started, failed = [str(v) for v in value[0]], [str(v) for v in value[1]]
            else:
                supervisor.complain(f"error launching on [{child.name}, uri {child.uri}]: {message}")
                failed = [p.plan.spec.resolved_name for p in child.processes]
            for label in started:
                process = child.process(label)
                if process is not None and process.starts == 0:
                    process.starts = 1
                    if process.state is NodeState.STARTING:
                        process.state = NodeState.RUNNING
            for process in child.processes:
                if process.starts == 0 and process.state is NodeState.STARTING:
                    process.state = NodeState.FAILED
                    process.problem = f"machine [{child.machine.name}] could not start it"
            if failed:
                supervisor.complain(f"remote[{child.name}]: could not start: {', '.join(failed)}")

    # -- stopping ------------------------------------------------------------------------------------------------

    async def shutdown(self) -> None:
        """Ask every child to stop its nodes, then end its SSH connection; nothing is left running anywhere."""
        await asyncio.gather(*(self._stop(child) for child in self.children), return_exceptions=True)

    async def _stop(self, child: RemoteChild) -> None:
        supervisor = self._supervisor
        options = supervisor.options
        for process in child.processes:
            if process.running:
                process.state = NodeState.STOPPING
        if child.uri is not None and child.ssh is not None and child.ssh.returncode is None:
            client = XmlRpcClient(child.uri, timeout=options.sigint_timeout + options.sigterm_timeout + SHUTDOWN_GRACE)
            try:
                await client.call("shutdown")
            except (XmlRpcError, OSError) as exc:
                supervisor.complain(f"remote[{child.name}]: unable to contact machine [{child.machine.name}] to "
                                    f"shut it down ({exc}); closing its connection")
            finally:
                await client.close()
        if child.ssh is not None:
            if child.ssh.stdin is not None:
                child.ssh.stdin.close()
            try:
                await asyncio.wait_for(child.ssh.wait(), SSH_EXIT_GRACE)
            except asyncio.TimeoutError:
                child.ssh.terminate()
                try:
                    await asyncio.wait_for(child.ssh.wait(), SSH_EXIT_GRACE)
                except asyncio.TimeoutError:
                    child.ssh.kill()
                    await child.ssh.wait()
        if child.pumps:
            await asyncio.wait(child.pumps, timeout=2.0)
        for process in child.processes:
            if process.state in (NodeState.RUNNING, NodeState.STOPPING, NodeState.RESPAWNING):
                process.state = NodeState.STOPPED
                process.note(f"[{process.label}] stopped by the launch's shutdown")
