"""Run a launch: master, params, then every node; respawn, required, and a clean Ctrl-C.

The master (with ``/rosout``) runs inside this process, on its event loop, when
none answers at ROS_MASTER_URI (see :func:`rostui.core.master.embedded.ensure_master`);
a running master is reused.  Order, as roslaunch: ``<rosparam command="delete|dump">``,
then ``clear_params``, then every param, then ``/roslaunch/uris/host_<host>__<port>``,
then the nodes.  Node stdout goes to ``$ROS_HOME/log/<run_id>/<name>-N-stdout.log``
unless ``output="screen"`` or ``--screen``; stderr always goes to the console.

With ``capture`` (``rostui launch --tui``) both streams of every node come
through pipes into the node's output ring instead (stdout still also into its
log file), the launcher's own lines go to :attr:`Supervisor.launch_output`,
and the monitor drives the launch through :meth:`Supervisor.start_node`,
:meth:`Supervisor.stop_node`, :meth:`Supervisor.restart_node` and
:meth:`Supervisor.request_stop`.
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
from pathlib import Path
from typing import Any, Callable
from urllib.parse import urlsplit, urlunsplit

import yaml

from rostui.core.log.files import ros_home, run_log_dir
from rostui.core.msg import MessageError
from rostui.core.network import resolve_addressing
from rostui.core.master.embedded import EmbeddedMaster, MasterStartError, ensure_master, \
    master_answers
from rostui.core.xmlrpc import XmlRpcClient, XmlRpcError
from rostui.core.xmlrpc.server import XmlRpcServer
from rostui.launch.errors import LaunchError
from rostui.launch.files import LaunchRequest
from rostui.launch.inspect import load_config, node_env
from rostui.launch.python_nodes import node_command
from rostui.launch.summary import launch_summary
from rostui.launch.machines import assign_machines
from rostui.launch.model import LaunchConfig, Machine, NodeSpec
from rostui.launch.output import OutputBuffer
from rostui.launch.process import ManagedProcess, NodeState, ProcessPlan
from rostui.launch.options import SupervisorOptions
from rostui.launch.remote_parent import RemoteLaunch, RemoteProcess

CALLER = "/roslaunch"
#: A respawned node that dies within this many seconds of starting is restarted with a growing delay.
QUICK_DEATH = 1.0
#: The longest back-off between restarts of a node that keeps dying at once.
MAX_BACKOFF = 30.0


#: Receives each line of the launcher's own output and whether it is an error (stderr).
Reporter = Callable[[str, bool], None]


def keep_quiet(_message: str, _error: bool) -> None:
    """A reporter that prints nothing: the lines stay only in :attr:`Supervisor.launch_output` (for the monitor)."""


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


def remote_machine(config: LaunchConfig, node: NodeSpec) -> Machine | None:
    """The machine ``node`` runs on when :func:`assign_machines` found it is another host (or user), else None."""
    return config.machine_of(node) if node.remote else None


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

    def get_pid(self, *_: Any) -> list[Any]:
        """roslaunch's name for :meth:`getPid` (its server takes no caller id)."""
        return self.getPid()

    def list_processes(self, *_: Any) -> list[Any]:
        processes = [p for p in self._supervisor.processes if p.proc is not None]
        running = [[p.plan.label, p.starts] for p in processes if p.proc and p.proc.returncode is None]
        dead = [[p.plan.label, p.starts] for p in processes if p.proc and p.proc.returncode is not None]
        return [1, "processes on this launcher", [running, dead]]

    def register(self, client: str, uri: str) -> list[Any]:
        """roslaunch's parent API: a child on a remote machine says where its XML-RPC server is."""
        return self._supervisor.remote.register(client, uri)

    def list_children(self) -> list[Any]:
        """roslaunch's parent API: the XML-RPC URIs of the registered children."""
        return self._supervisor.remote.list_children()

    def process_died(self, label: str, exit_code: int) -> list[Any]:
        """roslaunch's parent API: a node on a remote machine has ended."""
        return self._supervisor.remote.process_died(label, exit_code)

    def log(self, client: str, level: int, message: str) -> list[Any]:
        """roslaunch's parent API: a line of a child's own output."""
        return self._supervisor.remote.log(client, level, message)


