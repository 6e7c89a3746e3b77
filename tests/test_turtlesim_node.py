"""The turtlesim node as a user runs it: `rostui run turtlesim turtlesim_node --headless` on a live master.

Each test starts the real node in a subprocess against `rostui core` and talks
to it over ROS (an in-process rostui node, or the rostui command line).
"""

from __future__ import annotations

import asyncio
import contextlib
import math
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, AsyncIterator, Awaitable, Callable

import pytest

from cli_helpers import rostui
from conftest import free_port, stop_process
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node import AsyncNode
from rostui.core.node.services import ServiceException
from rostui.turtlesim.node import TurtlesimNode
from rostui.turtlesim.world import UPDATE_PERIOD, WORLD_SIZE

Pose = get_message_class("turtlesim/Pose")
Color = get_message_class("turtlesim/Color")
Velocity = get_message_class("turtlesim/Velocity")
Twist = get_message_class("geometry_msgs/Twist")
Log = get_message_class("rosgraph_msgs/Log")
Empty = get_service_class("std_srvs/Empty")
Spawn = get_service_class("turtlesim/Spawn")
Kill = get_service_class("turtlesim/Kill")
SetPen = get_service_class("turtlesim/SetPen")
TeleportAbsolute = get_service_class("turtlesim/TeleportAbsolute")
TeleportRelative = get_service_class("turtlesim/TeleportRelative")

CENTRE = WORLD_SIZE / 2.0
PATIENCE = 20.0


class Turtlesim:
    """A headless turtlesim process whose output goes to a file (it may log a WARN every 16 ms)."""

    def __init__(self, env: dict[str, str], log: Path, *args: str) -> None:
        self.log = log
        self._out = log.open("w")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "rostui", "run", "turtlesim", "turtlesim_node", "--headless", *args],
            env=env, stdin=subprocess.DEVNULL, stdout=self._out, stderr=subprocess.STDOUT,
        )

    @property
    def output(self) -> str:
        """Everything the node printed so far."""
        return self.log.read_text(errors="replace")

    def stop(self) -> int:
        """SIGINT and wait; return the exit status."""
        stop_process(self.proc, timeout=15)
        self._out.close()
        return self.proc.returncode


@pytest.fixture
def turtlesim(rostui_core, ros_env, tmp_path) -> Callable[..., Turtlesim]:
    """``turtlesim(*ros_args)`` starts a headless turtlesim; all are stopped after the test."""
    started: list[Turtlesim] = []

    def start(*args: str, env: dict[str, str] | None = None) -> Turtlesim:
        sim = Turtlesim(env or ros_env, tmp_path / f"turtlesim{len(started)}.log", *args)
        started.append(sim)
        return sim

    yield start
    for sim in started:
        sim.stop()


@contextlib.asynccontextmanager
async def probe() -> AsyncIterator[AsyncNode]:
    """An anonymous rostui node in this test process (ros_env applies to it)."""
    node = AsyncNode("turtle_probe", anonymous=True)
    await node.start()
    try:
        yield node
    finally:
        await node.shutdown()


