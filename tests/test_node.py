"""Behaviour of rostui nodes (async face) against a live `rostui core`."""

from __future__ import annotations

import asyncio
import subprocess
import sys
import textwrap
from typing import Any, Awaitable, Callable

import pytest

from rostui.core.msg import get_message_class, get_service_class
from rostui.core.network import resolve_addressing
from rostui.core.node import AsyncNode, MasterError, ServiceException
from rostui.core.xmlrpc import XmlRpcClient, call_sync

from conftest import stop_process

String = get_message_class("std_msgs/String")
SetBool = get_service_class("std_srvs/SetBool")


def run(coro: Awaitable[Any], timeout: float = 30.0) -> Any:
    """Run a coroutine to completion with an overall guard against hangs."""
    async def guarded() -> Any:
        return await asyncio.wait_for(coro, timeout)
    return asyncio.run(guarded())


async def until(predicate: Callable[[], bool], timeout: float = 10.0) -> None:
    """Poll until predicate() holds; fail the test if it never does."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while not predicate():
        if loop.time() > deadline:
            raise AssertionError("condition not reached")
        await asyncio.sleep(0.02)


def system_state(env: dict[str, str]) -> list[Any]:
    """The master's getSystemState value."""
    return call_sync(env["ROS_MASTER_URI"], "getSystemState", "/test")[2]


PUBLISHER_SCRIPT = textwrap.dedent("""
    import sys
    from rostui import client as ros
    String = ros.msg("std_msgs/String")
    ros.init_node("pub_proc")
    latch = "latch" in sys.argv
    pub = ros.Publisher("chatter", String, queue_size=10, latch=latch)
    if latch:
        pub.publish(String(data="latched hello"))
        ros.spin()
    else:
        rate = ros.Rate(50)
        i = 0
        while not ros.is_shutdown():
            pub.publish(String(data=f"{sys.argv[1]} {i}"))
            i += 1
            rate.sleep()
""")