class Supervisor:
    """Starts a loaded launch and keeps it running until Ctrl-C, a required node's death or all nodes ending.

    ``reporter`` receives the launcher's own lines (default: stdout, errors on
    stderr).  Every node of the file has a :class:`ManagedProcess` in
    :attr:`processes` once the master answers, in file order.
    """

    def __init__(self, config: LaunchConfig, anons: dict[str, str], options: SupervisorOptions,
                 reporter: Reporter | None = None) -> None:
        """Keep the config, the launch's anon names, the options and where the launcher's lines go."""
        self.config = config
        self.anons = anons
        self.options = options
        self.processes: list[ManagedProcess] = []
        self.master_uri = master_uri_for(options)
        self.embedded: EmbeddedMaster | None = None
        self.server: XmlRpcServer | None = None
        self.stopping = asyncio.Event()
        self.finished = asyncio.Event()
        """Set once :meth:`run` has stopped every node and the master."""
        self.exit_code = 0
        self.run_id = ""
        self.end_reason = ""
        """Why the launch ended by itself (a required node died, every node ended), for the monitor."""
        self.launch_output = OutputBuffer()
        """The launcher's own lines (what ``rostui launch`` prints)."""
        self._reporter = reporter
        self._watchers: dict[int, asyncio.Task[None]] = {}
        self._failures: dict[int, str] = {}
        self.remote = RemoteLaunch(self)
        """The children on other machines (roslaunch's remote protocol over SSH)."""

    # -- the launcher's own lines ------------------------------------------------------------------------------

    def say(self, message: str) -> None:
        """A line of the launcher's output."""
        self.launch_output.append("launch", message)
        if self._reporter is not None:
            self._reporter(message, False)
        else:
            say(message)

    def complain(self, message: str) -> None:
        """A line of the launcher's error output."""
        self.launch_output.append("error", message)
        if self._reporter is not None:
            self._reporter(message, True)
        else:
            complain(message)

    # -- set-up ------------------------------------------------------------------------------------------------

    async def _master(self) -> None:
        if self.options.wait:
            announced = False
            while not await master_answers(self.master_uri, timeout=1.0):
                if not announced:
                    self.say(f"roslaunch: waiting for a master at {self.master_uri}")
                    announced = True
                try:
                    await asyncio.wait_for(self.stopping.wait(), 0.5)
                    raise LaunchError("stopped while waiting for a master")
                except asyncio.TimeoutError:
                    continue
            return
        try:
            self.embedded = await ensure_master(self.master_uri)
        except MasterStartError as exc:
            raise LaunchError(str(exc)) from None
        except MessageError as exc:  # the in-process /rosout needs rosgraph_msgs/Log
            reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            raise LaunchError(f"cannot start a master with /rosout: {reason}") from None
        if self.embedded is not None:
            self.say(f"started master (in this process) and /rosout at {self.embedded.uri}")

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
                    self.complain(f"WARNING: rosparam delete {command.param}: {reply[1]}")
            else:
                reply = await self._call("getParam", command.param)
                if reply[0] != 1:
                    self.complain(f"WARNING: rosparam dump {command.param}: {reply[1]}")
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
                self.say(f"set parameter [{key}]")

    async def _advertise(self) -> None:
        # Like every server of a node: ROS_IP / ROS_HOSTNAME, else loopback only when the master is local.
        addressing = resolve_addressing(self.master_uri)
        self.server = XmlRpcServer(_LaunchApi(self), addressing.bind_host, 0,
                                   advertise_host=addressing.advertise_host)
        await self.server.start()
        key_host = socket.gethostname().replace(".", "_").replace("-", "_")
        await self._call("setParam", f"/roslaunch/uris/host_{key_host}__{self.server.port}", self.server.uri)

    # -- nodes -------------------------------------------------------------------------------------------------

    def _plan(self, node: NodeSpec, counter: int, run_dir: Path) -> ProcessPlan:
        label = log_label(node, counter)
        env = node_env(node, self.master_uri)
        if self.options.capture:
            env.setdefault("PYTHONUNBUFFERED", "1")  # a Python node's prints reach the monitor as they happen
        command = node_command(node, self.anons, env, [f"__log:={run_dir / (label + '.log')}"])
        argv, env = command.argv, command.env
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
        return ProcessPlan(node, label, argv, env, cwd, stdout_log, capture=self.options.capture,
                           notice=command.notice)

    def _prepare_nodes(self, run_dir: Path) -> None:
        """One process entry per node, in file order (a node that cannot run is marked FAILED, not dropped)."""
        for counter, node in enumerate(self.config.nodes, start=1):
            machine = remote_machine(self.config, node)
            if machine is not None:
                plan = ProcessPlan(node, log_label(node, counter), [], {}, "", None, self.options.capture)
                self.processes.append(self.remote.add(RemoteProcess(plan, machine=machine)))
                continue
            problem = prefix_problem(node)
            message = f"ERROR: cannot launch node [{node.resolved_name}]: {problem}; the other nodes keep running"
            try:
                plan = self._plan(node, counter, run_dir)
            except LaunchError as exc:
                plan = ProcessPlan(node, log_label(node, counter), [], {}, "", None, self.options.capture)
                problem, message = problem or exc.message, f"ERROR: {exc.message}"
            process = ManagedProcess(plan)
            if problem:
                process.state = NodeState.FAILED
                process.problem = problem
                self._failures[id(process)] = message
            self.processes.append(process)

    async def _start_nodes(self) -> None:
        for process in self.processes:
            if self.stopping.is_set():
                return
            if process.state is NodeState.STOPPED or isinstance(process, RemoteProcess):
                continue  # stopped from the monitor before its turn came, or started by its machine's child
            if process.state is NodeState.FAILED:
                message = self._failures[id(process)]
                self.complain(message)
                process.note(message, error=True)
                continue
            async with process.lock:
                await self._spawn(process, "started")

    async def _spawn(self, process: ManagedProcess, verb: str) -> bool:
        """Start ``process`` (the caller holds its lock) and watch it; False when it cannot be executed."""
        plan = process.plan
        process.reap_orphans()
        try:
            await process.start()
        except OSError as exc:
            message = f"ERROR: cannot launch node [{process.name}]: {plan.argv[0]}: {exc.strerror or exc}"
            self.complain(message)
            process.state = NodeState.FAILED
            process.problem = f"{plan.argv[0]}: {exc.strerror or exc}"
            process.note(message, error=True)
            return False
        message = f"process[{plan.label}]: {verb} with pid [{process.pid}]"
        self.say(message)
        process.note(message)
        self._watchers[id(process)] = asyncio.get_running_loop().create_task(self._watch(process))
        return True

    def _all_ended(self) -> bool:
        return all(p.state.ended and not p.plan.spec.respawn for p in self.processes)

    async def _watch(self, process: ManagedProcess) -> None:
        backoff = 0.0
        while True:
            assert process.proc is not None
            code = await process.proc.wait()
            await process.drain(0.5, give_up=False)  # its last lines come before the news of its death
            if self.stopping.is_set():
                return
            plan = process.plan
            ran_for = time.monotonic() - process.started_at
            process.exit_code = code
            process.state = NodeState.FINISHED if code == 0 else NodeState.DIED
            where = f", log file: {plan.stdout_log}" if plan.stdout_log else ""
            if code == 0:
                message = f"[{plan.label}] process has finished cleanly{where}"
                self.say(message)
            else:
                message = (f"[{plan.label}] process has died [pid {process.pid}, exit code {code}, "
                           f"cmd {' '.join(plan.argv)}]{where}")
                self.complain(message)
            process.note(message, error=code != 0)
            self._exited(process, code)
            node = plan.spec
            if self.node_ended(process, code):
                return
            backoff = min(MAX_BACKOFF, max(1.0, backoff * 2)) if ran_for < QUICK_DEATH else 0.0
            delay = node.respawn_delay + backoff
            process.state = NodeState.RESPAWNING
            process.respawn_at = time.monotonic() + delay
            if delay > 0:
                message = f"[{plan.label}] restarting process in {delay:g} s"
                self.say(message)
                process.note(message)
                try:
                    await asyncio.wait_for(self.stopping.wait(), delay)
                    return
                except asyncio.TimeoutError:
                    pass
            else:
                self.say(f"[{plan.label}] restarting process")
            async with process.lock:
                if self.stopping.is_set():
                    return
                process.reap_orphans()
                try:
                    await process.start()
                except OSError as exc:
                    self.complain(f"ERROR: cannot restart [{plan.label}]: {exc.strerror or exc}")
                    process.state = NodeState.FAILED
                    process.problem = str(exc.strerror or exc)
                    return
            message = f"process[{plan.label}]: restarted with pid [{process.pid}]"
            self.say(message)
            process.note(message)

    def _exited(self, process: ManagedProcess, code: int) -> None:
        """Called once for each death of a node's process, before the launch decides what follows."""

    def node_ended(self, process: ManagedProcess, code: int | None) -> bool:
        """After a node's death: end the launch for a ``required`` node or when every node has ended.

        True when the node will not be restarted (it is not ``respawn``).
        """
        node = process.plan.spec
        if node.required:
            self.complain(f"REQUIRED process [{process.label}] has died! Initiating shutdown!")
            self.end_reason = f"required node {process.name} has died (exit code {code}): the launch was shut down"
            self.exit_code = 1 if code != 0 else 0
            self.stopping.set()
            return True
        if not node.respawn:
            if self._all_ended() and self.embedded is None and not self.options.stay_when_all_ended:
                self.say("all processes on machine have died, roslaunch will exit")
                self.end_reason = "every node has ended: the launch is over"
                self.stopping.set()
            return True
        return False

    # -- control of one node (the monitor's start, stop and restart) ------------------------------------------

    def process_named(self, name: str) -> ManagedProcess:
        """The process of the node whose global name (or roslaunch label) is ``name``; LaunchError if none."""
        for process in self.processes:
            if name in (process.name, process.label):
                return process
        raise LaunchError(f"no node [{name}] in this launch")

    async def _unwatch(self, process: ManagedProcess) -> None:
        watcher = self._watchers.pop(id(process), None)
        if watcher is not None and not watcher.done():
            watcher.cancel()
            await asyncio.gather(watcher, return_exceptions=True)

    @staticmethod
    def _refuse_remote(process: ManagedProcess) -> None:
        if isinstance(process, RemoteProcess):
            raise LaunchError(f"node [{process.name}] runs on machine [{process.machine.name}]: it starts and "
                              "stops with the whole launch")

    def _check_open(self, process: ManagedProcess) -> None:
        if self.stopping.is_set():
            raise LaunchError("the launch is shutting down")
        self._refuse_remote(process)
        if process.state is NodeState.FAILED and not process.plan.argv:
            raise LaunchError(f"node [{process.name}] cannot be started: {process.problem}")

    async def _stop_locked(self, process: ManagedProcess, why: str) -> None:
        await self._unwatch(process)
        if process.running:
            process.state = NodeState.STOPPING
            how = await process.stop(self.options.sigint_timeout, self.options.sigterm_timeout)
            assert process.proc is not None
            process.exit_code = process.proc.returncode
            message = f"[{process.label}] {why} (ended on {how})" if how != "exited" else f"[{process.label}] {why}"
            self.say(message)
            process.note(message)
        process.state = NodeState.STOPPED
        process.respawn_at = None

    async def stop_node(self, name: str) -> None:
        """Stop one node as Ctrl-C would (SIGINT, SIGTERM, SIGKILL after the timeouts); it is not respawned.

        A stopped node stays stopped until :meth:`start_node` or :meth:`restart_node`;
        stopping a ``required`` node this way does not end the launch.
        """
        process = self.process_named(name)
        async with process.lock:
            if self.stopping.is_set():
                raise LaunchError("the launch is shutting down")
            self._refuse_remote(process)
            await self._stop_locked(process, "stopped on request")

    async def start_node(self, name: str) -> bool:
        """Start a node that is not running (stopped, ended, respawning: now); False when it cannot be executed."""
        process = self.process_named(name)
        async with process.lock:
            self._check_open(process)
            if process.running:
                return True
            await self._unwatch(process)
            return await self._spawn(process, "started on request")

    async def restart_node(self, name: str) -> bool:
        """Stop a node (when it runs) and start it again with a new process; False when it cannot be executed."""
        process = self.process_named(name)
        async with process.lock:
            self._check_open(process)
            await self._stop_locked(process, "stopped for a restart")
            return await self._spawn(process, "restarted on request")

    def request_stop(self) -> None:
        """Begin the shutdown (as Ctrl-C does); :attr:`finished` is set when every node is stopped."""
        if not self.stopping.is_set():
            self.say("shutting down processing monitor...")
        self.stopping.set()

    # -- run and stop ------------------------------------------------------------------------------------------

    async def run(self) -> int:
        """Set everything up, start the nodes and wait until the launch ends; returns the exit status."""
        loop = asyncio.get_running_loop()
        if self.options.handle_signals:
            for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
                loop.add_signal_handler(signum, self.request_stop)
        try:
            for line in launch_summary(self.config).split("\n"):
                self.say(line)
            await self._master()
            self.run_id = await self._run_id()
            run_dir = run_log_dir(self.run_id)
            self.say(f"logging to {run_dir}")
            await self._rosparam_commands()
            await self._set_params()
            await self._advertise()
            self._prepare_nodes(run_dir)
            assert self.server is not None
            await self.remote.start_children(self.server.uri, self.run_id)
            await self._start_nodes()
            await self.remote.launch_nodes()
            started = [p for p in self.processes if p.starts]
            if not started and self.embedded is None and not self.stopping.is_set() \
                    and not self.options.stay_when_all_ended:
                self.say("no nodes to run, roslaunch will exit")
                self.end_reason = "no node could run: the launch is over"
                self.stopping.set()
            await self.stopping.wait()
        except (XmlRpcError, OSError) as exc:
            self.complain(f"ERROR: cannot talk to the master at {self.master_uri}: {exc}")
            self.end_reason = f"cannot talk to the master at {self.master_uri}: {exc}"
            self.exit_code = 1
        finally:
            await self.shutdown()
        return self.exit_code

    async def _stop_for_shutdown(self, process: ManagedProcess) -> str:
        if isinstance(process, RemoteProcess):
            return "exited"  # its machine's child stops it (RemoteLaunch.shutdown)
        async with process.lock:
            was_running = process.running
            if was_running:
                process.state = NodeState.STOPPING
            how = await process.stop(self.options.sigint_timeout, self.options.sigterm_timeout)
            if was_running:
                process.state = NodeState.STOPPED
                process.note(f"[{process.label}] stopped by the launch's shutdown")
            if process.state is NodeState.RESPAWNING:
                process.state = NodeState.STOPPED
                process.respawn_at = None
            return how

    async def shutdown(self) -> None:
        """Stop every node (SIGINT, SIGTERM, SIGKILL after the timeouts), then the API server and the master."""
        self.stopping.set()
        try:
            stops = [self._stop_for_shutdown(p) for p in self.processes]
            remote = asyncio.get_running_loop().create_task(self.remote.shutdown())
            results = await asyncio.gather(*stops, return_exceptions=True)
            await remote
            for process, how in zip(self.processes, results):
                if how in ("SIGTERM", "SIGKILL"):
                    self.complain(f"[{process.plan.label}] did not stop on SIGINT: sent {how}")
                await process.drain()
                process.close_log()
            for watcher in self._watchers.values():
                watcher.cancel()
            if self.server is not None:
                await self.server.close()
            if self.embedded is not None:
                await self.embedded.stop()
            self.say("done")
        finally:
            self.finished.set()


    def kill_leftovers(self) -> None:
        """SIGKILL every process of every node still alive (the last resort when the event loop is gone)."""
        for process in self.processes:
            process.reap_orphans()
            process.close_log()


def load_supervisor(request: LaunchRequest, options: SupervisorOptions,
                    reporter: Reporter | None = None) -> Supervisor:
    """Load the files (any error raises LaunchError: nothing starts), check machines and executables."""
    config, loader = load_config(request)
    supervisor = Supervisor(config, loader.anons, options, reporter)
    for warning in config.warnings:
        supervisor.complain(f"WARNING: {warning}")
    assign_machines(config)  # a node that cannot run is reported when its turn comes, and the others start
    if options.verbose:
        for node in config.nodes:
            supervisor.say(f"node {node.resolved_name}: {node.package}/{node.type}")
    return supervisor


def run_launch(request: LaunchRequest, options: SupervisorOptions) -> int:
    """Load the files (any error: nothing starts), check machines, then supervise; returns the exit status."""
    supervisor = load_supervisor(request, options)
    return asyncio.run(supervisor.run())
