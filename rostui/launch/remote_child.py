"""The child side of remote launch: ``rostui launch --child NAME -u PARENT_URI --run_id ID``.

A parent launcher (rostui's or a real roslaunch) starts this over SSH on a
remote machine.  It serves roslaunch's child API (``launch``, ``shutdown``,
``get_pid``, ``list_processes``), registers with the parent, runs the nodes
each ``launch`` call sends with the same supervisor as a local launch
(output, respawn, ``required``, SIGINT then SIGTERM then SIGKILL), tells the
parent about its lines (``log``) and every death (``process_died``), and
sends each node's output lines back as ``[LABEL]<TAB>TEXT`` on its own stdout and
stderr (the SSH connection).  It sets no params and starts no master.  It
stops every node and exits on ``shutdown``, when its last node has ended (as
roslaunch's child), when the parent has not answered for 20 s (a lost
network), or when its stdin closes (the SSH connection is gone).
"""

from __future__ import annotations

import asyncio
import os
import signal
import sys
import tempfile
from pathlib import Path
from typing import Any

from rostui.core.log.files import run_log_dir
from rostui.core.network import resolve_addressing
from rostui.core.xmlrpc import XmlRpcClient, XmlRpcError
from rostui.core.xmlrpc.server import XmlRpcServer
from rostui.launch.errors import LaunchError
from rostui.launch.loader import XmlLoader
from rostui.launch.model import LaunchConfig, NodeSpec
from rostui.launch.output import OutputBuffer
from rostui.launch.process import ManagedProcess, NodeState, ProcessPlan
from rostui.launch.remote_protocol import LOG_ERROR, LOG_INFO, format_output_line
from rostui.launch.supervisor import Supervisor, SupervisorOptions, log_label, prefix_problem

#: Seconds the child waits for the parent to answer a call before it gives the parent up.
PARENT_TIMEOUT = 15.0
#: Seconds between the child's checks that its parent still answers (``get_pid``).
PARENT_CHECK_INTERVAL = 2.0
#: Seconds without an answer from the parent after which the child stops its nodes and exits.
PARENT_GIVE_UP = 20.0


class ForwardedOutput(OutputBuffer):
    """A node's output ring that also writes each of its lines to the SSH connection as ``[LABEL]<TAB>TEXT``.

    stderr lines always go, stdout lines only for a node whose output goes to
    the screen (``output="screen"`` or ``--screen``), as on a local launch.
    """

    def __init__(self, label: str, screen: bool) -> None:
        """The ring of node ``label``; ``screen``: its stdout is shown too."""
        super().__init__(max_lines=200)
        self.label = label
        self.screen = screen

    def append(self, stream: str, text: str) -> None:
        """Keep the line and, if it is the node's own output to show, send it on."""
        super().append(stream, text)
        if stream == "stderr" or (stream == "stdout" and self.screen):
            target = sys.stderr if stream == "stderr" else sys.stdout
            try:
                target.write(format_output_line(self.label, text) + "\n")
                target.flush()
            except (OSError, ValueError):
                pass  # the connection is gone; stdin's end of file stops the launch


class _ChildApi:
    """roslaunch's child XML-RPC API (no caller ids)."""

    def __init__(self, child: "ChildLauncher") -> None:
        self._child = child

    async def launch(self, launch_xml: str) -> list[Any]:
        return await self._child.launch_xml(str(launch_xml))

    async def shutdown(self) -> list[Any]:
        self._child.answering += 1
        try:
            self._child.request_stop()
            await self._child.finished.wait()
            return [1, "success", 1]
        finally:
            self._child.answering -= 1

    def get_pid(self) -> list[Any]:
        return [1, str(os.getpid()), os.getpid()]

    def getPid(self, *_: Any) -> list[Any]:  # noqa: N802 (XML-RPC name)
        return self.get_pid()

    def list_processes(self) -> list[Any]:
        running = [[p.label, p.starts] for p in self._child.processes if p.running]
        dead = [[p.label, p.starts] for p in self._child.processes if p.starts and not p.running]
        return [1, "processes on child machine", [running, dead]]

    def get_node_names(self) -> list[Any]:
        return [1, "node names", [p.name for p in self._child.processes if p.running]]


