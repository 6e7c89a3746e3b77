"""SVG snapshots of `rostui monitor` (stored in snapshots/test_monitor_snapshots/).

The app runs for real against a `rostui core` master; a node in the test
publishes over TCPROS.  Only time is the test's: the app and its source
read a clock the test steps 0.1 s per message, and repaints and rate
samples happen when the test asks, so rates, bandwidths, ages and
sparklines come out the same on every machine.  Regenerate with
``pytest tests/test_monitor_snapshots.py --snapshot-update`` and look at the
SVGs before committing them.
"""

from __future__ import annotations

from typing import Any, Iterator

import pytest
from textual.pilot import Pilot

from rostui.apps.monitor.app import MonitorApp
from rostui.core.msg import get_message_class
from rostui.core.rostime import Time

from conftest import until
from live_helpers import Watcher
from textual_snapshots import snapshot, truecolor  # noqa: F401  (SVGs in snapshots/; one colour system)

DEADLINE = 30.0
TOPICS = ("/diagnostics/log", "/turtle1/cmd_vel")


class SteppedClock:
    """Wall time that moves only when the test says."""

    def __init__(self) -> None:
        self.now = 1_700_000_000.0

    def __call__(self) -> float:
        return self.now


class Talkers:
    """A node in the test publishing a Log and a Twist, one message per call to :meth:`step`."""

    def __init__(self) -> None:
        self.watcher = Watcher("snapshot_talker")
        self.log = self.watcher.publisher("/diagnostics/log", "rosgraph_msgs/Log")
        self.twist = self.watcher.publisher("/turtle1/cmd_vel", "geometry_msgs/Twist")
        log_class = get_message_class("rosgraph_msgs/Log")
        self.log_msg = log_class(level=2, name="/battery_monitor", msg="battery at 87%", file="battery.py",
                                 function="check", line=42, topics=[f"/battery/cell{i}" for i in range(12)])
        self.log_msg.header.stamp = Time(1_700_000_000, 500_000_000)
        self.twist_msg = get_message_class("geometry_msgs/Twist")()
        self.twist_msg.linear.x = 2.0
        self.twist_msg.angular.z = 1.8

    def step(self) -> None:
        """Publish one message on each topic."""
        self.log.publish(self.log_msg)
        self.twist.publish(self.twist_msg)

    def close(self) -> None:
        """Leave the master."""
        self.watcher.close()


