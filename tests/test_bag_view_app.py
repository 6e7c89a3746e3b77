"""`rostui bag view` driven with Textual's pilot: every key, and what a subscribing node receives.

Live tests run `rostui core`, a subscriber in its own process (a real node
over TCPROS) and the app publishing through its node on Textual's loop. The
acceptance points of issue 9: seek to 50% then play publishes the second half
only; each step while paused publishes exactly one message.
"""

from __future__ import annotations

import asyncio
import io
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any
from xmlrpc.client import ServerProxy

import pytest
from rich.console import Console
from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp, parse_goto
from rostui.apps.bagview.record_app import BagRecordApp, topics_table
from rostui.core.bag.files import open_reader
from rostui.tools.bag.recorder import RecordOptions

from bag_view_helpers import STEP_NS, T0, Counter, Int32, write_counts
from bag_view_helpers import run_pilot as run
from cli_helpers import rostui
from conftest import REPO, start_rostui_core, stop_process, until


@pytest.fixture(autouse=True)
def utc(monkeypatch: pytest.MonkeyPatch) -> None:
    """Wall times shown in UTC."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()


@pytest.fixture
def counts_bag(tmp_path: Path) -> Path:
    """The counts bag (MCAP)."""
    return write_counts(tmp_path / "counts.mcap")


def status(app: BagViewApp) -> str:
    """The status line's text."""
    return str(app.status.render())


async def loaded(app: BagViewApp) -> None:
    """Wait until the bag is read."""
    await until(lambda: app.transport is not None, "the bag to be read")


async def publishing(app: BagViewApp, counter: Counter) -> None:
    """Wait until the app's node publishes every topic and the counter is connected to it."""
    await loaded(app)
    await until(lambda: app.node is not None, f"the app's node ({app.link})")
    await until(counter.connected, "the counter to connect to the app's publishers")


# -- acceptance, on a live graph -----------------------------------------------------------------
@pytest.mark.parametrize("name", ["counts.mcap", "counts.bag"])
def test_seek_to_half_then_play_publishes_the_second_half_only(name: str, tmp_path: Path, rostui_core: Any,
                                                                ros_env: dict[str, str]) -> None:
    path = write_counts(tmp_path / name)
    counter = Counter(ros_env, tmp_path, "/count", "/odd")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await publishing(app, counter)
        await pilot.press("5")
        assert app.transport is not None and app.transport.fraction() == pytest.approx(0.5)
        await pilot.press("space")
        await until(lambda: app.transport is not None and app.transport.at_end and app.transport.paused,
                    "the end of the bag")
        await until(lambda: len(counter.received()) >= 75, "the second half at the counter")
        await asyncio.sleep(0.5)
        app.refresh_view()
        assert "■ END" in status(app) and "published 75" in status(app)

    try:
        run(BagViewApp([str(path)], publish_all=True), scenario)
        assert counter.values("/count") == list(range(50, 100))
        assert counter.values("/odd") == list(range(51, 100, 2))
    finally:
        counter.close()


def test_each_step_while_paused_publishes_exactly_one_message(counts_bag: Path, tmp_path: Path, rostui_core: Any,
                                                              ros_env: dict[str, str]) -> None:
    counter = Counter(ros_env, tmp_path, "/count", "/odd")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await publishing(app, counter)
        await pilot.press("2")  # 20%: /count 20 is next (19.8 ms... rounds up to message 20)
        for n in range(1, 7):
            await pilot.press("s")
            await until(lambda: len(counter.received()) >= n, f"step {n} at the counter")
            await asyncio.sleep(0.3)
            assert len(counter.received()) == n, f"step {n} published more than one message"
        assert app.transport is not None and app.transport.paused
        assert "PAUSED" in status(app)

    try:
        run(BagViewApp([str(counts_bag)], publish_all=True), scenario)
        assert counter.received() == [("/count", 20), ("/count", 21), ("/odd", 21), ("/count", 22),
                                      ("/count", 23), ("/odd", 23)]
    finally:
        counter.close()


