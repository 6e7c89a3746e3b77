"""A rostui node outlives its master: a new master at the same URI learns everything the node has.

ROS 1 nodes register once; after a master restart they are unknown to it, and no new subscriber finds an
old publisher.  A rostui node checks about every second who answers at its master URI (pid, ``/run_id``, or
no answer then an answer) and registers again its publishers, subscribers, services and parameter
subscriptions.  Tested with `rostui core` killed with SIGKILL and started again on the same port, rostui
nodes in other processes and one in this process, and real command-line clients afterwards.
"""

from __future__ import annotations

import asyncio
import os
import subprocess
from typing import Any, Iterator

import pytest

from interop_helpers import Spawn, rostui_peer, run_tool, spawn  # noqa: F401  (spawn is a fixture)
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node import AsyncNode
from rostui.core.node.engine import Engine
from rostui.core.xmlrpc import XmlRpcServer, call_sync

from conftest import free_port, master_port, rostui_cmd, start_rostui_core, stop_process, wait_until
from test_node import run, until

String = get_message_class("std_msgs/String")
SetBool = get_service_class("std_srvs/SetBool")

#: The promise: every rostui node is known to a restarted master within this many seconds of it answering.
BACK_WITHIN = 5.0


def node_names(master: str) -> set[str]:
    """The nodes a master knows, as `rosnode list` computes them (everything in getSystemState)."""
    try:
        code, _, state = call_sync(master, "getSystemState", "/test")
    except OSError:
        return set()
    if code != 1:
        return set()
    return {node for kind in state for _, nodes in kind for node in nodes}


def publishers_of(master: str, topic: str) -> list[str]:
    """The nodes a master lists as publishing ``topic``."""
    return next((nodes for t, nodes in call_sync(master, "getSystemState", "/test")[2][0] if t == topic), [])


@pytest.fixture
def core(ros_env: dict[str, str]) -> Iterator[list[subprocess.Popen]]:
    """A `rostui core` on the ros_env port, in a list the test may replace it in; every one is stopped."""
    procs = [start_rostui_core(ros_env)]
    try:
        yield procs
    finally:
        for proc in procs:
            stop_process(proc)


@pytest.fixture
def engine() -> Iterator[Engine]:
    """An engine thread for a node in this process while the test blocks on processes."""
    eng = Engine()
    try:
        yield eng
    finally:
        eng.stop()


def test_nodes_register_again_after_the_master_is_killed_and_restarted(
        ros_env: dict[str, str], core: list[subprocess.Popen], spawn: Spawn, engine: Engine) -> None:
    master = ros_env["ROS_MASTER_URI"]
    latcher = spawn(rostui_peer("latch", "/chatter", "old hello"), label="rostui latched publisher")
    latcher.wait_for(r"^ready$")
    server = spawn(rostui_peer("serve", "/ping"), label="rostui SetBool server")
    server.wait_for(r"^ready$")

    node = AsyncNode("inproc", argv=[])
    engine.run(node.start())
    got: list[str] = []
    try:
        engine.run(node.advertise("inproc_out", String))
        engine.run(node.subscribe("later", String, lambda m: got.append(m.data)))
        engine.run(node.advertise_service("inproc_srv", SetBool, lambda req: (True, "in process")))
        assert engine.run(node.get_param_cached("/gain", 0)) == 0
        before = node_names(master)
        assert "/inproc" in before and len(before) >= 4, before

        old = core.pop()
        old.kill()  # SIGKILL: the master unregisters nothing and tells nobody
        old.wait()
        core.append(start_rostui_core(ros_env))
        assert master_port(ros_env) == int(master.rsplit(":", 1)[1])

        wait_until(lambda: before <= node_names(master),
                   f"every node back with the new master (missing: {before - node_names(master)})",
                   timeout=BACK_WITHIN)
        listed = set(run_tool(["rosnode", "list"], ros_env).stdout.split())
        assert before <= listed, before - listed

        # A new subscriber, a real command-line process, finds the old publisher.
        echo = subprocess.run(rostui_cmd("topic", "echo", "/chatter", "-n", "1"), env=ros_env,
                              capture_output=True, text=True, timeout=60)
        assert echo.returncode == 0, echo.stderr
        assert 'data: "old hello"' in echo.stdout, echo.stdout

        # Services of both nodes are found again.
        call = spawn(rostui_peer("call", "/ping", "true", "--no-wait"), label="rostui SetBool client")
        assert call.wait_exit() == 0, call.describe() + "\n" + server.describe()
        assert call.lines[-1] == "success=True message=got true", call.describe()
        assert call_sync(master, "lookupService", "/test", "/inproc_srv")[2] == node.service_uri
        assert "/inproc" in publishers_of(master, "/inproc_out")

        # The master knows our subscriber: a publisher started now reaches it (publisherUpdate as usual).
        spawn(rostui_cmd("topic", "pub", "/later", "std_msgs/String", "data: new", "-r", "10"),
              label="rostui topic pub")
        wait_until(lambda: "new" in got, "the in-process subscriber to hear a publisher that came after the restart")

        # And our parameter subscription: a change on the new master reaches the cache.
        call_sync(master, "setParam", "/test", "/gain", 7)
        wait_until(lambda: node.params.get("/gain") == 7, "paramUpdate of /gain from the new master")
        assert node.registrations_renewed >= 1
    finally:
        engine.run(node.shutdown())


