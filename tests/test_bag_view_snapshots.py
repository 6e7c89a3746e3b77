"""SVG snapshots of `rostui bag view` (stored in snapshots/test_bag_view_snapshots/).

The bag is the book's kind: turtlesim poses at 50 Hz for 12 s, velocity
commands in bursts (the turtle drives a side, turns, drives on), one latched
parameter-like message and a few log lines. Every stamp lies on a 10 ms grid
and wall times are shown in UTC. The playing state runs the transport on a
frozen clock (its wall clock is a constructor argument), so the screen is the
same on every run. Record mode records a burst of exactly 42 messages from a
publisher process on a live master, then waits until the rates have decayed.
Regenerate with ``pytest tests/test_bag_view_snapshots.py --snapshot-update``
and look at the SVGs before committing them.
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.bagview.record_app import BagRecordApp
from rostui.core.bag.files import open_writer
from rostui.core.bag.model import Connection
from rostui.tools.bag.recorder import RecordOptions
from rostui.core.msg import get_message_class

from conftest import REPO, stop_process, until
from textual_snapshots import snapshot  # noqa: F401  (stores SVGs in snapshots/)

T0 = 1_795_360_000_000_000_000
MS = 1_000_000

Pose = get_message_class("turtlesim/Pose")
Velocity = get_message_class("turtlesim/Velocity")
Log = get_message_class("rosgraph_msgs/Log")
Int32 = get_message_class("std_msgs/Int32")


@pytest.fixture(autouse=True)
def fixed_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """Truecolor, UTC."""
    monkeypatch.setenv("COLORTERM", "truecolor")
    monkeypatch.setenv("TERM", "xterm-256color")
    monkeypatch.delenv("NO_COLOR", raising=False)
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()


def conn(cid: int, topic: str, cls: Any, callerid: str, latching: bool = False) -> Connection:
    """A connection of ``cls`` on ``topic``."""
    return Connection(cid, topic, cls._type, cls._md5sum, cls._full_text, callerid, latching)


def write_square_bag(path: Path) -> Path:
    """Poses at 50 Hz for 12 s, velocity bursts, one latched count, log lines."""
    writer = open_writer(str(path))
    writer.add_connection(conn(0, "/turtle1/pose", Pose, "/turtlesim"))
    writer.add_connection(conn(1, "/turtle1/command_velocity", Velocity, "/draw_square"))
    writer.add_connection(conn(2, "/squares_drawn", Int32, "/draw_square", latching=True))
    writer.add_connection(conn(3, "/rosout", Log, "/draw_square"))
    writer.write(2, T0, Int32(data=3).serialize())
    x, y, theta = 5.544, 5.544, 0.0
    for i in range(600):
        t = T0 + i * 20 * MS
        side = (i // 150) % 4
        turning = i % 150 >= 120
        if i % 5 == 0 and (i // 150) != 2:  # commands at 10 Hz, none during the third side
            cmd = Velocity(linear=0.0 if turning else 2.0, angular=1.57 if turning else 0.0)
            writer.write(1, t, cmd.serialize())
        if turning:
            theta += 1.57 * 0.02
        else:
            x += 2.0 * 0.02 * (1 if side in (0, 3) else -1)
        writer.write(0, t, Pose(x=x, y=y, theta=theta, linear_velocity=0.0 if turning else 2.0,
                                angular_velocity=1.57 if turning else 0.0).serialize())
        if i % 150 == 0:
            log = Log(level=2, name="/draw_square", msg=f"side {i // 150 + 1}", file="draw_square.py",
                      function="main", line=42)
            log.header.stamp.secs, log.header.stamp.nsecs = divmod(t, 1_000_000_000)
            writer.write(3, t, log.serialize())
    writer.close()
    return path


@pytest.fixture
def square_bag(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> str:
    """The square bag in the test's folder, named as a user in that folder would name it."""
    monkeypatch.chdir(tmp_path)
    write_square_bag(tmp_path / "square.mcap")
    return "square.mcap"


#: A master URI nothing answers on (the discard port on loopback refuses at once).
NO_MASTER = "http://127.0.0.1:9/"


async def _loaded(pilot: Pilot) -> BagViewApp:
    app = pilot.app
    assert isinstance(app, BagViewApp)
    await until(lambda: app.transport is not None, "the bag to be read")
    return app


def test_paused_with_inspector(snap_compare, square_bag: str) -> None:
    """Paused at 37% with the pose selected: the cursor through every strip, the pose under it decoded."""
    async def run_before(pilot: Pilot) -> None:
        app = await _loaded(pilot)
        await pilot.press("g", *"37%", "enter", "down", "down", "down")
        app.refresh_view()
        await pilot.pause()

    assert snap_compare(BagViewApp([square_bag], publish=False), run_before=run_before, terminal_size=(120, 32))