def test_switched_off_topic_is_not_published(counts_bag: Path, tmp_path: Path, rostui_core: Any,
                                             ros_env: dict[str, str]) -> None:
    counter = Counter(ros_env, tmp_path, "/count", "/odd")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        await pilot.press("a")  # every topic on
        await publishing(app, counter)
        await pilot.press("down", "t")  # /odd off
        assert app.publishing == {"/count"}
        await until(lambda: {topic for topic, _ in app.publishers} == {"/count"}, "/odd unadvertised")
        await pilot.press("8", "space")
        await until(lambda: app.transport is not None and app.transport.at_end, "the end")
        await until(lambda: len(counter.values("/count")) >= 20, "the last 20 counts")

    try:
        run(BagViewApp([str(counts_bag)]), scenario)
        assert counter.values("/count") == list(range(80, 100))
        assert counter.values("/odd") == []
    finally:
        counter.close()


def test_nothing_is_published_until_a_topic_is_switched_on(counts_bag: Path, tmp_path: Path, rostui_core: Any,
                                                          ros_env: dict[str, str]) -> None:
    """Next to a live robot, playing a bag sends nothing: no node joins the master and a subscriber hears
    nothing until t publishes the selected topic (rqt_bag's Publish box); t again unadvertises it."""
    counter = Counter(ros_env, tmp_path, "/count", "/odd")
    master = ServerProxy(ros_env["ROS_MASTER_URI"])

    def bag_view_publishes() -> set[str]:
        publishers = master.getSystemState("/bag_view_test")[2][0]
        return {topic for topic, nodes in publishers if any(n.startswith("/bag_view") for n in nodes)}

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        assert "not publishing: t publishes the selected topic, a every topic" in str(app.header.render())
        await pilot.press("space")
        await until(lambda: app.transport is not None and app.transport.at_end, "the end of the bag")
        assert app.node is None and bag_view_publishes() == set() and counter.received() == []
        assert "published" not in status(app)
        await pilot.press("t")  # the selected topic, /count
        await until(lambda: bag_view_publishes() == {"/count"}, "/count advertised on the master")
        await until(lambda: "connected /count" in counter.lines(), "the counter to connect to /count")
        await until(lambda: "publishing 1 topic as /bag_view_" in app.link, "the header to say what is published")
        app.refresh_view()
        assert app.link in str(app.header.render())
        assert "● /count" in str(app.timeline.render()) and "○ /odd" in str(app.timeline.render())
        await pilot.press("9", "space")
        await until(lambda: len(counter.values("/count")) >= 10, "the last ten counts")
        await pilot.press("t")
        await until(lambda: bag_view_publishes() == set(), "/count unadvertised")

    try:
        run(BagViewApp([str(counts_bag)]), scenario)
        assert counter.values("/count") == list(range(90, 100)) and counter.values("/odd") == []
    finally:
        counter.close()


def test_without_a_master_it_browses_and_publishes_once_one_starts(counts_bag: Path, tmp_path: Path,
                                                                  ros_env: dict[str, str]) -> None:
    core: list[subprocess.Popen] = []

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        await until(lambda: "no master at" in str(app.header.render()), "the no-master notice")
        await pilot.press("5")
        assert app.transport is not None and app.transport.fraction() == pytest.approx(0.5)
        core.append(start_rostui_core(ros_env))
        counter = Counter(ros_env, tmp_path, "/count")
        try:
            await until(lambda: app.link.startswith("publishing"), "the node once the master answers")
            app.refresh_view()
            assert "publishing 2 topics as /bag_view_" in str(app.header.render())
            await until(counter.connected, "the counter to connect")
            await pilot.press("s")
            await until(lambda: counter.received() == [("/count", 50)], "a step published")
        finally:
            counter.close()

    try:
        run(BagViewApp([str(counts_bag)], publish_all=True), scenario)
    finally:
        for proc in core:
            stop_process(proc)


