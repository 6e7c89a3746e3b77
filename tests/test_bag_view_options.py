"""`rostui bag view --clock` and record mode's rosbag record flags (-e, -x, --size, --duration, --split).

The clock test is the real thing: the app under Textual's pilot publishes
through a real `roscore` to Debian's rospy, whose subscriber prints every
/clock it gets. Record tests run `rostui core` and talker processes; the
flag tests check that `bag record` and `bag view --record` read the same
words the same way (one function builds both commands' options).
"""

from __future__ import annotations

import asyncio
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from textual.pilot import Pilot

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.bagview.record_app import BagRecordApp, record_header
from rostui.apps.bagview.recording import RecordSession
from rostui.core.bag.files import open_reader
from rostui.core.bag.model import BagError
from rostui.tools.bag.record_options import record_options
from rostui.tools.bag.recorder import RecordOptions, TopicFilter

from bag_view_helpers import STEP_NS, T0, Int32, run_pilot, write_counts
from cli_helpers import rostui
from conftest import REPO, rostui_cmd, stop_process, until, wait_until
from interop_helpers import Spawn, rospy_peer, spawn  # noqa: F401  (spawn is a fixture)

END = T0 + 99 * STEP_NS


# -- --clock ------------------------------------------------------------------------------------------
def clocks(peer: Any) -> list[int]:
    """The /clock values (ns) the rospy peer printed so far."""
    return [int(line.split()[1]) for line in list(peer.lines) if line.startswith("clock ")]


async def clock_settles_at(peer: Any, value: int, what: str) -> int:
    """Wait until the rospy subscriber hears ``value`` several times in a row (the paused clock); returns how
    many values it had heard before them."""
    def settled() -> bool:
        got = clocks(peer)
        return len(got) >= 5 and got[-5:] == [value] * 5

    await until(settled, f"/clock to stay at {value} ({what})")
    return len(clocks(peer))


def recorded_clock(app: BagViewApp) -> list[int]:
    """From now on, every bag time the app sends on /clock, in the order it sends them."""
    bag_clock = app.bag_clock
    assert bag_clock is not None
    sent: list[int] = []
    publish = bag_clock.publish

    def recording(bag_ns: int) -> None:
        sent.append(bag_ns)
        publish(bag_ns)

    bag_clock.publish = recording  # type: ignore[method-assign]
    return sent


def test_clock_follows_pause_seek_step_and_play_to_rospy(tmp_path: Path, real_roscore: Any, rospy_available: None,
                                                          spawn: Spawn) -> None:
    """Paused, the clock repeats the cursor's bag time (as rosbag play does); a seek and a step move it;
    playing, it runs through the bag time in order and holds at the end."""
    bag = write_counts(tmp_path / "counts.bag")
    peer = spawn(rospy_peer("rospy_clock.py"), label="rospy /clock")
    peer.wait_for("subscribed")

    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await until(lambda: app.link.startswith("publishing /clock as /bag_view_"), f"the app's node ({app.link})")
        await clock_settles_at(peer, T0, "paused at the start")
        assert set(clocks(peer)) == {T0}, "a paused clock never moves"
        await pilot.press("5")
        assert app.transport is not None
        middle = app.transport.bag_ns()
        assert middle == T0 + round((END - T0) * 0.5)
        await clock_settles_at(peer, middle, "seeked to 50% while paused")
        await pilot.press("s")  # publishes /count 50 (T0 + 0.5 s) and the clock stands there
        stepped = T0 + 50 * STEP_NS
        await clock_settles_at(peer, stepped, "one step")
        sent = recorded_clock(app)
        before_play = len(clocks(peer))
        await pilot.press("space")
        await until(lambda: app.transport is not None and app.transport.at_end and app.transport.paused,
                    "the end of the bag")
        await clock_settles_at(peer, END, "held at the end")
        # The order is checked where the app sends it: once in CI, rospy printed two ticks of the paused clock
        # after the first tick of play, as when it hands a subscription over from one of its connections to
        # another (each has its own thread); our one connection writes in publish order.
        assert sent == sorted(sent), "the clock went back while playing"
        assert all(stepped <= t <= END for t in sent), (sent[0], sent[-1])
        played = clocks(peer)[before_play:]
        assert set(played) <= set(sent) | {stepped}, "rospy heard a time the app did not send"
        assert len(set(played)) > 10, "rospy did not hear the clock run while playing"

    run_pilot(BagViewApp([str(bag)], publish_clock=True, clock_hz=50.0), scenario)
    heard = clocks(peer)
    assert heard and all(T0 <= t <= END for t in heard)


