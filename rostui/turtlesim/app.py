"""TurtlesimApp: the turtlesim node, its renderer and arrow-key teleop in one terminal app.

On start the app makes sure a master answers (starting an embedded one when
none does and ROS_MASTER_URI names this machine), then runs two nodes on
Textual's event loop, as the book's two terminals would: ``/turtlesim``
(:class:`~rostui.turtlesim.node.TurtlesimNode`) and ``/teleop_turtle``, which
publishes each arrow key as ``geometry_msgs/Twist`` on ``<turtle>/cmd_vel``
and ``turtlesim/Velocity`` on the book's ``<turtle>/command_velocity``.
"""

from __future__ import annotations

import asyncio
import random
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from textual import events
from textual.app import ComposeResult
from textual.binding import Binding
from textual.widgets import Static

from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core import names
from rostui.core.log import Level, LogRecord
from rostui.core.log.console import format_line
from rostui.core.master.embedded import EmbeddedMaster, MasterStartError, ensure_master
from rostui.core.msg import get_message_class, get_service_class
from rostui.core.network import master_uri_from_env
from rostui.core.node.node import AsyncNode, MasterRefusedError, Publisher
from rostui.turtlesim.node import TurtlesimNode
from rostui.turtlesim.render import TurtleView
from rostui.turtlesim.teleop import NODE_NAME as TELEOP_NODE_NAME
from rostui.turtlesim.teleop import key_to_command, twist_bypasses_translator
from rostui.turtlesim.world import WORLD_SIZE

#: Status line refreshes per second (the pose text changes on every update while a turtle moves).
STATUS_RATE = 10.0

#: Seconds a WARN or ERROR of the turtlesim node stays in the status line.
NOTICE_SECONDS = 3.0

#: ROS arguments the teleop node shares with the turtlesim node (not its name, remaps or params).
_SHARED_SPECIALS = ("__ns", "__master", "__ip", "__hostname")

#: Key help: the first part ends the pose line, the second the master line.
TELEOP_KEYS = (key_line("↑↓←→ drive  Tab next"), "s spawn  c clear  r reset")
VIEW_KEYS = (key_line("Tab next"), "")
#: The key line while another node holds the teleop node's name (the arrow keys have no node to publish with).
TELEOP_TAKEN_KEYS = (key_line("↑↓←→ off: another /teleop_turtle runs  Tab next"), "s spawn  c clear  r reset")
#: Seconds between looks at the master for the name of the teleop node, while another node holds it.
TELEOP_RECLAIM_PERIOD = 1.0
#: Seconds within which a second q quits when other nodes use the embedded master.
QUIT_AGAIN_SECONDS = NOTICE_SECONDS


@dataclass(frozen=True)
class StatusInfo:
    """What the status line shows."""

    turtle: str
    x: float
    y: float
    theta: float
    rate: float
    master_uri: str
    embedded: bool
    teleop: bool
    state: str = "running"
    teleop_taken: bool = False
    notice: str = ""

    def lines(self) -> str:
        """Two lines: pose, rate and the main keys; the master and the other keys (or a fresh WARN)."""
        keys = TELEOP_TAKEN_KEYS if self.teleop_taken else TELEOP_KEYS if self.teleop else VIEW_KEYS
        master = f"embedded master {self.master_uri}" if self.embedded else f"master {self.master_uri}"
        if self.state != "running":
            return f"{self.state}…\n{master}"
        pose = f"{self.turtle} x {self.x:.2f} y {self.y:.2f} θ {self.theta:.2f}" if self.turtle else "no turtle"
        first = f"{pose} │ {self.rate:4.1f} Hz │ {keys[0]}"
        second = f"{master} │ {keys[1]}" if keys[1] else master
        if self.notice:
            second = self.notice
        return f"{first}\n{second}"


class StatusLine(Static):
    """Two lines under the world: the selected turtle's pose, update rate, master URI; key help."""

    def show(self, info: StatusInfo) -> None:
        """Display ``info`` (repaints only when the text changed)."""
        text = info.lines()
        if text != getattr(self, "_shown", None):
            self._shown = text
            self.update(text)