def start_publisher(env: dict[str, str], *args: str) -> subprocess.Popen:
    """A rostui publisher of std_msgs/String on /chatter in its own process."""
    return subprocess.Popen([sys.executable, "-c", PUBLISHER_SCRIPT, *args], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def test_same_process_nodes_deliver_directly(rostui_core: Any, ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        pub_node = await AsyncNode("direct_pub").start()
        sub_node = await AsyncNode("direct_sub").start()
        got: list[Any] = []
        await sub_node.subscribe("chatter", String, got.append)
        pub = await pub_node.advertise("chatter", String)
        await until(lambda: pub.get_num_connections() == 1)
        sent = String(data="same object")
        pub.publish(sent)
        await until(lambda: len(got) == 1)
        assert got[0] is sent
        async with XmlRpcClient(sub_node.uri) as client:
            info = (await client.call("getBusInfo", "/test"))[2]
        assert [row[2:5] for row in info if row[4] == "/chatter"] == [["i", "INTRAPROCESS", "/chatter"]]
        await pub_node.shutdown()
        await sub_node.shutdown()
    run(scenario())


def test_latched_message_reaches_late_subscriber(rostui_core: Any, ros_env: dict[str, str]) -> None:
    proc = start_publisher(ros_env, "x", "latch")
    try:
        async def scenario() -> None:
            node = await AsyncNode("late_sub").start()
            got: list[str] = []
            await until(lambda: any(t == "/chatter" for t, _ in system_state(ros_env)[0]))
            await node.subscribe("chatter", String, lambda m: got.append(m.data))
            await until(lambda: got == ["latched hello"])
            await node.shutdown()
        run(scenario())
    finally:
        stop_process(proc)


def test_subscriber_reconnects_when_publisher_restarts(rostui_core: Any, ros_env: dict[str, str]) -> None:
    first = start_publisher(ros_env, "first")
    second = None
    try:
        async def scenario() -> None:
            nonlocal second
            node = await AsyncNode("steady_sub").start()
            got: list[str] = []
            await node.subscribe("chatter", String, lambda m: got.append(m.data))
            await until(lambda: any(d.startswith("first") for d in got))
            stop_process(first)
            second = start_publisher(ros_env, "second")
            await until(lambda: any(d.startswith("second") for d in got), timeout=20)
            await node.shutdown()
        run(scenario(), timeout=60)
    finally:
        stop_process(first)
        if second is not None:
            stop_process(second)


def test_service_call_and_error_text(rostui_core: Any, ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        server_node = await AsyncNode("server").start()
        client_node = await AsyncNode("client").start()

        def handle(req: Any) -> Any:
            if not req.data:
                raise ServiceException("refusing false")
            return SetBool._response_class(success=True, message="ok")

        await server_node.advertise_service("toggle", SetBool, handle)
        proxy = client_node.service_proxy("toggle", SetBool)
        resp = await proxy.call(True)
        assert (resp.success, resp.message) == (True, "ok")
        with pytest.raises(ServiceException, match=r"service \[/toggle\] responded with an error: refusing false"):
            await proxy.call(False)
        persistent = client_node.service_proxy("toggle", SetBool, persistent=True)
        for _ in range(3):
            assert (await persistent.call(data=True)).success
        await persistent.close()
        with pytest.raises(ServiceException, match=r"service \[/missing\] unavailable"):
            await client_node.service_proxy("missing", SetBool).call(True)
        with pytest.raises(TimeoutError):
            await client_node.wait_for_service("missing", timeout=0.3)
        await server_node.shutdown()
        await client_node.shutdown()
    run(scenario())


def test_params_and_cache_follow_updates(rostui_core: Any, ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        node = await AsyncNode("params", argv=["_rate:=10", "__ns:=/robot"]).start()
        assert await node.get_param("~rate") == 10
        await node.set_param("gains", {"p": 1.5, "i": 0})
        assert await node.get_param("/robot/gains/p") == 1.5
        assert await node.get_param_cached("gains/p") == 1.5
        call_sync(ros_env["ROS_MASTER_URI"], "setParam", "/other", "/robot/gains/p", 2.5)
        await until(lambda: node.params.get("/robot/gains/p") == 2.5)
        assert await node.get_param_cached("gains/p") == 2.5
        assert await node.search_param("gains") == "/robot/gains"
        await node.delete_param("gains")
        assert not await node.has_param("gains")
        with pytest.raises(KeyError):
            await node.get_param("gains")
        assert await node.get_param("gains", "fallback") == "fallback"
        await node.shutdown()
    run(scenario())


def test_shutdown_unregisters_everything(rostui_core: Any, ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        node = await AsyncNode("tidy").start()
        await node.advertise("out", String)
        await node.subscribe("in", String, lambda m: None)
        await node.advertise_service("srv", SetBool, lambda r: (True, ""))
        pubs, subs, srvs = system_state(ros_env)
        assert ["/out", ["/tidy"]] in pubs and ["/in", ["/tidy"]] in subs and ["/srv", ["/tidy"]] in srvs
        await node.shutdown()
        pubs, subs, srvs = system_state(ros_env)
        everything = pubs + subs + srvs
        assert not [entry for entry in everything if "/tidy" in entry[1]]
    run(scenario())


def test_what_is_asked_for_after_shutdown_began_is_not_registered(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """Ctrl-C between init_node and a script's Subscriber line: the script goes on to make the subscriber while
    the node shuts down; like rospy, the node registers nothing more, so nothing stays listed with the master
    (the registration used to come after the unregistrations, and the dead node stayed on the graph)."""
    async def scenario() -> None:
        node = await AsyncNode("hasty").start()
        await node.subscribe("early", String, lambda m: None)
        await node.shutdown()
        await node.subscribe("late", String, lambda m: None)
        await node.advertise("out", String)
        await node.advertise_service("srv", SetBool, lambda r: (True, ""))
        pubs, subs, srvs = system_state(ros_env)
        assert not [entry for entry in pubs + subs + srvs if "/hasty" in entry[1]]
    run(scenario())


def test_master_down_is_one_clear_error(ros_env: dict[str, str]) -> None:
    async def scenario() -> None:
        with pytest.raises(MasterError, match="Unable to communicate with master"):
            await AsyncNode("lonely").start()
        node = await AsyncNode("quiet").start(announce=False)
        with pytest.raises(MasterError, match="Unable to communicate with master"):
            await node.advertise("x", String)
        await node.shutdown()
    run(scenario())


def test_servers_bind_loopback_unless_told_otherwise(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ROS_IP", raising=False)
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    local = resolve_addressing("http://localhost:11311")
    assert (local.bind_host, local.advertise_host) == ("127.0.0.1", "127.0.0.1")
    remote = resolve_addressing("http://robot.example:11311", ip="10.1.2.3")
    assert (remote.bind_host, remote.advertise_host) == ("0.0.0.0", "10.1.2.3")
    named = resolve_addressing("http://localhost:11311", hostname="laptop.lan")
    assert (named.bind_host, named.advertise_host) == ("0.0.0.0", "laptop.lan")

    async def scenario() -> None:
        node = await AsyncNode("bound", master_uri="http://127.0.0.1:1").start(announce=False)
        assert node._tcpros is not None
        assert {s.getsockname()[0] for s in node._tcpros.sockets} == {"127.0.0.1"}
        assert node.uri.startswith("http://127.0.0.1:")
        await node.shutdown()
    run(scenario())


def test_subscriber_queue_size_keeps_only_the_newest_backlog(rostui_core: Any, ros_env: dict[str, str]) -> None:
    script = textwrap.dedent("""
        import time
        from rostui import client as ros
        String = ros.msg("std_msgs/String")
        ros.init_node("burst")
        pub = ros.Publisher("burst", String, queue_size=1000)
        while pub.get_num_connections() == 0:
            time.sleep(0.01)
        for i in range(200):
            pub.publish(String(data=str(i)))
        time.sleep(2)
    """)

    async def scenario() -> None:
        node = await AsyncNode("slow_sub").start()
        got: list[int] = []

        def slow(msg: Any) -> None:
            got.append(int(msg.data))
            if len(got) == 1:
                import time
                time.sleep(0.5)  # the rest of the burst piles up meanwhile

        await node.subscribe("burst", String, slow, queue_size=1)
        proc = await asyncio.create_subprocess_exec(sys.executable, "-c", script, env=ros_env)
        try:
            await until(lambda: bool(got) and got[-1] == 199, timeout=20)
            assert len(got) < 200
        finally:
            await proc.wait()
            await node.shutdown()
    run(scenario())