def test_bag_play_paused_keeps_publishing_the_clock_to_rospy(tmp_path: Path, real_roscore: Any, rospy_available: None,
                                                            spawn: Spawn) -> None:
    """`bag play --clock --pause -s 0.5`: the one BagClock publishes the paused time over and over, as rosbag does."""
    bag = write_counts(tmp_path / "counts.mcap")
    peer = spawn(rospy_peer("rospy_clock.py"), label="rospy /clock")
    peer.wait_for("subscribed")
    spawn(rostui_cmd("bag", "play", "--clock", "--hz", "20", "--pause", "-s", "0.5", "-q", str(bag)), label="play")
    wait_until(lambda: len(clocks(peer)) >= 10, "ten /clock messages from a paused bag play")
    assert set(clocks(peer)) == {T0 + 500_000_000}


def test_without_clock_nothing_is_advertised_on_clock(counts_bag_path: Path, rostui_core: Any) -> None:
    async def scenario(pilot: Pilot, app: BagViewApp) -> None:
        await until(lambda: app.link.startswith("publishing 2 topics as"), f"the app's node ({app.link})")
        assert "/clock" not in app.node.publications and "/clock" not in app.link
        await pilot.press("space")

    run_pilot(BagViewApp([str(counts_bag_path)], publish_all=True), scenario)


@pytest.fixture
def counts_bag_path(tmp_path: Path) -> Path:
    """The counts bag (MCAP)."""
    return write_counts(tmp_path / "counts.mcap")


# -- the flags, the same in both commands ---------------------------------------------------------------
@pytest.mark.parametrize("args,message", [
    (["-O", "x.bag", "--compression", "zstd", "/x"], "a .bag file cannot use zstd compression (none, bz2 or lz4)"),
    (["-O", "x.mcap", "-j", "--compression", "bz2", "/x"], "MCAP files use lz4 or zstd compression, not bz2"),
    (["-O", "x.mcap", "--compression", "rar", "/x"], "unknown compression 'rar' (none, lz4, zstd or bz2)"),
    (["-O", "a.bag", "-o", "b", "/x"], "use -O NAME or -o PREFIX, not both"),
    (["--duration", "5x", "/x"], "invalid duration '5x' (a positive number of seconds"),
    (["--split", "/x"], "--split needs --size MB or --duration DURATION"),
    (["--size", "0", "/x"], "--size must be a positive number of MB, not 0"),
    (["-e", "/x(", "/y"], "invalid regular expression '/x(': "),
    (["-x", "[", "-a"], "invalid regular expression '[': "),
    (["-e"], "no topics given: name topics, or use -a (all), or -e with regular expressions"),
    ([], "no topics given"),
])
@pytest.mark.parametrize("command", [["record"], ["view", "--record"]])
def test_both_commands_refuse_the_same_flags_with_the_same_line(tmp_path: Path, ros_env: dict[str, str],
                                                                command: list[str], args: list[str],
                                                                message: str) -> None:
    result = rostui(["bag", *command, *args], ros_env)
    assert result.returncode == 1, result.stdout
    assert result.stderr.count("\n") == 1 and message in result.stderr, result.stderr
    assert result.stderr.startswith(f"rostui bag {' '.join(command)}: ")


@pytest.mark.parametrize("args,message", [
    (["counts.mcap", "-x", "/a", "--split"], "rostui bag view: -x, --split are recording options (add --record)"),
    (["counts.mcap", "--duration", "2"], "rostui bag view: --duration is a recording option (add --record)"),
    (["counts.mcap", "--clock", "--no-publish"], "--clock publishes; it cannot go with --no-publish"),
    (["counts.mcap", "--publish", "--no-publish"], "--publish publishes; it cannot go with --no-publish"),
    (["counts.mcap", "--topics", "/count", "--no-publish"], "--topics publishes; it cannot go with --no-publish"),
    (["counts.mcap", "--clock", "--hz", "0"], "the clock rate (--hz) must be a positive number, not 0"),
    (["--record", "/a", "--clock"], "rostui bag view --record: --clock and --hz are for viewing a bag"),
    (["-e", "/a.*", "--hz", "10"], "rostui bag view --record: --clock and --hz are for viewing a bag"),
])
def test_options_of_the_other_mode_are_one_line(tmp_path: Path, ros_env: dict[str, str], args: list[str],
                                                message: str) -> None:
    write_counts(tmp_path / "counts.mcap")
    result = rostui(["bag", "view", *[str(tmp_path / a) if a == "counts.mcap" else a for a in args]], ros_env)
    assert result.returncode == 1, result.stdout
    assert result.stderr.count("\n") == 1 and message in result.stderr, result.stderr