def test_node_registers_again_only_for_a_new_master(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """A master that keeps answering as itself costs one small check a second, nothing more."""
    async def scenario() -> None:
        node = await AsyncNode("steady").start()
        try:
            await node.advertise("steady_out", String)
            for _ in range(3):
                assert not await node.check_master()
            await asyncio.sleep(2.5)  # two or three checks of its own
            assert node.registrations_renewed == 0
        finally:
            await node.shutdown()
    run(scenario())


class FakeMaster:
    """Just enough of a master to count registrations, with a pid and /run_id the test changes."""

    def __init__(self) -> None:
        self.pid = os.getpid()
        self.run_id = "run-1"
        self.calls: list[str] = []

    def getPid(self, caller_id: str) -> list[Any]:
        self.calls.append("getPid")
        return [1, "", self.pid]

    def getParam(self, caller_id: str, key: str) -> list[Any]:
        return [1, "", self.run_id] if key == "/run_id" else [-1, "no such parameter", 0]

    def registerPublisher(self, caller_id: str, topic: str, type_: str, uri: str) -> list[Any]:
        self.calls.append(f"registerPublisher {topic}")
        return [1, "", []]

    def registerSubscriber(self, caller_id: str, topic: str, type_: str, uri: str) -> list[Any]:
        self.calls.append(f"registerSubscriber {topic}")
        return [1, "", []]

    def registerService(self, caller_id: str, service: str, service_uri: str, uri: str) -> list[Any]:
        self.calls.append(f"registerService {service}")
        return [1, "", 0]

    def subscribeParam(self, caller_id: str, uri: str, key: str) -> list[Any]:
        self.calls.append(f"subscribeParam {key}")
        return [1, "", 5]

    def unregisterPublisher(self, caller_id: str, topic: str, uri: str) -> list[Any]:
        return [1, "", 1]

    def unregisterSubscriber(self, caller_id: str, topic: str, uri: str) -> list[Any]:
        return [1, "", 1]

    def unregisterService(self, caller_id: str, service: str, service_uri: str) -> list[Any]:
        return [1, "", 1]

    def unsubscribeParam(self, caller_id: str, uri: str, key: str) -> list[Any]:
        return [1, "", 1]

    def count(self, call: str) -> int:
        """How many times ``call`` came in."""
        return self.calls.count(call)


def test_new_run_id_or_a_master_back_from_silence_means_register_again(ros_env: dict[str, str]) -> None:
    """Same pid, new /run_id (a master in a container restarted as pid 1); then no answer, then an answer."""
    async def scenario() -> None:
        fake = FakeMaster()
        port = free_port()
        server = XmlRpcServer(fake, "127.0.0.1", port)
        await server.start()
        node = await AsyncNode("watcher", argv=[], master_uri=f"http://127.0.0.1:{port}").start(announce=False)
        try:
            await node.advertise("out", String)
            await node.subscribe("in", String)
            await node.advertise_service("srv", SetBool, lambda req: (True, ""))
            await node.get_param_cached("/p")
            everything = ["registerPublisher /out", "registerSubscriber /in", "registerService /srv",
                          "subscribeParam /p"]
            assert [fake.count(c) for c in everything] == [1, 1, 1, 1]
            await until(lambda: fake.count("getPid") >= 2)
            assert [fake.count(c) for c in everything] == [1, 1, 1, 1]

            fake.run_id = "run-2"
            # the fake counts a call when it arrives; the node counts a renewal once every answer is back
            await until(lambda: node.registrations_renewed == 1)
            assert [fake.count(c) for c in everything] == [2, 2, 2, 2]

            await server.close()
            await asyncio.sleep(2 * 1.0)  # the checks find nobody
            assert node.params.get("/p") == 5
            server = XmlRpcServer(fake, "127.0.0.1", port)
            await server.start()
            await until(lambda: node.registrations_renewed == 2)
            assert [fake.count(c) for c in everything] == [3, 3, 3, 3]
        finally:
            await node.shutdown()
            await server.close()
    run(scenario())


def test_node_without_the_watch_never_checks(ros_env: dict[str, str]) -> None:
    """``watch_master=False`` (a node that manages its master itself) sends no checks."""
    async def scenario() -> None:
        fake = FakeMaster()
        port = free_port()
        server = XmlRpcServer(fake, "127.0.0.1", port)
        await server.start()
        node = await AsyncNode("quiet", argv=[], master_uri=f"http://127.0.0.1:{port}",
                               watch_master=False).start(announce=False)
        try:
            await node.advertise("out", String)
            await asyncio.sleep(1.5)
            assert fake.count("getPid") == 0
        finally:
            await node.shutdown()
            await server.close()
    run(scenario())


def test_checks_stop_when_the_node_shuts_down(ros_env: dict[str, str]) -> None:
    """After shutdown nothing is left running: no check, no registration with anybody."""
    async def scenario() -> None:
        fake = FakeMaster()
        port = free_port()
        server = XmlRpcServer(fake, "127.0.0.1", port)
        await server.start()
        node = await AsyncNode("brief", argv=[], master_uri=f"http://127.0.0.1:{port}").start(announce=False)
        await until(lambda: fake.count("getPid") >= 1)
        await node.shutdown()
        seen = len(fake.calls)
        await asyncio.sleep(1.5)
        assert len(fake.calls) == seen
        await server.close()
    run(scenario())


def test_the_node_is_the_judge_of_its_master(ros_env: dict[str, str]) -> None:
    """Waiting (and why), connected once the hooks ran, lost, connected again after a new master; a server that
    answers getPid with something else is not a master."""
    from rostui.core.node.master_watch import MasterState

    async def scenario() -> None:
        fake = FakeMaster()
        port = free_port()
        node = await AsyncNode("judged", argv=[], master_uri=f"http://127.0.0.1:{port}").start(announce=False)
        watch = node.master_watch
        assert watch is not None
        states: list[str] = []
        connects: list[MasterState] = []

        async def on_connect() -> None:
            connects.append(watch.state)  # the hooks run before the node counts as connected

        watch.on_connect.append(on_connect)
        watch.listeners.append(lambda state: states.append(state.value))
        server = XmlRpcServer(fake, "127.0.0.1", port)
        try:
            await until(lambda: watch.detail == "no answer")
            assert watch.state is MasterState.WAITING and connects == []

            real_pid = fake.pid
            fake.pid = "not-a-pid"  # type: ignore[assignment]
            await server.start()
            await until(lambda: "not a pid" in watch.detail)
            assert watch.state is MasterState.WAITING and connects == []

            fake.pid = real_pid
            await until(lambda: watch.state is MasterState.CONNECTED)
            assert connects == [MasterState.WAITING] and node.registrations_renewed == 0

            await server.close()
            await until(lambda: watch.state is MasterState.LOST)
            server = XmlRpcServer(fake, "127.0.0.1", port)
            await server.start()
            await until(lambda: watch.state is MasterState.CONNECTED)
            assert len(connects) == 2 and node.registrations_renewed == 1

            fake.run_id = "run-2"  # another master took its place between two checks: lost, then connected again
            await until(lambda: node.registrations_renewed == 2 and watch.state is MasterState.CONNECTED)
            assert len(connects) == 3
            assert states == ["waiting", "waiting", "connected", "lost", "connected", "lost", "connected"]
        finally:
            await node.shutdown()
            await server.close()
    run(scenario())


def test_a_hook_that_fails_is_tried_again_at_the_next_check(ros_env: dict[str, str]) -> None:
    """A set-up the master failed half-way (it went, or refused) leaves the node waiting; the next check retries."""
    from rostui.core.master_errors import MasterUnreachableError
    from rostui.core.node.master_watch import MasterState

    async def scenario() -> None:
        fake = FakeMaster()
        port = free_port()
        server = XmlRpcServer(fake, "127.0.0.1", port)
        await server.start()
        node = AsyncNode("retried", argv=[], master_uri=f"http://127.0.0.1:{port}")
        watch = node.master_watch
        assert watch is not None
        tries: list[int] = []

        async def flaky() -> None:
            tries.append(len(tries))
            if len(tries) == 1:
                raise MasterUnreachableError(node.master_uri, "went half-way")

        watch.on_connect.append(flaky)
        await node.start(announce=False)
        try:
            await until(lambda: watch.state is MasterState.CONNECTED)
            assert tries == [0, 1]
        finally:
            await node.shutdown()
            await server.close()
    run(scenario())