class ChildLauncher(Supervisor):
    """A launch on a remote machine, run on behalf of a parent launcher."""

    def __init__(self, name: str, parent_uri: str, run_id: str, options: SupervisorOptions) -> None:
        """Child ``name`` of the parent at ``parent_uri``, for the parent's ``run_id``."""
        options.capture = True  # each line goes to the parent tagged with its node
        options.handle_signals = True
        super().__init__(LaunchConfig(), {}, options, reporter=self._report)
        self.name = name
        self.parent_uri = parent_uri
        self.run_id = run_id
        self._counter = 0
        self.answering = 0
        """``shutdown`` calls of the parent still waiting for their answer."""
        self._outbox: asyncio.Queue[tuple[str, tuple[Any, ...]]] | None = None

    # -- talking to the parent ---------------------------------------------------------------------------------

    def _report(self, message: str, error: bool) -> None:
        self._send("log", self.name, LOG_ERROR if error else LOG_INFO, message)

    def _send(self, method: str, *args: Any) -> None:
        """Queue a call to the parent (sent in order by :meth:`_deliver`)."""
        if self._outbox is not None:
            self._outbox.put_nowait((method, args))

    async def _deliver(self) -> None:
        assert self._outbox is not None
        client = XmlRpcClient(self.parent_uri, timeout=PARENT_TIMEOUT)
        try:
            while True:
                method, args = await self._outbox.get()
                try:
                    await client.call(method, *args)
                except (XmlRpcError, OSError):
                    if not self.stopping.is_set():
                        print(f"rostui launch --child: the parent at {self.parent_uri} does not answer; stopping",
                              file=sys.stderr, flush=True)
                        self.stopping.set()
                finally:
                    self._outbox.task_done()
        finally:
            await client.close()

    async def _watch_parent(self) -> None:
        """Stop the launch when the parent has not answered for :data:`PARENT_GIVE_UP` seconds (a lost network)."""
        loop = asyncio.get_running_loop()
        last_answer = loop.time()
        while not self.stopping.is_set():
            await asyncio.sleep(PARENT_CHECK_INTERVAL)
            client = XmlRpcClient(self.parent_uri, timeout=PARENT_CHECK_INTERVAL * 2)
            try:
                await client.call("get_pid")
                last_answer = loop.time()
            except (XmlRpcError, OSError):
                if loop.time() - last_answer > PARENT_GIVE_UP:
                    print(f"rostui launch --child: the parent at {self.parent_uri} has not answered for "
                          f"{PARENT_GIVE_UP:g} s; stopping", file=sys.stderr, flush=True)
                    self.request_stop()
            finally:
                await client.close()

    def _exited(self, process: ManagedProcess, code: int) -> None:
        self._send("process_died", process.label, code)

    # -- the parent's launch calls -----------------------------------------------------------------------------

    async def launch_xml(self, xml: str) -> list[Any]:
        """Start the nodes of a ``<launch>`` document; ``[1, msg, [started labels, failed labels]]``."""
        if self.stopping.is_set():
            return [0, "the child is shutting down", [[], []]]
        try:
            nodes, anons = _load_string(xml)
        except LaunchError as exc:
            return [-1, f"ERROR: {exc}", [[], []]]
        self.anons.update(anons)
        run_dir = run_log_dir(self.run_id)
        started: list[str] = []
        failed: list[str] = []
        self._report("launching nodes...", False)
        for node in nodes:
            self._counter += 1
            process = self._prepare(node, self._counter, run_dir)
            self.processes.append(process)
            ok = False
            if process.state is not NodeState.FAILED:
                async with process.lock:
                    ok = await self._spawn(process, "started")
            (started if ok else failed).append(process.label)
        self._report("... done launching nodes", False)
        return [1, "launched", [started, failed]]

    def _prepare(self, node: NodeSpec, counter: int, run_dir: Path) -> ManagedProcess:
        problem = prefix_problem(node)
        try:
            plan = self._plan(node, counter, run_dir)  # finds the executable, or raises LaunchError
        except LaunchError as exc:
            problem = problem or exc.message
            plan = ProcessPlan(node, log_label(node, counter), [], {}, "", None, True)
        process = ManagedProcess(plan)
        process.output = ForwardedOutput(plan.label, self.options.screen or node.output == "screen")
        if problem:
            process.state = NodeState.FAILED
            process.problem = problem
            self.complain(f"ERROR: cannot launch node [{node.resolved_name}]: {problem}")
        return process

    # -- running -----------------------------------------------------------------------------------------------

    async def run(self) -> int:
        """Serve the child API, register with the parent and run until told to stop; the exit status."""
        loop = asyncio.get_running_loop()
        for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            loop.add_signal_handler(signum, self.request_stop)
        self._outbox = asyncio.Queue()
        deliver = loop.create_task(self._deliver())
        watch_stdin = loop.create_task(_until_stdin_closes())
        watch_stdin.add_done_callback(lambda _task: self.request_stop())
        try:
            addressing = resolve_addressing(self.master_uri)
            self.server = XmlRpcServer(_ChildApi(self), addressing.bind_host, 0,
                                       advertise_host=addressing.advertise_host)
            await self.server.start()
            client = XmlRpcClient(self.parent_uri, timeout=PARENT_TIMEOUT)
            try:
                reply = await client.call("register", self.name, self.server.uri)
            finally:
                await client.close()
            if not (isinstance(reply, list) and reply and reply[0] == 1):
                raise LaunchError(f"the parent at {self.parent_uri} refused child [{self.name}]: {reply}")
            watch_parent = loop.create_task(self._watch_parent())
            await self.stopping.wait()
            watch_parent.cancel()
        except (XmlRpcError, OSError) as exc:
            print(f"rostui launch --child: cannot reach the parent at {self.parent_uri}: {exc}", file=sys.stderr,
                  flush=True)
            self.exit_code = 1
        finally:
            watch_stdin.cancel()
            server, self.server = self.server, None
            await self.shutdown()
            for _ in range(100):  # the parent's shutdown call gets its answer before the server goes
                if not self.answering:
                    break
                await asyncio.sleep(0.02)
            if server is not None:
                await server.close()
            try:
                await asyncio.wait_for(self._outbox.join(), 5.0)
            except asyncio.TimeoutError:
                pass
            deliver.cancel()
        return self.exit_code

    def say(self, message: str) -> None:
        """A line of the child's own: to the parent (``log``) only, so the connection carries node lines alone."""
        self.launch_output.append("launch", message)
        self._report(message, False)

    def complain(self, message: str) -> None:
        """An error line of the child's own, to the parent."""
        self.launch_output.append("error", message)
        self._report(message, True)