class TurtlesimApp(ReleasesOnExit, KeysApp):
    """turtlesim in the terminal: the simulator node, its view and (with ``teleop``) arrow-key driving.

    ``argv`` holds ROS arguments for the turtlesim node (``__name:=``,
    ``__ns:=``, remaps, ``_param:=``).  ``started`` is set once the nodes run.
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "turtlesim"

    BINDINGS = [
        Binding("q", "quit_asking", "quit (twice while other nodes use the master it started)"),
        Binding("tab", "select_next", "next turtle", priority=True),
        Binding("shift+tab", "select_previous", "previous turtle", priority=True),
        Binding("s", "spawn", "spawn"),
        Binding("c", "clear", "clear"),
        Binding("r", "reset", "reset"),
    ]

    def __init__(self, argv: Sequence[str] = (), *, teleop: bool = True) -> None:
        super().__init__()
        self.argv = list(argv)
        self.teleop = teleop
        args = names.parse_argv(self.argv)
        self.master_uri = master_uri_from_env(args.master)
        self.sim = TurtlesimNode(self.argv, master_uri=self.master_uri, console=False)
        self.embedded: EmbeddedMaster | None = None
        self.teleop_node: AsyncNode | None = None
        self.started = asyncio.Event()
        self._teleop_argv = [f"{key}:={args.specials[key]}" for key in _SHARED_SPECIALS if key in args.specials]
        self._publishers: dict[str, tuple[Publisher, Publisher]] = {}
        self._stopping = False
        self.farewell = ""
        """The node's shutdown line, printed once the app has left the screen (empty unless asked to shut down)."""
        self._selected = ""
        self._notice: tuple[float, str] = (0.0, "")
        self._quit_asked = float("-inf")
        self.sim.log.add_sink(self._on_log)

    # -- composition ---------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """The world view above the status line."""
        yield TurtleView(self.sim.world, id="world")
        yield StatusLine(id="status", markup=False)

    def on_mount(self) -> None:
        """Start ROS in the background, refresh the status line, stop cleanly on SIGTERM/SIGHUP."""
        self.run_worker(self._start_ros(), name="start-ros", exclusive=True, exit_on_error=False)
        self.set_interval(1.0 / STATUS_RATE, self.refresh_status)
        self.refresh_status()
        quit_on_signals(self)

    @property
    def view(self) -> TurtleView:
        """The world view."""
        return self.query_one("#world", TurtleView)

    @property
    def selected(self) -> str:
        """Name of the turtle the arrow keys drive."""
        return self._selected

    def select(self, name: str) -> None:
        """Make ``name`` the selected turtle."""
        self._selected = name
        self.view.selected = name
        if self.teleop and self.started.is_set() and name:
            self.run_worker(self._publishers_for(name), group="advertise")
        self.refresh_status()

    # -- ROS -------------------------------------------------------------------------
    async def _start_ros(self) -> None:
        try:
            self.embedded = await ensure_master(self.master_uri)
            await self.sim.start()
            if self.teleop:
                await self._start_teleop_node()
        except MasterStartError as exc:
            await self._fail(f"ERROR: {exc}")
            return
        except Exception as exc:  # a node could not register: say why in one line
            await self._fail(f"ERROR: turtlesim could not start: {exc}")
            return
        self.started.set()
        self.select(next(iter(self.sim.world.turtles), ""))
        reason = await self.sim.wait_stopped()
        if not self._stopping:  # `rostui node kill /turtlesim`, a same-name node, or the master asked
            await self._stop_ros()
            # A node asked to shut down ends normally (as roscpp's turtlesim does), saying why as the node logged it.
            self.farewell = format_line(Level.WARN, f"Shutdown request received. Reason given for shutdown: [{reason}]",
                                        self.sim.name)
            self.exit(0)

    async def _start_teleop_node(self) -> None:
        """Register the arrow keys' node and watch for another node taking its name."""
        node = AsyncNode(TELEOP_NODE_NAME, argv=self._teleop_argv, master_uri=self.master_uri)
        node.log.console = None  # its "Shutdown request received" must not write over the screen
        await node.start()
        self.teleop_node = node
        self.run_worker(self._watch_teleop_node(node), group="teleop", exit_on_error=False)

    async def _watch_teleop_node(self, node: AsyncNode) -> None:
        """Another /teleop_turtle (`rostui teleop`, turtle_teleop_key) makes the master shut ours down, as ROS
        does with a name registered twice: say so, and take the name back once that node has gone."""
        reason = await node.wait_shutdown()
        if self._stopping:
            return
        self.teleop_node = None
        self._publishers.clear()
        self.notify(f"{node.name} was taken by another node ({reason}): the arrow keys are off until it ends",
                    title="teleop", severity="warning", timeout=8)
        self.refresh_status()
        while not self._stopping and self.sim.node is not None:
            await asyncio.sleep(TELEOP_RECLAIM_PERIOD)
            try:
                await self.sim.node.master_call("lookupNode", node.name)
                continue  # the other node still holds the name
            except MasterRefusedError:
                pass  # no such node: the name is free again
            except Exception:
                continue  # no master just now
            if self._stopping:
                return
            try:
                await self._start_teleop_node()
            except Exception:
                continue
            self.notify(f"{node.name} is free again: the arrow keys drive", title="teleop", timeout=5)
            self.select(self._selected)
            return

    async def _fail(self, message: str) -> None:
        await self._stop_ros()
        self.exit(1, return_code=1, message=message)

    async def _stop_ros(self) -> None:
        """Shut both nodes down (unregistering them), then the embedded master; idempotent."""
        if self._stopping:
            return
        self._stopping = True
        for stop in (
            lambda: self.teleop_node.shutdown("turtlesim app quit") if self.teleop_node else None,
            lambda: self.sim.stop("turtlesim app quit"),
            lambda: self.embedded.stop() if self.embedded else None,
        ):
            try:
                pending = stop()
                if pending is not None:
                    await asyncio.wait_for(pending, 5.0)
            except Exception:  # keep stopping the rest; the process is ending anyway
                pass

    async def _publishers_for(self, turtle: str) -> tuple[Publisher, Publisher] | None:
        """The (Twist, Velocity) publishers of ``turtle``, advertised on first use."""
        pubs = self._publishers.get(turtle)
        if pubs is None and self.teleop_node is not None and self.sim.node is not None:
            twist = await self.teleop_node.advertise(
                self.sim.node.resolve(f"{turtle}/cmd_vel"), get_message_class("geometry_msgs/Twist"), queue_size=1)
            velocity = await self.teleop_node.advertise(
                self.sim.node.resolve(f"{turtle}/command_velocity"), get_message_class("turtlesim/Velocity"),
                queue_size=1)
            pubs = self._publishers.setdefault(turtle, (twist, velocity))
        return pubs

    async def drive(self, turtle: str, linear: float, angular: float) -> None:
        """Publish one teleop command to ``turtle`` on both its command topics."""
        pubs = await self._publishers_for(turtle)
        if pubs is None:
            return
        twist_pub, velocity_pub = pubs
        for _ in range(40):  # a just-advertised topic: give the simulator a moment to connect
            if twist_pub.get_num_connections() > 0 or self._stopping:
                break
            await asyncio.sleep(0.025)
        twist = twist_pub.msg_class()
        twist.linear.x = linear
        twist.angular.z = angular
        if not twist_bypasses_translator(twist_pub.subscriber_names(), velocity_pub.subscriber_names()):
            twist_pub.publish(twist)
        velocity_pub.publish(velocity_pub.msg_class(linear=linear, angular=angular))

    def _on_log(self, record: LogRecord) -> None:
        """Keep the turtlesim node's last WARN/ERROR (e.g. the wall) for the status line."""
        if record.level >= Level.WARN:
            self._notice = (time.monotonic(), f"[{record.level.name}] {record.message}")

    # -- status ------------------------------------------------------------------------
    def status_info(self) -> StatusInfo:
        """The values the status line shows now."""
        turtle = self.sim.world.turtles.get(self._selected)
        state = "running" if self.started.is_set() else "starting"
        stamp, notice = self._notice
        return StatusInfo(
            turtle=turtle.name if turtle else "",
            x=turtle.x if turtle else 0.0,
            y=turtle.y if turtle else 0.0,
            theta=turtle.theta if turtle else 0.0,
            rate=self.sim.rate,
            master_uri=self.embedded.uri if self.embedded else self.master_uri,
            embedded=self.embedded is not None,
            teleop=self.teleop,
            state=state,
            teleop_taken=self.teleop and self.started.is_set() and self.teleop_node is None,
            notice=notice if time.monotonic() - stamp < NOTICE_SECONDS else "",
        )

    def refresh_status(self) -> None:
        """Keep the selection valid and show the current status."""
        turtles = self.sim.world.turtles
        if self.started.is_set() and self._selected not in turtles and turtles:
            self.select(next(iter(turtles)))
            return
        for status in self.query("#status").results(StatusLine):  # none while the screen is torn down
            status.show(self.status_info())

    # -- keys ---------------------------------------------------------------------------
    def key_notes(self) -> tuple[tuple[str, str], ...]:
        """The arrow keys drive (teleop mode); they are read in :meth:`on_key`, not bound."""
        if not self.teleop:
            return ()
        return (("↑ / ↓", "drive forward / backward"), ("← / →", "turn left / right"))

    def on_key(self, event: events.Key) -> None:
        """Arrow keys drive the selected turtle (teleop mode)."""
        command = key_to_command(event.key)
        if command is None or not self.teleop:
            return
        event.stop()
        if self.started.is_set() and self._selected:
            self.run_worker(self.drive(self._selected, *command), group="drive")

    def _step_selection(self, step: int) -> None:
        names_ = list(self.sim.world.turtles)
        if not names_:
            return
        index = names_.index(self._selected) if self._selected in names_ else -step
        self.select(names_[(index + step) % len(names_)])

    def action_select_next(self) -> None:
        """Tab: select the next turtle (spawn order)."""
        self._step_selection(1)

    def action_select_previous(self) -> None:
        """Shift+Tab: select the previous turtle."""
        self._step_selection(-1)

    async def action_spawn(self) -> None:
        """Spawn a turtle at a random pose and select it."""
        if not self.started.is_set() or not self.teleop:
            return
        margin = 1.0
        name = await self.sim.spawn("", random.uniform(margin, WORLD_SIZE - margin),
                                    random.uniform(margin, WORLD_SIZE - margin), random.uniform(-3.14, 3.14))
        self.select(name)

    async def action_clear(self) -> None:
        """Clear the trails through the node's ``clear`` service (re-reads the background params)."""
        await self._call_empty_service("clear")

    async def action_reset(self) -> None:
        """Reset the simulator through the node's ``reset`` service."""
        await self._call_empty_service("reset")

    async def _call_empty_service(self, name: str) -> None:
        caller = self.teleop_node or self.sim.node  # the sim's own node while another holds the teleop's name
        if not self.started.is_set() or caller is None or self.sim.node is None:
            return
        proxy = caller.service_proxy(self.sim.node.resolve(name), get_service_class("std_srvs/Empty"))
        try:
            await proxy.call()
        except Exception as exc:
            self.notify(f"{name} failed: {exc}", severity="error")

    async def release(self) -> None:
        """Unregister the nodes and stop the embedded master (saying which other nodes it leaves behind)."""
        if self.embedded is not None and not self._stopping:
            others = await self._other_nodes()
            if others:
                self.farewell = (f"turtlesim stopped the master it started at {self.embedded.uri}; "
                                 f"{', '.join(others)} {'is' if len(others) == 1 else 'are'} left without a master "
                                 "(start `rostui core` first to keep them connected)")
        await self._stop_ros()

    async def action_quit_asking(self) -> None:
        """q: quit; when other nodes use the master this turtlesim started, the first q says so and a second
        q within a few seconds quits (Ctrl-C and signals quit at once, saying which nodes lose their master)."""
        if self.embedded is not None and not self._stopping:
            others = await self._other_nodes()
            now = time.monotonic()
            if others and now - self._quit_asked > QUIT_AGAIN_SECONDS:
                self._quit_asked = now
                self._notice = (now, f"{', '.join(others)} use the master turtlesim started: q again quits "
                                     "and stops it")
                self.refresh_status()
                return
        await self.action_quit()

    async def _other_nodes(self) -> list[str]:
        """The nodes registered with this process's embedded master besides its own, sorted."""
        node = self.sim.node
        if node is None:
            return []
        try:
            publishers, subscribers, services = await asyncio.wait_for(node.master_call("getSystemState"), 2.0)
        except Exception:
            return []
        ours = {node.name, "/rosout"} | ({self.teleop_node.name} if self.teleop_node is not None else set())
        ours.add(node.resolve(f"/{TELEOP_NODE_NAME}"))
        listed = {n for _name, nodes in (*publishers, *subscribers, *services) for n in nodes}
        return sorted(listed - ours)


def run_app(argv: Sequence[str], *, teleop: bool = True) -> int:
    """Run :class:`TurtlesimApp` in this terminal; returns the exit status.

    Prints one line and returns 1 when stdin or stdout is not a terminal.
    """
    if terminal_missing("turtlesim", "use `rostui run turtlesim turtlesim_node --headless` without one"):
        return 1
    try:
        app = TurtlesimApp(argv, teleop=teleop)
    except (names.InvalidNameError, ValueError) as exc:
        print(f"ERROR: {exc}", file=sys.stderr)
        return 1
    app.run()
    if app.farewell:
        print(app.farewell, file=sys.stderr, flush=True)
    return app.return_code or 0
