"""`rostui bag view` end to end in a real terminal (tmux), started through the real command line.

A shell runs in a detached 120x30 tmux pane; the test types `rostui bag view`
there with the test's ROS environment, against `rostui core`, with a
subscriber process counting what the app publishes, and reads the screen
with `tmux capture-pane`. q must bring the shell back with exit status 0.
"""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
import xmlrpc.client
from pathlib import Path
from typing import Any, Iterator

import pytest

from rostui.core.bag.files import open_reader

from bag_view_helpers import Counter, write_counts
from conftest import REPO, stop_process, wait_until
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "VIEW_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 120x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("bagview", 120, 30) as pane:
        yield pane


def view_line(env: dict[str, str], *args: str, cwd: Path) -> str:
    """The shell line that runs `rostui bag view ARGS` in ``cwd`` with the test's ROS environment, then its status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    values["TZ"] = "UTC"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    command = shlex.join([sys.executable, "-m", "rostui", "bag", "view", *args])
    return f"cd {shlex.quote(str(cwd))} && env -u COLUMNS -u LINES {assignments} {command}; echo {EXIT_MARK}$?"


def test_bag_view_seeks_plays_and_quits_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str],
                                                tmp_path: Path) -> None:
    """The timeline and inspector show; playing publishes nothing until a switches every topic on (a live
    subscriber hears nothing, no node joins the master); then 5 and space publish the second half; q gives the
    shell back."""
    write_counts(tmp_path / "counts.bag")
    counter = Counter(ros_env, tmp_path, "/count", "/odd")
    try:
        pane.type(view_line(ros_env, "counts.bag", cwd=tmp_path))
        pane.wait_until(lambda: pane.shows("counts.bag · ", "150 msgs", "/count", "/odd", "PAUSED"),
                        "the header, the timeline and the paused state")
        assert pane.shows("not publishing: t publishes the selected topic, a every topic")
        pane.keys("Space")
        pane.wait_until(lambda: pane.shows("■ END", "data: 99"), "the whole bag played")
        assert counter.received() == [] and bag_view_nodes(ros_env) == [], "playing published unasked"
        pane.keys("a")
        pane.wait_until(lambda: pane.shows("publishing 2 topics as /bag_view_"), "the app's node")
        wait_until(counter.connected, "the counter to connect to the app")
        pane.keys("5")
        pane.wait_until(lambda: pane.shows(" 50%", "data: 49"), "the cursor at 50% and /count 49 inspected")
        pane.keys("Space")
        pane.wait_until(lambda: pane.shows("■ END", "published 75", "data: 99"), "the end of the bag")
        wait_until(lambda: len(counter.received()) >= 75, "the second half at the counter")
        assert counter.values("/count") == list(range(50, 100))
        assert counter.values("/odd") == list(range(51, 100, 2))
        pane.keys("q")
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "exit status 0 after q")
        screen = pane.screen()
        assert "150 msgs" not in screen, "the app's screen was left behind"
        assert screen.rstrip().endswith("$")
    finally:
        counter.close()


def test_bag_view_of_a_garbage_file_is_one_line_in_tmux(pane: Pane, ros_env: dict[str, str],
                                                        tmp_path: Path) -> None:
    """Random bytes: one error line, exit status 1, no screen opened."""
    (tmp_path / "junk.mcap").write_bytes(bytes(range(256)) * 8)
    pane.type(view_line(ros_env, "junk.mcap", cwd=tmp_path))
    pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}1"), "exit status 1")
    assert ("\nrostui bag view: junk.mcap is neither an MCAP file nor a rosbag file (unknown first bytes)\n"
            f"{EXIT_MARK}1\n") in pane.screen()


def app_pids(marker: str) -> list[int]:
    """Processes whose command line holds ``marker`` (a path only this test uses)."""
    out = subprocess.run(["pgrep", "-f", marker], capture_output=True, text=True).stdout
    return [int(p) for p in out.split() if int(p) != os.getpid()]


def bag_view_nodes(env: dict[str, str]) -> list[str]:
    """Nodes named /bag_view_... that the master knows as publishers."""
    code, _, state = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/test")
    assert code == 1
    return sorted({n for _topic, nodes in state[0] for n in nodes if n.startswith("/bag_view_")})


def test_closing_the_terminal_while_playing_ends_the_app_and_its_node(pane: Pane, rostui_core: Any,
                                                                     ros_env: dict[str, str],
                                                                     tmp_path: Path) -> None:
    """The terminal goes away (SIGHUP) mid-playback: the node unregisters and the process ends."""
    bag = write_counts(tmp_path / "hangup.mcap", count=3000)  # 30 s
    pane.type(view_line(ros_env, "--play", "--publish", str(bag), cwd=tmp_path))
    pane.wait_until(lambda: pane.shows("▶ PLAYING", "publishing 2 topics as /bag_view_"), "playing and publishing")
    wait_until(lambda: len(bag_view_nodes(ros_env)) == 1, "the app's node on the master")
    pids = app_pids(str(bag))
    assert pids
    pane.close()
    wait_until(lambda: not app_pids(str(bag)), "the app to end after its terminal went away", timeout=30)
    assert bag_view_nodes(ros_env) == []


TALKER = r'''
from rostui import client as ros
ros.init_node("tmux_numbers")
Int32 = ros.msg("std_msgs/Int32")
pub = ros.Publisher("/numbers", Int32, queue_size=100)
rate = ros.Rate(50)
n = 0
while not ros.is_shutdown():
    pub.publish(Int32(data=n))
    n += 1
    rate.sleep()
'''


def start_numbers_talker(tmp_path: Path, ros_env: dict[str, str]) -> subprocess.Popen:
    """Start TALKER (std_msgs/Int32 on /numbers) as its own process."""
    script = tmp_path / "tmux_numbers.py"
    script.write_text(TALKER)
    return subprocess.Popen([sys.executable, str(script)], env=ros_env, cwd=REPO, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)


def test_bag_view_record_splits_and_quits_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str],
                                                  tmp_path: Path) -> None:
    """--record: live counts; n splits into rec_1.mcap; q finishes and reports both files."""
    talker = start_numbers_talker(tmp_path, ros_env)
    try:
        pane.type(view_line(ros_env, "--record", "/numbers", "-O", "rec.mcap", cwd=tmp_path))
        pane.wait_until(lambda: pane.shows("● REC", "'rec_0.mcap'", "/numbers", " Hz"), "recording /numbers")
        pane.keys("n")
        pane.wait_until(lambda: pane.shows("'rec_1.mcap'", "2 files"), "the split into rec_1.mcap")
        pane.keys("q")
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "exit status 0 after q")
        assert "to rec_0.mcap, rec_1.mcap" in pane.screen()
        assert (tmp_path / "rec_0.mcap").stat().st_size > 0 and (tmp_path / "rec_1.mcap").stat().st_size > 0
    finally:
        stop_process(talker)


def test_bag_view_record_regex_stops_at_duration_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str],
                                                         tmp_path: Path) -> None:
    """-e '/num.*' --duration 2: /numbers is found, the recording stops by itself and says so; q reports the file."""
    talker = start_numbers_talker(tmp_path, ros_env)
    try:
        pane.type(view_line(ros_env, "-e", "/num.*", "--duration", "2", "-O", "rec.bag", cwd=tmp_path))
        pane.wait_until(lambda: pane.shows("recording topics matching /num.* into rec_<n>.bag · stops at 2 s"),
                        "the header naming the pattern and the limit")
        pane.wait_until(lambda: pane.shows("● REC", "'rec_0.bag'", "/numbers", " Hz"), "recording /numbers")
        pane.wait_until(lambda: pane.shows("■ STOPPED", "│ reached --duration 2 s"), "the stop at 2 s")
        pane.keys("q")
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "exit status 0 after q")
        assert " messages to rec_0.bag\n" in pane.screen()
        reader = open_reader(str(tmp_path / "rec_0.bag"))
        try:
            assert reader.summary().closed and [c.topic for c in reader.summary().connections] == ["/numbers"]
        finally:
            reader.close()
    finally:
        stop_process(talker)
