"""`rostui graph` end to end in a real terminal: a tmux pane runs the real command against live nodes.

The book's turtlesim system runs on a `rostui core` master; the test types
`rostui graph --book` into a shell in a detached 100x30 tmux pane, reads the
drawing off the screen, switches views, searches and selects with keys sent
by `tmux send-keys`, watches a new node appear, and quits with q back to the
shell prompt with exit status 0.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any, Callable, Iterator

import pytest

from conftest import need_peer
from graph_helpers import book_system, stop_programs
from live_helpers import Program

DEADLINE = 30.0
EXIT_MARK = "GRAPH_EXIT="


def wait_until(predicate: Callable[[], bool], what: str, timeout: float = DEADLINE) -> None:
    """Poll ``predicate`` until it holds; fail with ``what`` when it never does."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.1)


class Pane:
    """One tmux session with a plain shell on a private tmux server."""

    def __init__(self, socket: str) -> None:
        self.socket = socket

    def tmux(self, *args: str) -> str:
        """Run a tmux command against this server; return its stdout."""
        result = subprocess.run(["tmux", "-u", "-L", self.socket, *args], capture_output=True, text=True,
                                timeout=DEADLINE)
        assert result.returncode == 0, f"tmux {' '.join(args)}: {result.stderr}"
        return result.stdout

    def screen(self) -> str:
        """The visible screen text."""
        return self.tmux("capture-pane", "-p", "-t", "graph")

    def type(self, line: str) -> None:
        """Type a command line and Enter."""
        self.tmux("send-keys", "-t", "graph", "-l", line)
        self.tmux("send-keys", "-t", "graph", "Enter")

    def keys(self, *keys: str) -> None:
        """Send key names (``Tab``, ``Enter``, ``q``)."""
        self.tmux("send-keys", "-t", "graph", *keys)


@pytest.fixture
def pane(tmp_path: Path) -> Iterator[Pane]:
    """A detached 100x30 tmux session running /bin/sh with a plain prompt."""
    need_peer(shutil.which("tmux") is not None, "tmux")
    pane = Pane(f"rostui-graph-{os.getpid()}-{tmp_path.name}")
    subprocess.run(["tmux", "-u", "-L", pane.socket, "-f", "/dev/null", "new-session", "-d", "-s", "graph",
                    "-x", "100", "-y", "30", "env PS1='$ ' /bin/sh"], check=True, timeout=DEADLINE)
    try:
        pane.tmux("set-option", "-t", "graph", "status", "off")
        yield pane
    finally:
        subprocess.run(["tmux", "-L", pane.socket, "kill-server"], capture_output=True, timeout=DEADLINE)


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
        assert "│ /teleop_turtle │──▶│ /turtlesim │" in pane.screen()
        pane.keys("/")
        pane.tmux("send-keys", "-t", "graph", "-l", "turtlesim")
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