async def until(check: Callable[[], Any], what: str, timeout: float = PATIENCE) -> Any:
    """Poll ``check`` (sync or async) until it returns something truthy."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + timeout
    while True:
        value = check()
        if asyncio.iscoroutine(value):
            value = await value
        if value:
            return value
        if loop.time() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        await asyncio.sleep(0.05)


async def published_topics(node: AsyncNode) -> set[str]:
    return {name for name, _ in await node.master_call("getPublishedTopics", "")}


async def wait_topic(node: AsyncNode, topic: str) -> None:
    async def present() -> bool:
        return topic in await published_topics(node)
    await until(present, f"{topic} to be published")


class Latest:
    """The newest message of a topic and how many arrived."""

    def __init__(self) -> None:
        self.msg: Any = None
        self.count = 0

    def __call__(self, msg: Any) -> None:
        self.msg = msg
        self.count += 1


async def watch(node: AsyncNode, topic: str, msg_class: Any) -> Latest:
    latest = Latest()
    await node.subscribe(topic, msg_class, latest)
    await until(lambda: latest.count > 0, f"a message on {topic}")
    return latest


async def connected_publisher(node: AsyncNode, topic: str, msg_class: Any):
    pub = await node.advertise(topic, msg_class)
    await until(lambda: pub.get_num_connections() > 0, f"turtlesim to subscribe to {topic}")
    return pub


async def settled(latest: Latest, seconds: float = 0.3) -> Any:
    """Wait until the pose stays the same for a while (the command expired); return it."""
    async def still() -> Any:
        before = latest.msg
        await asyncio.sleep(seconds)
        after = latest.msg
        return after if (before.x, before.y, before.theta) == (after.x, after.y, after.theta) else None
    return await until(still, "the turtle to stop")


def run(coro: Awaitable[Any]) -> Any:
    return asyncio.run(coro)


# --------------------------------------------------------------------------- start-up and rate
def test_starts_logs_like_turtlesim_and_publishes_pose_at_62_5_hz(turtlesim) -> None:
    sim = turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            pose = await watch(node, "/turtle1/pose", Pose)
            loop = asyncio.get_running_loop()
            start, first = loop.time(), pose.count
            await asyncio.sleep(2.0)
            rate = (pose.count - first) / (loop.time() - start)
            assert 40.0 < rate < 85.0, rate
            msg = pose.msg
            assert (msg.x, msg.y, msg.theta) == pytest.approx((CENTRE, CENTRE, 0.0), abs=1e-6)
            colour = await watch(node, "/turtle1/color_sensor", Color)
            assert (colour.msg.r, colour.msg.g, colour.msg.b) == (69, 86, 255)

    run(scenario())
    out = sim.output
    assert "[ INFO] [" in out
    assert "]: Starting turtlesim with node name /turtlesim" in out
    assert "]: Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]" in out


def test_in_process_node_measures_its_rate_and_calls_listeners(rostui_core) -> None:
    async def scenario() -> None:
        sim = TurtlesimNode(console=False)
        ticks = []
        sim.add_listener(lambda: ticks.append(1))
        await sim.start()
        try:
            assert list(sim.world.turtles) == ["turtle1"]
            await until(lambda: sim.rate > 0.0, "a measured rate")
            assert 40.0 < sim.rate < 85.0, sim.rate
            assert len(ticks) >= sim.updates - 1 > 0
            assert await sim.spawn("", 2.0, 2.0, 0.0) == "turtle2"
            async with probe() as node:
                await wait_topic(node, "/turtle2/pose")
                await sim.kill("turtle2")
                assert "/turtle2/pose" not in await published_topics(node)
                assert list(sim.world.turtles) == ["turtle1"]
        finally:
            await sim.stop()
        assert not sim.running

    run(scenario())


# --------------------------------------------------------------------------- driving
def test_cmd_vel_moves_the_turtle_and_the_command_expires_after_a_second(turtlesim) -> None:
    turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            pose = await watch(node, "/turtle1/pose", Pose)
            cmd = await connected_publisher(node, "/turtle1/cmd_vel", Twist)
            twist = Twist()
            twist.linear.x = 1.0
            cmd.publish(twist)
            moving = await until(lambda: pose.msg if pose.msg.linear_velocity == 1.0 else None, "motion")
            assert moving.x > CENTRE
            stopped = await settled(pose)
            # One command drives for one second (about 62 updates of 16 ms at 1 m/s), then expires.
            assert stopped.linear_velocity == 0.0 and stopped.angular_velocity == 0.0
            assert stopped.x - CENTRE == pytest.approx(62 * UPDATE_PERIOD, abs=0.3)
            assert stopped.y == pytest.approx(CENTRE, abs=1e-5)

    run(scenario())


def test_book_command_velocity_turns_and_moves(turtlesim) -> None:
    turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            pose = await watch(node, "/turtle1/pose", Pose)
            cmd = await connected_publisher(node, "/turtle1/command_velocity", Velocity)
            for _ in range(3):
                cmd.publish(Velocity(linear=1.0, angular=1.0))
                await asyncio.sleep(0.5)
            stopped = await settled(pose)
            assert stopped.theta > 1.0 and stopped.y > CENTRE and stopped.x > CENTRE
            # On a circle of radius v/w = 1 m around (CENTRE, CENTRE + 1).
            assert math.hypot(stopped.x - CENTRE, stopped.y - CENTRE - 1.0) == pytest.approx(1.0, abs=0.05)

    run(scenario())


def test_hitting_the_wall_warns_on_rosout(turtlesim) -> None:
    sim = turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            logs: list[Any] = []
            await node.subscribe("/rosout_agg", Log, logs.append)
            await wait_topic(node, "/turtle1/pose")
            pose = await watch(node, "/turtle1/pose", Pose)
            cmd = await connected_publisher(node, "/turtle1/cmd_vel", Twist)
            twist = Twist()
            twist.linear.x = 10.0
            cmd.publish(twist)
            await until(lambda: pose.msg.x == pytest.approx(WORLD_SIZE), "the turtle at the right wall")
            warns = await until(lambda: [m for m in logs if "Oh no! I hit the wall!" in m.msg], "the WARN on rosout")
            assert warns[0].level == Log.WARN and warns[0].name == "/turtlesim"
            assert warns[0].msg.startswith("Oh no! I hit the wall! (Clamping from [x=11.")
            assert warns[0].msg.endswith(", y=5.544445])")

    run(scenario())
    assert "[ WARN] [" in sim.output and "Oh no! I hit the wall!" in sim.output


# --------------------------------------------------------------------------- services
def test_spawn_kill_and_their_errors(turtlesim, ros_env) -> None:
    sim = turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            spawn = node.service_proxy("/spawn", Spawn)
            kill = node.service_proxy("/kill", Kill)
            assert (await spawn.call(x=3.0, y=3.0, theta=0.0, name="")).name == "turtle2"
            await wait_topic(node, "/turtle2/pose")
            await kill.call(name="turtle2")
            with pytest.raises(ServiceException, match=r"Tried to kill turtle \[turtle2\], which does not exist"):
                await kill.call(name="turtle2")
            assert "/turtle2/pose" not in await published_topics(node)

    run(scenario())
    first = rostui(["service", "call", "/spawn", "3", "3", "0", "Mikey"], ros_env)
    assert first.returncode == 0 and first.stdout.strip() == 'name: "Mikey"', first.stderr
    topics = rostui(["topic", "list"], ros_env).stdout.split()
    assert {"/Mikey/pose", "/Mikey/cmd_vel", "/Mikey/command_velocity", "/Mikey/color_sensor"} <= set(topics)
    services = rostui(["service", "list"], ros_env).stdout.split()
    assert {"/Mikey/set_pen", "/Mikey/teleport_absolute", "/Mikey/teleport_relative"} <= set(services)
    again = rostui(["service", "call", "/spawn", "3", "3", "0", "Mikey"], ros_env)
    assert again.returncode != 0 and "A turtle named [Mikey] already exists" in again.stderr
    assert "[ERROR] [" in sim.output and "]: A turtle named [Mikey] already exists" in sim.output
    assert "Spawning turtle [Mikey] at x=[3.000000], y=[3.000000], theta=[0.000000]" in sim.output


def test_pen_teleport_and_colour_sensor(turtlesim) -> None:
    turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            pose = await watch(node, "/turtle1/pose", Pose)
            colour = await watch(node, "/turtle1/color_sensor", Color)
            set_pen = node.service_proxy("/turtle1/set_pen", SetPen)
            absolute = node.service_proxy("/turtle1/teleport_absolute", TeleportAbsolute)
            relative = node.service_proxy("/turtle1/teleport_relative", TeleportRelative)
            await set_pen.call(r=255, g=0, b=0, width=5, off=0)
            await absolute.call(x=1.0, y=1.0, theta=0.0)
            await absolute.call(x=9.0, y=1.0, theta=0.0)   # a red line along y = 1
            await set_pen.call(r=0, g=0, b=0, width=0, off=1)
            await absolute.call(x=5.0, y=1.0, theta=math.pi / 2)
            await until(lambda: pose.msg.x == pytest.approx(5.0) and pose.msg.y == pytest.approx(1.0),
                        "the teleported pose")
            await until(lambda: (colour.msg.r, colour.msg.g, colour.msg.b) == (255, 0, 0), "red under the turtle")
            await relative.call(linear=2.0, angular=0.0)
            await until(lambda: pose.msg.y == pytest.approx(3.0, abs=1e-4), "the relative teleport")
            assert pose.msg.x == pytest.approx(5.0, abs=1e-4) and pose.msg.theta == pytest.approx(math.pi / 2)
            await until(lambda: (colour.msg.r, colour.msg.g, colour.msg.b) == (69, 86, 255), "background again")

    run(scenario())


def test_background_params_are_created_and_clear_rereads_them(turtlesim, ros_env) -> None:
    preset = rostui(["param", "set", "/background_g", "10"], ros_env)
    assert preset.returncode == 0, preset.stderr
    turtlesim()

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/turtle1/pose")
            assert [await node.get_param(f"/background_{c}") for c in "rgb"] == [69, 10, 255]
            colour = await watch(node, "/turtle1/color_sensor", Color)
            await until(lambda: (colour.msg.r, colour.msg.g, colour.msg.b) == (69, 10, 255), "the preset colour")
            # The book's set_bg_color: set the params, then call clear.
            for c, value in zip("rgb", (255, 255, 0)):
                await node.set_param(f"background_{c}", value)
            await node.service_proxy("/clear", Empty).call()
            await until(lambda: (colour.msg.r, colour.msg.g, colour.msg.b) == (255, 255, 0), "yellow background")
            await node.set_param("background_r", 0)
            spawn = node.service_proxy("/spawn", Spawn)
            await spawn.call(x=2.0, y=2.0, theta=0.0, name="extra")
            await node.service_proxy("/reset", Empty).call()
            await until(lambda: (colour.msg.r, colour.msg.g, colour.msg.b) == (0, 255, 0), "reset re-reads params")
            assert "/extra/pose" not in await published_topics(node)
            assert "/turtle1/pose" in await published_topics(node)

    run(scenario())
    listed = rostui(["param", "list"], ros_env).stdout.split()
    assert {"/background_b", "/background_g", "/background_r"} <= set(listed)


# --------------------------------------------------------------------------- names and lifecycle
def test_namespaces_let_two_turtlesims_run_at_once(turtlesim, ros_env) -> None:
    one = turtlesim("__ns:=sim1")
    two = turtlesim("__ns:=sim2", "__name:=A")

    async def scenario() -> None:
        async with probe() as node:
            await wait_topic(node, "/sim1/turtle1/pose")
            await wait_topic(node, "/sim2/turtle1/pose")
            pose1 = await watch(node, "/sim1/turtle1/pose", Pose)
            pose2 = await watch(node, "/sim2/turtle1/pose", Pose)
            cmd = await connected_publisher(node, "/sim1/turtle1/cmd_vel", Twist)
            twist = Twist()
            twist.linear.x = 2.0
            cmd.publish(twist)
            await settled(pose1)
            assert pose1.msg.x > CENTRE + 1.0 and pose2.msg.x == pytest.approx(CENTRE)
            assert await node.get_param("/sim2/background_r") == 69
            spawned = await node.service_proxy("/sim2/spawn", Spawn).call(x=1.0, y=1.0, theta=0.0, name="")
            assert spawned.name == "turtle2"
            await wait_topic(node, "/sim2/turtle2/pose")

    run(scenario())
    nodes = rostui(["node", "list"], ros_env).stdout.split()
    assert "/sim1/turtlesim" in nodes and "/sim2/A" in nodes
    assert "Starting turtlesim with node name /sim2/A" in two.output
    assert "Starting turtlesim with node name /sim1/turtlesim" in one.output


def test_ctrl_c_unregisters_and_exits_zero(turtlesim, ros_env) -> None:
    sim = turtlesim()
    run(_wait_for_turtle1())
    sim.proc.send_signal(signal.SIGINT)
    assert sim.proc.wait(timeout=PATIENCE) == 0, sim.output
    assert "/turtlesim" not in rostui(["node", "list"], ros_env).stdout.split()
    assert "/turtle1/pose" not in rostui(["topic", "list"], ros_env).stdout.split()
    assert "/spawn" not in rostui(["service", "list"], ros_env).stdout.split()
    assert "Traceback" not in sim.output


def test_a_second_node_with_the_same_name_replaces_the_first(turtlesim, ros_env) -> None:
    first = turtlesim()
    run(_wait_for_turtle1())
    second = turtlesim()
    assert first.proc.wait(timeout=PATIENCE) == 0, first.output
    assert "Shutdown request received" in first.output
    run(_wait_for_turtle1())
    assert second.proc.poll() is None
    assert "/turtlesim" in rostui(["node", "list"], ros_env).stdout.split()


async def _wait_for_turtle1() -> None:
    async with probe() as node:
        await wait_topic(node, "/turtle1/pose")
        await watch(node, "/turtle1/pose", Pose)


def test_without_a_master_it_says_so_once_and_stops_cleanly(ros_env, tmp_path) -> None:
    env = dict(ros_env, ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}")
    sim = Turtlesim(env, tmp_path / "nomaster.log")
    try:
        deadline = time.monotonic() + PATIENCE
        while "Unable to contact the master" not in sim.output and sim.proc.poll() is None:
            assert time.monotonic() < deadline, sim.output
            time.sleep(0.1)
        assert "Unable to contact the master at [http://127.0.0.1:" in sim.output
        time.sleep(1.0)  # it keeps waiting quietly
    finally:
        rc = sim.stop()
    assert rc == 0, sim.output
    assert sim.output.count("Unable to contact the master") == 1
    assert "Traceback" not in sim.output