def test_playing_at_double_rate_publishing_a_topic_with_no_master_and_loop(snap_compare, square_bag: str) -> None:
    """Playing ×2 with loop, /rosout switched on for publishing (●) with no master to publish to (the header
    says so), the velocity command under the cursor (frozen clock)."""
    async def run_before(pilot: Pilot) -> None:
        app = await _loaded(pilot)
        await pilot.press("g", *"4.5", "enter")
        for _ in range(3):
            await pilot.press("s")
        await pilot.press("t", "down", "down", "plus", "l", "space")
        assert app.transport is not None and not app.transport.paused and app.publishing == {"/rosout"}
        await until(lambda: app.link.startswith("no master at"), "the app to find no master")
        app.refresh_view()
        await pilot.pause()

    app = BagViewApp([square_bag], master_uri=NO_MASTER, clock=lambda: 1000.0)
    assert snap_compare(app, run_before=run_before, terminal_size=(120, 32))


def test_small_terminal(snap_compare, square_bag: str) -> None:
    """80x24 at the end of the bag: long names cut, key help cut, the end state."""
    async def run_before(pilot: Pilot) -> None:
        app = await _loaded(pilot)
        await pilot.press("end")
        app.refresh_view()
        await pilot.pause()

    assert snap_compare(BagViewApp([square_bag], publish=False), run_before=run_before, terminal_size=(80, 24))


#: Chunk age for the recording snapshots: the burst stays in one chunk, so the sizes shown do not depend on
#: whether the recorder's half-second flush fell in the middle of the burst (it does on a loaded machine:
#: 3.2 KB in two chunks where one chunk is 2.5 KB).
ONE_CHUNK = 3600.0

BURST = r'''
import time
from rostui import client as ros
ros.init_node("burst")
String = ros.msg("std_msgs/String")
Pose = ros.msg("turtlesim/Pose")
chatter = ros.Publisher("/chatter", String, queue_size=100)
pose = ros.Publisher("/turtle1/pose", Pose, queue_size=100)
while chatter.get_num_connections() < 1 or pose.get_num_connections() < 1:
    time.sleep(0.02)
time.sleep(0.3)
for n in range(30):
    chatter.publish(String(data="hello world %d" % n))
for n in range(12):
    pose.publish(Pose(x=float(n)))
print("sent", flush=True)
while not ros.is_shutdown():
    time.sleep(0.1)
'''


def start_burst(tmp_path: Path, ros_env: dict[str, str]) -> tuple[subprocess.Popen, Path]:
    """Start the burst of 30 + 12 messages (BURST); returns the process and the file its output goes to."""
    script = tmp_path / "burst.py"
    script.write_text(BURST)
    out = tmp_path / "burst.out"
    with out.open("w") as sink:
        burst = subprocess.Popen([sys.executable, str(script)], env=ros_env, cwd=REPO, stdout=sink,
                                 stderr=subprocess.STDOUT)
    return burst, out


def rates_settled(session: Any) -> bool:
    """True when every topic's rate reads 0 and stays 0 at the next redraw: the oldest sample in its window
    already holds today's count (one sample alone reads 0 too, but the next one may show the burst)."""
    return all(m.samples and m.samples[0][1] == m.count for m in session.meters.values())


@pytest.mark.parametrize("size", [(100, 20), (80, 24)], ids=["100x20", "80x24"])
def test_record_mode(snap_compare, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, rostui_core: Any,
                     ros_env: dict[str, str], size: tuple[int, int]) -> None:
    """Recording two topics after a burst of 30 + 12 messages: counts, sizes, rates back to 0; at 80x24 the
    key line starts with `? help  q quit`."""
    monkeypatch.chdir(tmp_path)
    burst, out = start_burst(tmp_path, ros_env)

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, BagRecordApp)
        session = app.session
        await until(lambda: session.recording, "recording")
        await until(lambda: "sent" in out.read_text(), "the burst")
        await until(lambda: sum(m.count for m in session.meters.values()) >= 42, "42 messages counted")
        await until(lambda: rates_settled(session), "rates back to 0", timeout=20)
        await until(lambda: session.total_bytes > 0 and session.messages == 42, "42 messages written")
        app.refresh_view()
        await pilot.pause()

    try:
        app = BagRecordApp(RecordOptions(topics=["/chatter", "/turtle1/pose"], output_name="session.mcap",
                                         max_chunk_age=ONE_CHUNK))
        assert snap_compare(app, run_before=run_before, terminal_size=size)
    finally:
        stop_process(burst)


def test_record_mode_stopped_at_its_duration(snap_compare, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                             rostui_core: Any, ros_env: dict[str, str]) -> None:
    """--duration 6: the burst of 30 + 12 is recorded, then the recording stops by itself and says so."""
    from rostui.tools.bag.record_options import record_options

    monkeypatch.chdir(tmp_path)
    burst, out = start_burst(tmp_path, ros_env)

    async def run_before(pilot: Pilot) -> None:
        app = pilot.app
        assert isinstance(app, BagRecordApp)
        session = app.session
        await until(lambda: "sent" in out.read_text(), "the burst")
        await until(lambda: session.current is None and session.files, "the stop at --duration 6, file closed")
        assert session.messages == 42, "the burst did not fit in the 6 s"
        await until(lambda: rates_settled(session), "rates back to 0", timeout=20)
        app.refresh_view()
        await pilot.pause()

    try:
        options = record_options(["/chatter", "/turtle1/pose"], name="session.mcap", duration="6")
        options.max_chunk_age = ONE_CHUNK
        app = BagRecordApp(options)
        assert snap_compare(app, run_before=run_before, terminal_size=(100, 20))
    finally:
        stop_process(burst)