def _load_string(xml: str) -> tuple[list[NodeSpec], dict[str, str]]:
    """The nodes of a ``<launch>`` document sent by the parent (read with the same loader as files)."""
    with tempfile.NamedTemporaryFile("w", suffix=".launch", encoding="utf-8", delete=False) as handle:
        handle.write(xml)
        path = handle.name
    try:
        config = LaunchConfig()
        loader = XmlLoader()
        loader.load(path, config, {})
        return config.nodes, loader.anons
    finally:
        os.unlink(path)


async def _until_stdin_closes() -> None:
    """Return when stdin reaches end of file (the SSH connection that started the child has closed)."""
    loop = asyncio.get_running_loop()
    reader = asyncio.StreamReader()
    try:
        if os.path.samefile(f"/proc/self/fd/{sys.stdin.fileno()}", os.devnull):
            raise ValueError("stdin is /dev/null")
        await loop.connect_read_pipe(lambda: asyncio.StreamReaderProtocol(reader), sys.stdin)
    except (OSError, ValueError):
        await asyncio.Event().wait()  # stdin is not a pipe (a terminal, /dev/null): nothing to watch
    while await reader.read(4096):
        pass


def run_child(name: str, parent_uri: str, run_id: str, options: SupervisorOptions) -> int:
    """``rostui launch --child``: run until the parent or the connection ends it; the exit status."""
    return asyncio.run(ChildLauncher(name, parent_uri, run_id, options).run())