# -- keys, offline --------------------------------------------------------------------------------
def test_keys_move_the_cursor_change_rate_loop_topics_and_inspector(counts_bag: Path) -> None:
    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        t = app.transport
        assert t is not None and t.paused
        assert "browsing only" in str(app.header.render())
        await pilot.press("end")
        assert t.bag_ns() == t.end_ns
        await pilot.press("home", "right")
        assert t.bag_ns() == t.end_ns  # +1 s on a 0.99 s bag: clamped at the end
        await pilot.press("3")
        assert t.bag_ns() == T0 + round(99 * STEP_NS * 0.3)
        await pilot.press("left")
        assert t.bag_ns() == T0
        await pilot.press("pagedown", "pagedown")
        assert t.fraction() == pytest.approx(0.2)
        await pilot.press("g", *"75%", "enter")
        assert t.fraction() == pytest.approx(0.75)
        await pilot.press("g", *"0.25", "enter")
        assert t.bag_ns() == T0 + 250_000_000
        await pilot.press("g", *"soon", "enter")
        assert t.bag_ns() == T0 + 250_000_000
        await pilot.press("plus")
        assert t.rate == 2.0
        await pilot.press("minus", "minus", "minus")
        assert t.rate == 0.25
        await pilot.press("l")
        assert t.loop and " loop " in status(app)
        await pilot.press("down", "t", "a")  # browsing only: t and a say so and publish nothing
        assert app.publishing == set() and app.node is None and "○ /odd" in str(app.timeline.render())
        assert any("opened with --no-publish" in n.message for n in app._notifications)
        app.refresh_view()
        assert str(app.inspector_text.render()) == "data: 25"  # /odd under the cursor at 0.25 s
        assert "/odd  std_msgs/Int32  #13 of 50" in str(app.inspector_title.render())
        await pilot.press("up")
        app.refresh_view()
        assert str(app.inspector_text.render()) == "data: 25"
        await pilot.press("down", "full_stop", "full_stop")
        app.refresh_view()
        assert t.bag_ns() == T0 + 290_000_000 and str(app.inspector_text.render()) == "data: 29"
        await pilot.press("comma")
        assert t.bag_ns() == T0 + 270_000_000
        await pilot.press("home", "comma")
        assert t.bag_ns() == T0
        await pilot.press("i")
        assert not app.inspector.display

    run(BagViewApp([str(counts_bag)], publish=False), scenario)


def test_step_while_playing_pauses_and_play_at_the_end_starts_over(counts_bag: Path) -> None:
    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        t = app.transport
        assert t is not None
        before = t.published
        await pilot.press("9", "space")  # the last tenth may play out before the next line runs
        await until(lambda: t.paused and t.at_end and t.published > before, "the last tenth played to the end")
        played: list[int] = []
        publish = t.publish

        def recording(conn: Any, ns: int, data: bytes) -> None:
            played.append(ns)
            publish(conn, ns, data)

        t.publish = recording
        await pilot.press("space")
        assert not t.paused
        # what was published, not where the cursor is: a slow machine's catching up may pass any point between
        # two looks
        await until(lambda: bool(played), "playing again")
        assert played[0] == T0, "play at the end starts over from the first message"
        await pilot.press("s")
        assert t.paused

    run(BagViewApp([str(counts_bag)], publish=False, rate=0.5), scenario)


def test_parse_goto() -> None:
    start, end = T0, T0 + 10_000_000_000
    assert parse_goto("50%", start, end) == T0 + 5_000_000_000
    assert parse_goto(" 2.5 ", start, end) == T0 + 2_500_000_000
    assert parse_goto("1700000001.5", start, end) == T0 + 1_500_000_000
    for bad in ("150%", "x", ""):
        with pytest.raises(ValueError):
            parse_goto(bad, start, end)