def test_topic_choice_is_rosbag_records() -> None:
    """-e: the topics are patterns matched against whole names; -x: whole names, from -a and -e only."""
    regex = TopicFilter(record_options(["/cam/.*", "/imu"], regex=True, exclude="/cam/raw"), str)
    assert regex.explicit == [] and regex.discovers
    assert [t for t in ("/cam/rgb", "/cam/raw", "/cam/raw/x", "/imu", "/imu2", "/x/cam/rgb") if regex.wants(t)] == \
        ["/cam/rgb", "/cam/raw/x", "/imu"]
    named = TopicFilter(record_options(["/cam/raw", "/imu"], exclude="/cam/raw"), str)
    assert named.explicit == ["/cam/raw", "/imu"] and not named.discovers
    everything = TopicFilter(record_options([], all_topics=True, exclude="/rosout.*"), str)
    assert everything.wants("/a") and not everything.wants("/rosout_agg") and everything.wants("/x/rosout")
    opts = record_options(["/a"], name="f.bag", bz2=True, split=True, duration="1m")
    assert (opts.compression, opts.duration_s, opts.split) == ("bz2", 60.0, True)
    with pytest.raises(BagError, match="invalid duration"):
        record_options(["/a"], duration="soon")


def test_record_header_names_the_choice_and_the_limits() -> None:
    def header(opts: RecordOptions) -> str:
        return record_header(RecordSession(opts)).plain

    assert header(record_options(["/cam/.*"], regex=True, exclude="/cam/raw", name="r.mcap", duration="30")) == (
        "recording topics matching /cam/.* except those matching /cam/raw into r_<n>.mcap · stops at 30 s"
        " · next file r_0.mcap")
    assert header(record_options(["/a", "/b"], name="r.bag", split=True, size_mb=2, duration="1m")) == (
        "recording /a, /b into r_<n>.bag · splits every 2 MB or 60 s · next file r_0.bag")


# -- record mode on a live graph ------------------------------------------------------------------------
TALKERS = r'''
import sys
from rostui import client as ros
ros.init_node("option_talkers", anonymous=True)
Int32 = ros.msg("std_msgs/Int32")
pubs = [ros.Publisher(t, Int32, queue_size=100) for t in sys.argv[1:]]
rate = ros.Rate(100)
n = 0
while not ros.is_shutdown():
    for pub in pubs:
        pub.publish(Int32(data=n))
    n += 1
    rate.sleep()
'''


def talkers(tmp_path: Path, env: dict[str, str], *topics: str) -> subprocess.Popen:
    """A process publishing 0, 1, 2, ... on each of ``topics`` at 100 Hz (std_msgs/Int32)."""
    script = tmp_path / "option_talkers.py"
    script.write_text(TALKERS)
    return subprocess.Popen([sys.executable, str(script), *topics], env=env, cwd=REPO, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)


def topic_values(path: Path) -> dict[str, list[int]]:
    """The Int32 values of each topic in a recorded file (which must be closed: it has a summary)."""
    reader = open_reader(str(path))
    try:
        assert reader.summary().closed, f"{path} was not closed"
        values: dict[str, list[int]] = {}
        for conn, _t, data in reader.messages():
            values.setdefault(conn.topic, []).append(Int32().deserialize(data).data)
        return values
    finally:
        reader.close()


def status_text(app: BagRecordApp) -> str:
    """The status line, redrawn now."""
    app.refresh_view()
    return str(app.status.render())


def test_regex_picks_up_topics_that_appear_later_and_exclude_leaves_some_out(tmp_path: Path, rostui_core: Any,
                                                                             ros_env: dict[str, str]) -> None:
    procs: list[subprocess.Popen] = []

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: session.recording, f"recording to start ({app.problem})")
        assert session.subscribed == set()
        procs.append(talkers(tmp_path, ros_env, "/num/a", "/num/skip", "/other"))  # after the start
        await until(lambda: "/num/a" in session.subscribed, "-e to find /num/a")
        await until(lambda: session.meters.get("/num/a") is not None and session.meters["/num/a"].count >= 20,
                    "messages of /num/a")
        await asyncio.sleep(1.5)  # more polls of the master: the others stay out
        assert session.subscribed == {"/num/a"}
        assert "recording topics matching /num/.* except those matching /num/skip" in str(app.header.render())

    opts = record_options(["/num/.*"], regex=True, exclude="/num/skip", name=str(tmp_path / "re.mcap"))
    try:
        run_pilot(BagRecordApp(opts), scenario)
    finally:
        for proc in procs:
            stop_process(proc)
    values = topic_values(tmp_path / "re_0.mcap")
    assert list(values) == ["/num/a"] and len(values["/num/a"]) >= 20


