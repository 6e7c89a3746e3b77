"""`rostui monitor` end to end in a real terminal: a tmux pane runs the real command against live publishers.

Two `rostui topic pub -r` processes publish on a `rostui core` master; the
test types `rostui monitor /log` into a shell in a detached 110x40 tmux
pane, reads the table and the expanded message tree off the screen, filters
with /, opens the publish editor with p, and quits with q back to the shell
prompt with exit status 0.  A second test plots a headless turtlesim's pose
(`rostui monitor /turtle1/pose/x:y:theta`) and reads the axes off the screen.
"""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from live_helpers import Program, start_headless_sim
from monitor_helpers import start_publishers, stop_all
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "MONITOR_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 110x40 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("monitor", 110, 40) as pane:
        yield pane


def line_of(screen: str, text: str) -> str:
    """The first screen line holding ``text``."""
    return next((line for line in screen.splitlines() if text in line), "")


def test_monitor_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui monitor /log`: live rows, the Log tree with INFO, / filter, p editor with a template, q quits."""
    pubs = start_publishers(ros_env, tmp_path, [
        ("/log", "rosgraph_msgs/Log", "{level: 2, msg: tmux hello}", 5),
        ("/cmd_vel", "geometry_msgs/Twist", "{linear: {x: 0.5}}", 10),
    ])
    try:
        values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
        values["TERM"] = "xterm-256color"
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env -u COLUMNS -u LINES {assignments} {shlex.quote(sys.executable)} -m rostui monitor /log "
                  f"--period 0.5; echo {EXIT_MARK}$?")
        pane.wait_until(lambda: "● live" in line_of(pane.screen(), "/cmd_vel") and
                        "● live" in line_of(pane.screen(), "/log "), "both topics live")
        pane.wait_until(lambda: "level: 2 (INFO)" in pane.screen() and "msg: 'tmux hello'" in pane.screen(),
                        "the expanded Log tree")
        screen = pane.screen()
        assert "geometry_msgs/Twist" in line_of(screen, "/cmd_vel") and "● master" in screen
        assert "/log [rosgraph_msgs/Log]" in screen
        pane.keys("/")
        pane.keys("-l", "cmd")
        pane.keys("Enter")
        pane.wait_until(lambda: "1 shown" in pane.screen(), "the filter keeping one row")
        pane.keys("p")
        pane.wait_until(lambda: "template for geometry_msgs/Twist" in pane.screen(), "the publish editor")
        screen = pane.screen()
        assert "linear:" in screen and "  x: 0.0" in screen, screen
        assert "/cmd_vel" in line_of(screen, "│ topic "), screen
        pane.keys("Escape")
        pane.wait_until(lambda: "template for" not in pane.screen(), "the editor closed")
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
        screen = pane.screen()
        assert "/cmd_vel" not in screen, "the app's screen was left behind"
        assert screen.rstrip().endswith("$")
    finally:
        stop_all(pubs)


def test_monitor_plot_in_tmux(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui monitor /turtle1/pose/x:y:theta` at 100x32 with a headless turtlesim driven by pubvel:
    the plot with axes, ticks and a legend; space pauses, + widens the window, v hides it, q quits."""
    programs = [start_headless_sim(ros_env, tmp_path),
                Program(ros_env, tmp_path, "agitr", "pubvel", label="pubvel")]
    try:
        with shell_pane("monitor_plot", 100, 32) as pane:
            values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
            values["TERM"] = "xterm-256color"
            assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
            pane.type(f"env -u COLUMNS -u LINES {assignments} {shlex.quote(sys.executable)} -m rostui monitor "
                      f"/turtle1/pose/x:y:theta --period 0.5; echo {EXIT_MARK}$?")
            pane.wait_until(lambda: all(f"/turtle1/pose/{f} = " in pane.screen() for f in ("x", "y", "theta")),
                            "the legend of the three fields")
            pane.wait_until(lambda: "3 fields  │  last 10 s  │  range " in pane.screen(), "the plot's heading")
            screen = pane.screen()
            axis = line_of(screen, "-10 ").split()
            assert axis == ["-10", "-8", "-6", "-4", "-2", "0"], "the time axis in whole seconds:\n" + screen
            assert "seconds before now" in screen and "▶ live" in screen
            assert sum("┤" in line for line in screen.splitlines()) >= 3, "y ticks on the left axis:\n" + screen
            pane.keys("Space")
            pane.wait_until(lambda: "paused (" in pane.screen() and "seconds before the pause" in pane.screen(),
                            "the paused plot")
            pane.wait_until(lambda: "paused (0 new" not in pane.screen(), "points counted while paused")
            pane.keys("+")
            pane.wait_until(lambda: "last 20 s" in pane.screen() and "-15" in line_of(pane.screen(), "-20"),
                            "a 20 s window")
            pane.keys("Space", "v")
            pane.wait_until(lambda: "seconds before" not in pane.screen(), "the plot hidden")
            pane.keys("q")
            pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
            screen = pane.screen()
            assert "turtlesim/Pose" not in screen and screen.rstrip().endswith("$"), "the app's screen was left behind"
    finally:
        for program in reversed(programs):
            program.stop()
