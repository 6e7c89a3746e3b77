"""The turtlesim ROS node: a TurtleWorld on the running asyncio loop, spoken to over ROS.

Like ROS turtlesim, every name is relative to the node's namespace, so
``__ns:=sim1`` and ``__name:=A`` work and several simulators run at once:

- parameters ``background_r``, ``background_g``, ``background_b`` (created
  with the default colour when absent, read again on ``clear`` and ``reset``);
- services ``clear``, ``reset`` (std_srvs/Empty), ``spawn`` (turtlesim/Spawn),
  ``kill`` (turtlesim/Kill);
- per turtle NAME: subscriptions ``NAME/cmd_vel`` (geometry_msgs/Twist) and
  ``NAME/command_velocity`` (turtlesim/Velocity, the book's groovy-era topic),
  publications ``NAME/pose`` (turtlesim/Pose) and ``NAME/color_sensor``
  (turtlesim/Color) on every update, services ``NAME/set_pen``,
  ``NAME/teleport_absolute``, ``NAME/teleport_relative``.

The world updates every 16 ms on absolute deadlines (no drift; missed ticks
are skipped, never bunched), with ROS's fixed step of 0.016 s.
"""

from __future__ import annotations

import asyncio
import math
import signal
import sys
from dataclasses import dataclass
from typing import Any, Callable, Sequence

from rostui.core.log import NodeLog
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.node.node import AsyncNode, Publisher, Subscriber
from rostui.core.node.services import ServiceException, ServiceServer
from rostui.turtlesim.world import (
    DEFAULT_BACKGROUND,
    UPDATE_PERIOD,
    WORLD_SIZE,
    NameTaken,
    TurtleWorld,
    UnknownTurtle,
    f32,
)

Twist = get_message_class("geometry_msgs/Twist")
Velocity = get_message_class("turtlesim/Velocity")
Pose = get_message_class("turtlesim/Pose")
Color = get_message_class("turtlesim/Color")
Empty = get_service_class("std_srvs/Empty")
Spawn = get_service_class("turtlesim/Spawn")
Kill = get_service_class("turtlesim/Kill")
SetPen = get_service_class("turtlesim/SetPen")
TeleportAbsolute = get_service_class("turtlesim/TeleportAbsolute")
TeleportRelative = get_service_class("turtlesim/TeleportRelative")

BACKGROUND_PARAMS = ("background_r", "background_g", "background_b")
"""Parameter names (relative to the node's namespace) of the background colour."""

RATE_WINDOW = 1.0
"""Seconds over which the achieved update rate is measured."""


@dataclass(eq=False)
class _TurtleEndpoints:
    """The ROS side of one turtle: what must be unregistered when it dies."""

    pose: Publisher
    color: Publisher
    subscribers: tuple[Subscriber, ...]
    services: tuple[ServiceServer, ...]