def test_a_truncated_bag_opens_with_a_notice(tmp_path: Path) -> None:
    path = tmp_path / "cut.bag"
    write_counts(path, count=400, flush_every=100)
    size = path.stat().st_size
    with open(path, "r+b") as f:
        f.truncate(size // 2)

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await loaded(app)
        assert app.index is not None and 0 < len(app.index) < 600
        header = str(app.header.render())
        assert "cut.bag" in header and "showing what is readable" in header

    run(BagViewApp([str(path)], publish=False), scenario)


def test_missing_and_garbage_files_are_one_line(tmp_path: Path, ros_env: dict[str, str]) -> None:
    junk = tmp_path / "junk.mcap"
    junk.write_bytes(os.urandom(3000))
    empty = tmp_path / "empty.bag"
    empty.write_bytes(b"#ROSBAG V2.0\n" + os.urandom(200))
    for args in (["view", str(tmp_path / "nope.mcap")], ["view", str(junk)], ["view", str(empty)], ["view"],
                 ["view", "-r", "0", str(junk)], ["view", "--record"],
                 ["view", "--record", "-a", "--mcap", "--compression", "bz2"]):
        result = rostui(["bag", *args], ros_env, timeout=30)
        assert result.returncode == 1, (args, result.stdout, result.stderr)
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("rostui bag view"), (args, result.stderr)
        assert "Traceback" not in result.stderr


# -- record mode ----------------------------------------------------------------------------------
TALKER = r'''
import sys
from rostui import client as ros
ros.init_node("view_talker")
pub = ros.Publisher("/numbers", ros.msg("std_msgs/Int32"), queue_size=100)
rate = ros.Rate(100)
n = 0
while not ros.is_shutdown():
    pub.publish(ros.msg("std_msgs/Int32")(data=n))
    n += 1
    rate.sleep()
'''


def file_values(path: Path) -> list[int]:
    """The /numbers values in a recorded file."""
    reader = open_reader(str(path))
    try:
        return [Int32().deserialize(d).data for c, _t, d in reader.messages() if c.topic == "/numbers"]
    finally:
        reader.close()


def test_record_counts_live_and_splits_without_losing_or_doubling(tmp_path: Path, rostui_core: Any,
                                                                   ros_env: dict[str, str]) -> None:
    script = tmp_path / "view_talker.py"
    script.write_text(TALKER)
    talker = subprocess.Popen([sys.executable, str(script)], env=ros_env, cwd=REPO, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    base = tmp_path / "session.mcap"

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: session.recording, f"recording to start ({app.problem})")
        await until(lambda: "/numbers" in session.meters and session.meters["/numbers"].count >= 50,
                    "50 messages counted")
        await asyncio.sleep(0.6)
        rate, bandwidth = session.meters["/numbers"].rates()
        assert 30 < rate < 200 and bandwidth == pytest.approx(rate * 4)
        await pilot.press("n")
        await until(lambda: len(session.files) == 2 and session.current is not None
                    and session.current.recorder.current_file[0] == session.files[-1], "the split")
        assert session.files == [str(tmp_path / "session_0.mcap"), str(tmp_path / "session_1.mcap")]
        first_file_count = session.meters["/numbers"].count - session.meters["/numbers"].file_count
        await until(lambda: session.meters["/numbers"].file_count >= 50, "50 messages in the second file")
        await pilot.press("r")
        await until(lambda: not session.recording, "recording stopped")
        app.refresh_view()
        text = str(app.status.render())
        assert "■ STOPPED" in text and "session_1.mcap" in text and "2 files" in text
        assert first_file_count > 0
        await pilot.press("r")
        await until(lambda: session.recording, "recording again")
        assert session.file == str(tmp_path / "session_2.mcap")
        await until(lambda: session.meters["/numbers"].file_count >= 10, "messages in the third file")

    try:
        run(BagRecordApp(RecordOptions(topics=["/numbers"], output_name=str(base))), scenario)
    finally:
        stop_process(talker)
    first, second, third = (file_values(tmp_path / f"session_{i}.mcap") for i in range(3))
    assert first and second and third
    assert first + second == list(range(first[0], second[-1] + 1)), "the split lost or doubled messages"
    assert third[0] > second[-1]


def test_record_all_topics_finds_the_published_ones(tmp_path: Path, rostui_core: Any, ros_env: dict[str, str],
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    script = tmp_path / "view_talker.py"
    script.write_text(TALKER)
    talker = subprocess.Popen([sys.executable, str(script)], env=ros_env, cwd=REPO, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: "/numbers" in session.subscribed, "-a to find /numbers")
        await until(lambda: session.meters.get("/numbers") is not None and session.meters["/numbers"].count > 5,
                    "messages of /numbers")
        app.refresh_view()
        assert "recording all topics into " in str(app.header.render())
        console = Console(width=100, record=True, file=io.StringIO())
        console.print(topics_table(session))
        rows = [line for line in console.export_text().splitlines() if line.startswith("/numbers")]
        assert len(rows) == 1 and " Hz" in rows[0]

    try:
        run(BagRecordApp(RecordOptions(all_topics=True, output_prefix="all")), scenario)
    finally:
        stop_process(talker)
    files = sorted(tmp_path.glob("all_*_0.bag"))  # rosbag's format unless asked for MCAP
    assert len(files) == 1 and file_values(files[0])
