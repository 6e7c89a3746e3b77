"""Run a launch: master, params, then every node; respawn, required, and a clean Ctrl-C.

The master (with ``/rosout``) runs inside this process, on its event loop, when
none answers at ROS_MASTER_URI (see :func:`rostui.core.master.embedded.ensure_master`);
a running master is reused.  Order, as roslaunch: ``<rosparam command="delete|dump">``,
then ``clear_params``, then every param, then ``/roslaunch/uris/host_<host>__<port>``,
then the nodes.  Node stdout goes to ``$ROS_HOME/log/<run_id>/<name>-N-stdout.log``
unless ``output="screen"`` or ``--screen``; stderr always goes to the console.
"""

from __future__ import annotations

import asyncio
import os
import shlex
import shutil
import signal
import socket
import sys
import time
import uuid
import xmlrpc.client
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit, urlunsplit

import yaml

from rostui.core.log.files import ros_home, run_log_dir
from rostui.core.master.embedded import EmbeddedMaster, MasterUnavailableError, ensure_master, is_local_host, \
    master_answers
from rostui.core.xmlrpc import XmlRpcClient, XmlRpcError
from rostui.core.xmlrpc.server import XmlRpcServer
from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest
from rostui.launch.inspect import load_config, node_argv, node_env
from rostui.launch.model import LaunchConfig, NodeSpec
from rostui.launch.process import ManagedProcess, ProcessPlan

CALLER = "/roslaunch"
#: A respawned node that dies within this many seconds of starting is restarted with a growing delay.
QUICK_DEATH = 1.0
#: The longest back-off between restarts of a node that keeps dying at once.
MAX_BACKOFF = 30.0


@dataclass
class SupervisorOptions:
    """Command-line options of a launch."""

    screen: bool = False
    verbose: bool = False
    wait: bool = False
    port: int | None = None
    sigint_timeout: float = 15.0
    sigterm_timeout: float = 2.0


def say(message: str) -> None:
    """A line of the launcher's own output."""
    print(message, flush=True)


def complain(message: str) -> None:
    """A line on stderr."""
    print(message, file=sys.stderr, flush=True)


def master_uri_for(options: SupervisorOptions) -> str:
    """ROS_MASTER_URI, with its port replaced by ``-p PORT`` when given."""
    uri = os.environ.get("ROS_MASTER_URI") or "http://localhost:11311/"
    if options.port is None:
        return uri if uri.endswith("/") else uri + "/"
    parts = urlsplit(uri)
    host = parts.hostname or "localhost"
    return urlunsplit((parts.scheme or "http", f"{host}:{options.port}", "/", "", ""))


def check_machines(config: LaunchConfig) -> None:
    """Refuse (before anything starts) nodes assigned to an unknown machine or to another host."""
    for node in config.nodes:
        if not node.machine:
            continue
        machine = config.machines.get(node.machine)
        if machine is None:
            raise LaunchError(f"unknown machine [{node.machine}] for node [{node.resolved_name}]",
                              node.filename, node.line)
        if not is_local_host(machine.address):
            raise LaunchError(f"node [{node.resolved_name}] is assigned to machine [{machine.name}] at "
                              f"{machine.address}: remote launch (ssh) is not available in rostui",
                              node.filename, node.line)


def log_label(node: NodeSpec, counter: int) -> str:
    """roslaunch's process name for log files: ``ns-name-N`` without the leading slash."""
    return f"{node.resolved_name.lstrip('/').replace('/', '-')}-{counter}"


def prefix_problem(node: NodeSpec) -> str | None:
    """Why the node's launch-prefix cannot run (its program is missing), or None."""
    if not node.launch_prefix:
        return None
    words = shlex.split(node.launch_prefix)
    if words and shutil.which(words[0]) is None:
        return f"launch-prefix program '{words[0]}' is not installed (launch-prefix=\"{node.launch_prefix}\")"
    return None


class _LaunchApi:
    """The launcher's XML-RPC API (``/roslaunch/uris/...`` points here): pid and the processes it runs."""

    def __init__(self, supervisor: "Supervisor") -> None:
        self._supervisor = supervisor

    def getPid(self, *_: Any) -> list[Any]:  # noqa: N802 (XML-RPC name)
        return [1, "", os.getpid()]

    def list_processes(self, *_: Any) -> list[Any]:
        processes = [p for p in self._supervisor.processes if p.proc is not None]
        running = [[p.plan.label, p.starts] for p in processes if p.proc and p.proc.returncode is None]
        dead = [[p.plan.label, p.starts] for p in processes if p.proc and p.proc.returncode is not None]
        return [1, "processes on this launcher", [running, dead]]