def test_duration_stops_the_recording_and_the_app_says_so(tmp_path: Path, rostui_core: Any,
                                                          ros_env: dict[str, str]) -> None:
    proc = talkers(tmp_path, ros_env, "/numbers")

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: session.recording, f"recording to start ({app.problem})")
        await until(lambda: not session.recording, "--duration 1 to stop the recording")
        text = status_text(app)
        assert "■ STOPPED" in text and "│ reached --duration 1 s" in text, text
        assert session.errors == [] and session.messages > 0
        recorded = session.messages
        await asyncio.sleep(0.5)
        assert session.messages == recorded, "messages were still counted after the limit"
        await pilot.press("r")  # again, into the next file, with the limit again
        await until(lambda: session.recording, "recording again")
        assert "reached" not in status_text(app)
        await until(lambda: not session.recording, "the second recording to stop at its limit")
        assert "reached --duration 1 s" in status_text(app)

    try:
        run_pilot(BagRecordApp(record_options(["/numbers"], name=str(tmp_path / "d.bag"), duration="1")), scenario)
    finally:
        stop_process(proc)
    first, second = topic_values(tmp_path / "d_0.bag")["/numbers"], topic_values(tmp_path / "d_1.bag")["/numbers"]
    assert first and second and second[0] > first[-1]


def test_size_stops_the_recording_at_that_size(tmp_path: Path, rostui_core: Any, ros_env: dict[str, str]) -> None:
    proc = talkers(tmp_path, ros_env, "/numbers")

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: session.recording, f"recording to start ({app.problem})")
        await until(lambda: not session.recording, "--size to stop the recording")
        assert "│ reached --size 0.004 MB" in status_text(app)

    try:
        run_pilot(BagRecordApp(record_options(["/numbers"], name=str(tmp_path / "s.mcap"), size_mb=0.004)),
                  scenario)
    finally:
        stop_process(proc)
    path = tmp_path / "s_0.mcap"
    assert topic_values(path)["/numbers"]
    assert 4000 <= path.stat().st_size < 4000 + 8192  # the last message, the index and the summary after it


@pytest.mark.parametrize("limit,shown", [({"duration": "1"}, "splits every 1 s"),
                                         ({"size_mb": 0.003}, "splits every 0.003 MB")])
def test_split_at_a_limit_goes_on_in_the_next_file_losing_nothing(tmp_path: Path, rostui_core: Any,
                                                                  ros_env: dict[str, str], limit: dict[str, Any],
                                                                  shown: str) -> None:
    """Files made before the first message arrived (an interval with nothing in it is a file, as rosbag makes it;
    a loaded machine can take longer than the first second to connect) are left out; from the file that got the
    first message on, every file holds messages, and together they hold every message once."""
    proc = talkers(tmp_path, ros_env, "/numbers")
    first: list[int] = []

    async def scenario(pilot: Pilot, app: BagRecordApp) -> None:
        session = app.session
        await until(lambda: session.recording, f"recording to start ({app.problem})")
        await until(lambda: session.messages > 0, "the first message recorded")
        first.append(len(session.files) - 1)
        await until(lambda: len(session.files) >= first[0] + 3 and session.recording, "two splits at the limit")
        assert shown in str(app.header.render())
        assert "reached" not in status_text(app) and session.errors == [], (status_text(app), session.errors)

    try:
        run_pilot(BagRecordApp(record_options(["/numbers"], name=str(tmp_path / "p.mcap"), split=True, **limit)),
                  scenario)
    finally:
        stop_process(proc)
    files = sorted(tmp_path.glob("p_*.mcap"), key=lambda p: int(p.stem.split("_")[1]))
    pieces = [topic_values(p).get("/numbers", []) for p in files]
    ends = [(piece[0], piece[-1]) if piece else () for piece in pieces]
    start = next((i for i, piece in enumerate(pieces) if piece), len(pieces))
    assert start <= first[0], f"the file said to get the first message has none: {ends}"
    assert "duration" in limit or start == 0, f"a size split before any message: {ends}"
    files, pieces = files[start:], pieces[start:]
    assert len(pieces) >= 3 and all(pieces[:2]), ends
    joined = [v for piece in pieces for v in piece]
    assert joined == list(range(joined[0], joined[-1] + 1)), f"the splits lost or doubled messages: {ends}"
    if "duration" in limit:
        assert 50 <= len(pieces[1]) <= 250, "the middle file does not hold about a second"
    else:
        assert files[1].stat().st_size >= 3000, "the middle file was split before it reached --size"