class TurtlesimNode:
    """ROS turtlesim on the running asyncio loop (a headless process or Textual's loop).

    ``argv`` is the node's command line without the program name (ROS
    arguments such as ``__name:=``, ``__ns:=`` and remappings apply).
    ``console=False`` keeps log lines off the terminal (they still go to
    /rosout and the log file), for a full-screen app.
    """

    def __init__(self, argv: Sequence[str] = (), *, name: str = "turtlesim", master_uri: str | None = None,
                 contacts: bool = False, console: bool = True) -> None:
        self.world = TurtleWorld(contacts=contacts)
        self.node = AsyncNode(name, argv=list(argv), master_uri=master_uri, package="turtlesim")
        if not console:
            self.node.log.console = None
        self.rate = 0.0
        self.updates = 0
        self._endpoints: dict[str, _TurtleEndpoints] = {}
        self._frame_services: list[ServiceServer] = []
        self._listeners: list[Callable[[], None]] = []
        self._timer: asyncio.TimerHandle | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._next_deadline = 0.0
        self._window_start = 0.0
        self._window_count = 0
        self._watch: asyncio.Task[None] | None = None
        self._busy = asyncio.Lock()

    # -- lifecycle ---------------------------------------------------------------------
    @property
    def log(self) -> NodeLog:
        """The node's logger (console, /rosout and log file)."""
        return self.node.log

    @property
    def name(self) -> str:
        """The node's resolved name, e.g. ``/turtlesim`` or ``/sim1/turtlesim``."""
        return self.node.name

    @property
    def running(self) -> bool:
        """True between a successful start and stop (or the node being shut down)."""
        return self._timer is not None

    async def start(self) -> None:
        """Register with the master (waiting for it, with one warning), set up params, services and turtle1."""
        node = self.node
        self._loop = asyncio.get_running_loop()
        await node.start(announce=False)

        def warn() -> None:
            node.log.warn("Unable to contact the master at [%s]; will keep trying.", node.master_uri)

        await node.wait_for_master(on_wait=warn)
        await node.announce()
        await self._ensure_background_params()
        self.world.clear(await self._read_background())
        self._frame_services = list(await asyncio.gather(
            node.advertise_service("clear", Empty, self._on_clear),
            node.advertise_service("reset", Empty, self._on_reset),
            node.advertise_service("spawn", Spawn, self._on_spawn),
            node.advertise_service("kill", Kill, self._on_kill),
        ))
        node.log.info("Starting turtlesim with node name %s", node.name)
        centre = WORLD_SIZE / 2.0
        await self.spawn("", centre, centre, 0.0)
        self._start_loop()
        self._watch = self._loop.create_task(self._watch_shutdown())

    async def stop(self, reason: str = "shutdown") -> None:
        """Stop updating and unregister everything from the master."""
        self._stop_loop()
        if self._watch is not None and self._watch is not asyncio.current_task():
            self._watch.cancel()
        self._endpoints.clear()
        if self.node.loop is None:  # never started: nothing is registered or open
            return
        await self.node.shutdown(reason)

    async def wait_stopped(self) -> str:
        """Wait until the node shuts down (stop(), a master's shutdown request); return the reason."""
        return await self.node.wait_shutdown()

    async def _watch_shutdown(self) -> None:
        """A same-name node or `rosnode kill` shuts the node down: stop updating too."""
        await self.node.wait_shutdown()
        self._stop_loop()

    def add_listener(self, callback: Callable[[], None]) -> None:
        """Call ``callback()`` after every update (on the loop's thread)."""
        self._listeners.append(callback)

    def remove_listener(self, callback: Callable[[], None]) -> None:
        """Stop calling a listener added with add_listener."""
        if callback in self._listeners:
            self._listeners.remove(callback)

    # -- turtles -----------------------------------------------------------------------
    async def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """Add a turtle with its topics and services; NameTaken for a duplicate ("" picks ``turtleN``)."""
        real_name = self.world.spawn(name, x, y, theta)
        try:
            self._endpoints[real_name] = await self._attach(real_name)
        except BaseException:
            if real_name in self.world.turtles:
                self.world.kill(real_name)
            raise
        self.node.log.info("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]", real_name, f32(x), f32(y),
                           f32(theta))
        return real_name

    async def kill(self, name: str) -> None:
        """Remove a turtle and unregister its topics and services; UnknownTurtle if there is none."""
        self.world.kill(name)
        endpoints = self._endpoints.pop(name, None)
        if endpoints is not None:
            await self._detach(endpoints)

    async def _attach(self, name: str) -> _TurtleEndpoints:
        node = self.node
        world = self.world

        def on_twist(msg: Any) -> None:
            if name in world.turtles:
                world.command(name, msg.linear.x, msg.linear.y, msg.angular.z)

        def on_velocity(msg: Any) -> None:
            if name in world.turtles:
                world.command(name, msg.linear, 0.0, msg.angular)

        def on_set_pen(req: Any) -> Any:
            self._turtle_call(world.set_pen, name, req.r, req.g, req.b, req.width, bool(req.off))
            return SetPen._response_class()

        def on_teleport_absolute(req: Any) -> Any:
            self._turtle_call(world.teleport_absolute, name, req.x, req.y, req.theta)
            return TeleportAbsolute._response_class()

        def on_teleport_relative(req: Any) -> Any:
            self._turtle_call(world.teleport_relative, name, req.linear, req.angular)
            return TeleportRelative._response_class()

        (pose, color), subscribers, services = await asyncio.gather(
            asyncio.gather(
                node.advertise(f"{name}/pose", Pose, queue_size=1),
                node.advertise(f"{name}/color_sensor", Color, queue_size=1),
            ),
            asyncio.gather(
                node.subscribe(f"{name}/cmd_vel", Twist, on_twist, queue_size=1),
                node.subscribe(f"{name}/command_velocity", Velocity, on_velocity, queue_size=1),
            ),
            asyncio.gather(
                node.advertise_service(f"{name}/set_pen", SetPen, on_set_pen),
                node.advertise_service(f"{name}/teleport_absolute", TeleportAbsolute, on_teleport_absolute),
                node.advertise_service(f"{name}/teleport_relative", TeleportRelative, on_teleport_relative),
            ),
        )
        return _TurtleEndpoints(pose, color, subscribers, services)

    async def _detach(self, endpoints: _TurtleEndpoints) -> None:
        node = self.node
        if node.is_shutdown:
            return
        await asyncio.gather(
            endpoints.pose.unregister(),
            endpoints.color.unregister(),
            *(sub.unregister() for sub in endpoints.subscribers),
            *(node.unadvertise_service(server) for server in endpoints.services),
        )

    @staticmethod
    def _turtle_call(method: Callable[..., None], name: str, *args: Any) -> None:
        try:
            method(name, *args)
        except UnknownTurtle:
            raise ServiceException(f"turtle [{name}] does not exist") from None

    # -- frame services -------------------------------------------------------------------
    async def clear(self) -> None:
        """Erase the trails with the background the parameters give now."""
        self.world.clear(await self._read_background())

    async def reset(self) -> None:
        """Kill every turtle, spawn turtle1 at the centre and clear (as the reset service)."""
        endpoints = list(self._endpoints.values())
        self._endpoints.clear()
        await asyncio.gather(*(self._detach(ends) for ends in endpoints))
        self.world.reset(await self._read_background())
        for name, turtle in self.world.turtles.items():
            self._endpoints[name] = await self._attach(name)
            self.node.log.info("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]", name, turtle.x, turtle.y,
                               turtle.theta)

    async def _on_clear(self, _req: Any) -> Any:
        self.node.log.info("Clearing turtlesim.")
        async with self._busy:
            await self.clear()
        return Empty._response_class()

    async def _on_reset(self, _req: Any) -> Any:
        self.node.log.info("Resetting turtlesim.")
        async with self._busy:
            await self.reset()
        return Empty._response_class()

    async def _on_spawn(self, req: Any) -> Any:
        async with self._busy:
            try:
                name = await self.spawn(req.name, req.x, req.y, req.theta)
            except NameTaken as exc:
                self.node.log.error("A turtle named [%s] already exists", req.name)
                raise ServiceException(str(exc)) from None
        return Spawn._response_class(name=name)

    async def _on_kill(self, req: Any) -> Any:
        async with self._busy:
            try:
                await self.kill(req.name)
            except UnknownTurtle:
                self.node.log.error("Tried to kill turtle [%s], which does not exist", req.name)
                raise ServiceException(f"Tried to kill turtle [{req.name}], which does not exist") from None
        return Kill._response_class()

    # -- parameters ---------------------------------------------------------------------------
    async def _ensure_background_params(self) -> None:
        node = self.node
        present = await asyncio.gather(*(node.has_param(key) for key in BACKGROUND_PARAMS))
        missing = [(key, value) for key, value, ok in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND, present) if not ok]
        await asyncio.gather(*(node.set_param(key, value) for key, value in missing))

    async def _read_background(self) -> tuple[int, int, int]:
        """The background from the parameters; a missing or non-integer one takes the default component."""
        node = self.node
        values = await asyncio.gather(*(node.get_param(key, None) for key in BACKGROUND_PARAMS))
        colour = []
        for key, value, default in zip(BACKGROUND_PARAMS, values, DEFAULT_BACKGROUND):
            if isinstance(value, int) and not isinstance(value, bool):
                colour.append(value & 0xFF)
            else:
                if value is not None:
                    node.log.warn("Parameter [%s] is %r, not an integer; using %d", node.resolve(key), value, default)
                colour.append(default)
        return colour[0], colour[1], colour[2]

    # -- the update loop ---------------------------------------------------------------------
    def _start_loop(self) -> None:
        loop = self._loop
        assert loop is not None
        now = loop.time()
        self._next_deadline = now + UPDATE_PERIOD
        self._window_start = now
        self._window_count = 0
        self._timer = loop.call_at(self._next_deadline, self._tick)

    def _stop_loop(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def _tick(self) -> None:
        loop = self._loop
        assert loop is not None
        try:
            self._update()
        except Exception as exc:  # one bad update must not stop the simulator
            self.node.log.error("turtlesim update failed: %s", exc)
        now = loop.time()
        self.updates += 1
        self._window_count += 1
        elapsed = now - self._window_start
        if elapsed >= RATE_WINDOW:
            self.rate = self._window_count / elapsed
            self._window_start = now
            self._window_count = 0
        deadline = self._next_deadline + UPDATE_PERIOD
        if deadline <= now:  # late by a whole period or more: skip the missed ticks, keep the phase
            deadline += math.ceil((now - deadline) / UPDATE_PERIOD) * UPDATE_PERIOD
            if deadline <= now:
                deadline += UPDATE_PERIOD
        self._next_deadline = deadline
        if self._timer is not None:
            self._timer = loop.call_at(deadline, self._tick)

    def _update(self) -> None:
        """One simulator step: move, warn about walls, publish poses and colours, tell listeners."""
        world = self.world
        hits = world.update(UPDATE_PERIOD)
        log = self.node.log
        for hit in hits:
            log.warn("Oh no! I hit the wall! (Clamping from [x=%f, y=%f])", hit.x, hit.y)
        endpoints = self._endpoints
        for name, turtle in world.turtles.items():
            ends = endpoints.get(name)
            if ends is None:
                continue
            pose = ends.pose
            if pose.impl.links or pose.impl.local:
                pose.publish(Pose(turtle.x, turtle.y, turtle.theta, turtle.linear_velocity, turtle.angular))
            color = ends.color
            if color.impl.links or color.impl.local:
                r, g, b = turtle.color
                color.publish(Color(r, g, b))
        for listener in self._listeners:
            listener()


async def run_headless(argv: Sequence[str]) -> int:
    """Run a turtlesim node with no display until Ctrl-C, SIGTERM or a shutdown request.

    Returns 0 after a clean shutdown (everything unregistered), 1 when the
    node could not start.
    """
    sim = TurtlesimNode(argv)
    loop = asyncio.get_running_loop()
    stop = asyncio.Event()
    reason = "user request"

    def on_signal(signum: int) -> None:
        nonlocal reason
        reason = "signal-interrupt" if signum == signal.SIGINT else "signal-terminate"
        stop.set()

    handled = []
    for signum in (signal.SIGINT, signal.SIGTERM):
        try:
            loop.add_signal_handler(signum, on_signal, signum)
            handled.append(signum)
        except (NotImplementedError, RuntimeError, ValueError):
            pass  # not the main thread: the caller handles signals
    starting = loop.create_task(sim.start())
    stopping = loop.create_task(stop.wait())
    status = 0
    try:
        await asyncio.wait({starting, stopping}, return_when=asyncio.FIRST_COMPLETED)
        if not starting.done():
            starting.cancel()  # interrupted while waiting for the master
        elif starting.exception() is None:
            ended = loop.create_task(sim.wait_stopped())
            await asyncio.wait({ended, stopping}, return_when=asyncio.FIRST_COMPLETED)
            ended.cancel()
        elif not sim.node.is_shutdown:
            print(f"turtlesim: cannot start: {starting.exception()}", file=sys.stderr)
            status = 1
    finally:
        stopping.cancel()
        await asyncio.gather(starting, return_exceptions=True)
        await sim.stop(reason)
        for signum in handled:
            loop.remove_signal_handler(signum)
    return status


def main(argv: Sequence[str]) -> int:
    """Blocking entry point for ``turtlesim_node --headless``: run on a fresh engine loop."""
    from rostui.core.node.engine import new_event_loop

    loop = new_event_loop()
    asyncio.set_event_loop(loop)
    try:
        return loop.run_until_complete(run_headless(argv))
    finally:
        loop.close()