class Supervisor:
    """Starts a loaded launch and keeps it running until Ctrl-C, a required node's death or all nodes ending."""

    def __init__(self, config: LaunchConfig, anons: dict[str, str], options: SupervisorOptions) -> None:
        """Keep the config, the launch's anon names and the options."""
        self.config = config
        self.anons = anons
        self.options = options
        self.processes: list[ManagedProcess] = []
        self.master_uri = master_uri_for(options)
        self.embedded: EmbeddedMaster | None = None
        self.server: XmlRpcServer | None = None
        self.stopping = asyncio.Event()
        self.exit_code = 0
        self.run_id = ""

    # -- set-up ------------------------------------------------------------------------------------------------

    async def _master(self) -> None:
        if self.options.wait:
            announced = False
            while not await master_answers(self.master_uri, timeout=1.0):
                if not announced:
                    say(f"roslaunch: waiting for a master at {self.master_uri}")
                    announced = True
                try:
                    await asyncio.wait_for(self.stopping.wait(), 0.5)
                    raise LaunchError("stopped while waiting for a master")
                except asyncio.TimeoutError:
                    continue
            return
        try:
            self.embedded = await ensure_master(self.master_uri)
        except MasterUnavailableError as exc:
            raise LaunchError(str(exc)) from None
        if self.embedded is not None:
            say(f"started master (in this process) and /rosout at {self.embedded.uri}")

    async def _call(self, method: str, *args: Any) -> Any:
        client = XmlRpcClient(self.master_uri, timeout=10.0)
        try:
            return await client.call(method, CALLER, *args)
        finally:
            await client.close()

    async def _run_id(self) -> str:
        reply = await self._call("getParam", "/run_id")
        if isinstance(reply, list) and reply and reply[0] == 1 and isinstance(reply[2], str) and reply[2]:
            return reply[2]
        run_id = str(uuid.uuid1())
        await self._call("setParam", "/run_id", run_id)
        return run_id

    async def _rosparam_commands(self) -> None:
        for command in self.config.rosparam_commands:
            if command.command == "delete":
                reply = await self._call("deleteParam", command.param)
                if reply[0] != 1:
                    complain(f"WARNING: rosparam delete {command.param}: {reply[1]}")
            else:
                reply = await self._call("getParam", command.param)
                if reply[0] != 1:
                    complain(f"WARNING: rosparam dump {command.param}: {reply[1]}")
                    continue
                target = Path(command.file or "rosparam_dump.yaml")
                target.write_text(yaml.safe_dump(reply[2], default_flow_style=False), encoding="utf-8")

    async def _set_params(self) -> None:
        for ns in dict.fromkeys(self.config.clear_params):
            reply = await self._call("hasParam", ns)
            if reply[0] == 1 and reply[2]:
                await self._call("deleteParam", ns)
        for key, value in self.config.params.items():
            if isinstance(value, xmlrpc.client.Binary):
                value = value.data
            reply = await self._call("setParam", key, value)
            if reply[0] != 1:
                raise LaunchError(f"cannot set parameter [{key}]: {reply[1]}")
            if self.options.verbose:
                say(f"set parameter [{key}]")

    async def _advertise(self) -> None:
        host = urlsplit(self.master_uri).hostname or "localhost"
        self.server = XmlRpcServer(_LaunchApi(self), "0.0.0.0", 0, advertise_host=host)
        await self.server.start()
        key_host = socket.gethostname().replace(".", "_").replace("-", "_")
        await self._call("setParam", f"/roslaunch/uris/host_{key_host}__{self.server.port}", self.server.uri)

    # -- nodes -------------------------------------------------------------------------------------------------

    def _plan(self, node: NodeSpec, counter: int, run_dir: Path) -> ProcessPlan:
        label = log_label(node, counter)
        argv = node_argv(node, self.anons) + [f"__log:={run_dir / (label + '.log')}"]
        env = node_env(node, self.master_uri)
        if node.cwd == "node":
            exe = len(shlex.split(node.launch_prefix or ""))
            if argv[exe] == sys.executable:  # a built-in Python script run by this Python
                exe += 1
            cwd = str(Path(argv[exe]).resolve().parent)
        else:
            cwd = str(ros_home())
            Path(cwd).mkdir(parents=True, exist_ok=True)
        to_screen = self.options.screen or node.output == "screen"
        stdout_log = None if to_screen else run_dir / f"{label}-stdout.log"
        return ProcessPlan(node, label, argv, env, cwd, stdout_log)

    async def _start_nodes(self, run_dir: Path) -> None:
        counter = 0
        for node in self.config.nodes:
            if self.stopping.is_set():
                return
            counter += 1
            name = node.resolved_name
            problem = prefix_problem(node)
            if problem:
                complain(f"ERROR: cannot launch node [{name}]: {problem}; the other nodes keep running")
                continue
            try:
                plan = self._plan(node, counter, run_dir)
            except LaunchError as exc:
                complain(f"ERROR: {exc.message}")
                continue
            process = ManagedProcess(plan)
            try:
                await process.start()
            except OSError as exc:
                complain(f"ERROR: cannot launch node [{name}]: {plan.argv[0]}: {exc.strerror or exc}")
                continue
            self.processes.append(process)
            say(f"process[{plan.label}]: started with pid [{process.pid}]")
            asyncio.get_running_loop().create_task(self._watch(process))

    async def _watch(self, process: ManagedProcess) -> None:
        backoff = 0.0
        while True:
            assert process.proc is not None
            code = await process.proc.wait()
            if self.stopping.is_set():
                return
            plan = process.plan
            ran_for = time.monotonic() - process.started_at
            where = f", log file: {plan.stdout_log}" if plan.stdout_log else ""
            if code == 0:
                say(f"[{plan.label}] process has finished cleanly{where}")
            else:
                complain(f"[{plan.label}] process has died [pid {process.pid}, exit code {code}, "
                         f"cmd {' '.join(plan.argv)}]{where}")
            node = plan.spec
            if node.required:
                complain(f"REQUIRED process [{plan.label}] has died! Initiating shutdown!")
                self.exit_code = 1 if code != 0 else 0
                self.stopping.set()
                return
            if not node.respawn:
                if all(p.proc is not None and p.proc.returncode is not None and not p.plan.spec.respawn
                       for p in self.processes) and self.embedded is None:
                    say("all processes on machine have died, roslaunch will exit")
                    self.stopping.set()
                return
            backoff = min(MAX_BACKOFF, max(1.0, backoff * 2)) if ran_for < QUICK_DEATH else 0.0
            delay = node.respawn_delay + backoff
            if delay > 0:
                say(f"[{plan.label}] restarting process in {delay:g} s")
                try:
                    await asyncio.wait_for(self.stopping.wait(), delay)
                    return
                except asyncio.TimeoutError:
                    pass
            else:
                say(f"[{plan.label}] restarting process")
            process.reap_orphans()
            try:
                await process.start()
            except OSError as exc:
                complain(f"ERROR: cannot restart [{plan.label}]: {exc.strerror or exc}")
                return
            say(f"process[{plan.label}]: restarted with pid [{process.pid}]")

    # -- run and stop ------------------------------------------------------------------------------------------

    async def run(self) -> int:
        """Set everything up, start the nodes and wait until the launch ends; returns the exit status."""
        loop = asyncio.get_running_loop()
        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            loop.add_signal_handler(signum, self._on_signal)
        try:
            await self._master()
            self.run_id = await self._run_id()
            run_dir = run_log_dir(self.run_id)
            say(f"logging to {run_dir}")
            await self._rosparam_commands()
            await self._set_params()
            await self._advertise()
            await self._start_nodes(run_dir)
            if not self.processes and self.embedded is None and not self.stopping.is_set():
                say("no nodes to run, roslaunch will exit")
                self.stopping.set()
            await self.stopping.wait()
        except (XmlRpcError, OSError) as exc:
            complain(f"ERROR: cannot talk to the master at {self.master_uri}: {exc}")
            self.exit_code = 1
        finally:
            await self.shutdown()
        return self.exit_code

    def _on_signal(self) -> None:
        if not self.stopping.is_set():
            say("shutting down processing monitor...")
        self.stopping.set()

    async def shutdown(self) -> None:
        """Stop every node (SIGINT, SIGTERM, SIGKILL after the timeouts), then the API server and the master."""
        self.stopping.set()
        stops = [p.stop(self.options.sigint_timeout, self.options.sigterm_timeout) for p in self.processes]
        results = await asyncio.gather(*stops, return_exceptions=True)
        for process, how in zip(self.processes, results):
            if how in ("SIGTERM", "SIGKILL"):
                complain(f"[{process.plan.label}] did not stop on SIGINT: sent {how}")
            process.close_log()
        if self.server is not None:
            await self.server.close()
        if self.embedded is not None:
            await self.embedded.stop()
        say("done")


def run_launch(request: LaunchRequest, options: SupervisorOptions) -> int:
    """Load the files (any error: nothing starts), check machines, then supervise; returns the exit status."""
    config, loader = load_config(request)
    for warning in config.warnings:
        complain(f"WARNING: {warning}")
    check_machines(config)
    for node in config.nodes:
        node_argv(node, loader.anons)  # every executable must exist before anything starts
    if options.verbose:
        for node in config.nodes:
            say(f"node {node.resolved_name}: {node.package}/{node.type}")
    supervisor = Supervisor(config, loader.anons, options)
    return asyncio.run(supervisor.run())