@pytest.fixture
def talkers(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[Talkers]:
    """The publishing node."""
    talkers = Talkers()
    yield talkers
    talkers.close()


def stepped_app(clock: SteppedClock, topics: tuple[str, ...] = ()) -> MonitorApp:
    """The app with repaints and samples only on request."""
    return MonitorApp(topics, period=0.2, refresh=3600, sample_every=3600, clock=clock)


async def feed(pilot: Pilot, talkers: Talkers, clock: SteppedClock, messages: int = 31) -> None:
    """Once subscribed, publish ``messages`` per topic 0.1 s apart (on the clock), sampling every second."""
    app = pilot.app
    assert isinstance(app, MonitorApp)

    def connected() -> bool:
        app.repaint()
        stats = [app.source._watches.get(t) for t in TOPICS]
        # a watch exists before its subscription does: its handle is set once subscribing finished
        subscribed = all(w is not None and w.handle is not None and w.handle.get_num_connections() > 0 for w in stats)
        # and the publisher drops a message sent before its end of the connection has finished the handshake
        return subscribed and all(p.get_num_connections() > 0 for p in (talkers.log, talkers.twist))
    await until(connected, "the monitor connected to both topics, at both ends", DEADLINE)
    start = clock.now
    for k in range(messages):
        clock.now = start + k * 0.1
        talkers.step()
        await until(lambda: all(app.source.stats(t).messages == k + 1 for t in TOPICS), f"message {k + 1}", DEADLINE)
        if k and k % 10 == 0:
            app.source.sample()
    clock.now += 0.05
    app.repaint()
    await pilot.pause()


def test_table(snap_compare, talkers: Talkers) -> None:
    """The table: two live topics at 10 Hz with bandwidth and age, rosout's topics without publishers' messages."""
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed(pilot, talkers, clock)

    assert snap_compare(stepped_app(clock), run_before=run_before, terminal_size=(100, 12))


def test_expanded_log_tree(snap_compare, talkers: Talkers) -> None:
    """`rostui monitor /diagnostics/log`: the message tree (level 2 as INFO, 12 topics cut to 8) and the charts.

    Tab moves into the tree and Enter opens the topics array.
    """
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed(pilot, talkers, clock)
        app = pilot.app
        assert isinstance(app, MonitorApp)
        await pilot.press("tab")
        topics = app.message_trees.topic_node("/diagnostics/log").children[-1]
        app.message_trees.move_cursor(topics)
        await pilot.press("enter")
        await pilot.pause()

    assert snap_compare(stepped_app(clock, ("/diagnostics/log",)), run_before=run_before, terminal_size=(110, 40))


def test_publish_editor(snap_compare, talkers: Talkers) -> None:
    """p on /turtle1/cmd_vel: the editor with the Twist template rostopic pub's completion gives."""
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed(pilot, talkers, clock, messages=2)
        app = pilot.app
        assert isinstance(app, MonitorApp)
        assert app.table.select_topic("/turtle1/cmd_vel")
        await pilot.press("p")
        await pilot.pause()

    assert snap_compare(stepped_app(clock), run_before=run_before, terminal_size=(100, 30))


class PoseTalker:
    """A turtle's /turtle1/pose as turtlesim publishes it, on a fixed circle: one message per :meth:`step`."""

    def __init__(self) -> None:
        self.watcher = Watcher("snapshot_turtle")
        self.pub = self.watcher.publisher("/turtle1/pose", "turtlesim/Pose")
        self.pose_class = get_message_class("turtlesim/Pose")
        self.k = 0

    def step(self) -> None:
        """The next pose: 2 m/s along a circle of radius 2 around the window's centre (0.1 s later)."""
        import math

        angle = 0.1 * self.k
        self.pub.publish(self.pose_class(x=5.544 + 2 * math.sin(angle), y=5.544 - 2 * math.cos(angle) + 2,
                                         theta=math.remainder(angle, 2 * math.pi), linear_velocity=2.0,
                                         angular_velocity=1.0))
        self.k += 1

    def close(self) -> None:
        """Leave the master."""
        self.watcher.close()


@pytest.fixture
def turtle(rostui_core: Any, ros_env: dict[str, str]) -> Iterator[PoseTalker]:
    """The publishing turtle."""
    talker = PoseTalker()
    yield talker
    talker.close()


async def feed_pose(pilot: Pilot, turtle: PoseTalker, clock: SteppedClock, messages: int = 80) -> None:
    """Once the plotted fields are resolved and subscribed, publish ``messages`` poses 0.1 s apart on the clock."""
    app = pilot.app
    assert isinstance(app, MonitorApp)

    def connected() -> bool:
        app.repaint()
        watch = app.source._watches.get("/turtle1/pose")
        return not app.pending and watch is not None and watch.handle is not None \
            and watch.handle.get_num_connections() > 0
    await until(connected, "the monitor plotting /turtle1/pose", DEADLINE)
    start = clock.now
    for k in range(messages):
        clock.now = start + k * 0.1
        turtle.step()
        await until(lambda: app.source.stats("/turtle1/pose").messages == k + 1, f"pose {k + 1}", DEADLINE)
        if k and k % 10 == 0:
            app.source.sample()
    clock.now += 0.05
    app.repaint()
    await pilot.pause()


def test_plot_turtle_pose_80x24(snap_compare, turtle: PoseTalker) -> None:
    """`rostui monitor /turtle1/pose/x:y` at 80x24: the plot with axes, ticks, legend and the last 10 s."""
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed_pose(pilot, turtle, clock)

    assert snap_compare(stepped_app(clock, ("/turtle1/pose/x:y",)), run_before=run_before, terminal_size=(80, 24))


def test_plot_turtle_pose_100x32(snap_compare, turtle: PoseTalker) -> None:
    """`rostui monitor /turtle1/pose/x /turtle1/pose/y /turtle1/pose/theta` at 100x32, paused after 8 s."""
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed_pose(pilot, turtle, clock)
        await pilot.press("space")
        for _ in range(5):
            clock.now += 0.1
            turtle.step()
        await until(lambda: pilot.app.source.plot.since_pause == 15, "15 points counted while paused", DEADLINE)
        pilot.app.repaint()
        await pilot.pause()

    app = stepped_app(clock, ("/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta"))
    assert snap_compare(app, run_before=run_before, terminal_size=(100, 32))


def test_table_at_80x24(snap_compare, talkers: Talkers) -> None:
    """The table in an 80x24 terminal: the filter line and the key line starting with `? help  q quit`."""
    clock = SteppedClock()

    async def run_before(pilot: Pilot) -> None:
        await feed(pilot, talkers, clock, messages=2)

    assert snap_compare(stepped_app(clock), run_before=run_before, terminal_size=(80, 24))
