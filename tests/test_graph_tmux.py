"""`rostui graph` end to end in a real terminal: a tmux pane runs the real command against live nodes.

The book's turtlesim system runs on a `rostui core` master; the test types
`rostui graph --book` into a shell in a detached 100x30 tmux pane, reads the
drawing off the screen, switches views, searches and selects with keys sent
by `tmux send-keys`, watches a new node appear, and quits with q back to the
shell prompt with exit status 0.
"""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import wait_until
from graph_helpers import book_system, stop_programs
from live_helpers import Program
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "GRAPH_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 100x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("graph", 100, 30) as pane:
        yield pane


def test_graph_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui graph --book`: Figure 2.4 on screen; 1 for nodes only; / and Enter for details; q quits."""
    programs = book_system(ros_env, tmp_path)
    try:
        values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
        values["TERM"] = "xterm-256color"
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env -u COLUMNS -u LINES {assignments} {shlex.quote(sys.executable)} -m rostui graph --book --period 0.5; "
                  f"echo {EXIT_MARK}$?")
        wait_until(lambda: "/turtle1/color_sensor" in pane.screen(), "the book's graph on screen")
        screen = pane.screen()
        assert "Nodes/Topics (all) · hide debug" in screen and "● master" in screen
        row = next(line for line in screen.splitlines() if "/teleop_turtle" in line)
        assert "│ /teleop_turtle │──▶│ /turtle1/command_velocity │" in row
        pane.keys("1")
        wait_until(lambda: "/turtle1/pose" not in pane.screen(), "the nodes-only view")
        assert "│ /teleop_turtle │─── /turtle1/command_velocity ──▶│ /turtlesim │" in pane.screen()
        pane.keys("/")
        wait_until(lambda: "search:" in pane.screen(), "the search prompt")  # letters typed before it are keys
        pane.keys("-l", "turtlesim")
        pane.keys("Enter")
        wait_until(lambda: "Pid:" in pane.screen(), "turtlesim's node info with its pid")
        assert "Node /turtlesim" in pane.screen()
        sub = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
        try:
            pane.keys("Escape")
            wait_until(lambda: "/subscribe_to_pose" in pane.screen(), "a new node on screen")
            assert "3 nodes" in pane.screen()
        finally:
            sub.stop()
        pane.keys("q")
        wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
        screen = pane.screen()
        assert "/turtle1/command_velocity" not in screen, "the app's screen was left behind"
        assert screen.rstrip().endswith("$")
    finally:
        stop_programs(programs)
