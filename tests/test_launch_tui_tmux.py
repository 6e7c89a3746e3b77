"""`rostui launch --tui` end to end in a real terminal (tmux), started through the real command line.

A shell runs in a detached 120x30 tmux pane; the test types `rostui launch
--tui FILE` there with the test's ROS environment (no master runs: the launch
starts its own), reads the screen with `tmux capture-pane`, kills a respawn
node from outside, restarts one with r, and leaves with q or Ctrl-C.  After
the shell is back, no process of the launch may be left.
"""

from __future__ import annotations

import os
import re
import shlex
import signal
import subprocess
import sys
from pathlib import Path
from typing import Iterator

import psutil
import pytest

from conftest import REPO, wait_until
from launch_tui_helpers import still_alive, tui_env, write_launch  # noqa: F401  (tui_env is a fixture)
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "LAUNCH_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 120x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("launchtui", 120, 30) as pane:
        yield pane


def launch_line(env: dict[str, str], *args: str) -> str:
    """The shell line that runs `rostui launch ARGS` with the test's ROS environment, then prints its status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP", "ROS_PACKAGE_PATH")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    command = shlex.join([sys.executable, "-m", "rostui", "launch", *args])
    return f"cd {shlex.quote(str(REPO))} && env {assignments} {command}; echo {EXIT_MARK}$?"


def row(pane: Pane, node: str) -> tuple[str, int | None, int | None]:
    """The state, pid and restart count the screen shows for ``node`` (pid None when the row shows none)."""
    for line in pane.screen().splitlines():
        words = line.split()
        if words and words[0] == node:
            match = re.search(rf"{re.escape(node)}\s+(.+?)\s+(\d+|-)\s+([\d.]+|-)\s+([\d.]+ MB|-)\s+(\d+)", line)
            if match:
                pid = int(match.group(2)) if match.group(2) != "-" else None
                return match.group(1), pid, int(match.group(5))
    return "", None, None


def launcher_tree(launch_file: Path) -> set[int]:
    """The pids of the `rostui launch --tui` process running ``launch_file`` and of all its descendants."""
    pids: set[int] = set()
    for process in psutil.process_iter(["cmdline"]):
        cmdline = process.info["cmdline"] or []
        if "--tui" in cmdline and str(launch_file) in cmdline:
            pids.add(process.pid)
            try:
                pids.update(child.pid for child in process.children(recursive=True))
            except psutil.Error:
                continue
    return pids


def test_monitor_kill_respawn_restart_and_quit(pane: Pane, tui_env: dict[str, str], tmp_path: Path) -> None:
    """A killed respawn node dies and comes back on screen; r changes a pid; q leaves nothing behind."""
    launch = write_launch(tmp_path / "live.launch", """
  <node pkg="tuitest" type="chatty" name="talker" args="5"/>
  <node pkg="tuitest" type="quiet" name="phoenix" respawn="true" respawn_delay="1"/>""")
    pane.type(launch_line(tui_env, "--tui", str(launch)))
    pane.wait_until(lambda: row(pane, "/phoenix")[0] == "running" and row(pane, "/talker")[0] == "running",
                    "both nodes running on screen")
    pane.wait_until(lambda: pane.shows("line 5 of 5", "a warning from chatty"), "the talker's output")
    assert pane.shows("live.launch", "(in this process)", "2 running", "respawn 1 s")
    _, first, restarts = row(pane, "/phoenix")
    assert first is not None and restarts == 0
    os.kill(first, signal.SIGKILL)
    pane.wait_until(lambda: pane.shows("died: exit code -9, SIGKILL") or row(pane, "/phoenix")[2] == 1,
                    "the death of /phoenix on screen")
    pane.wait_until(lambda: row(pane, "/phoenix")[0] == "running" and row(pane, "/phoenix")[2] == 1,
                    "/phoenix back with one restart")
    second = row(pane, "/phoenix")[1]
    assert second not in (None, first)
    _, talker_before, _ = row(pane, "/talker")
    pane.keys("r")  # the cursor is on the first row: /talker
    pane.wait_until(lambda: row(pane, "/talker")[1] not in (None, talker_before) and row(pane, "/talker")[2] == 1,
                    "a new pid for /talker after r")
    pids = launcher_tree(launch)
    assert len(pids) >= 3, pids
    pane.keys("q")
    pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "the shell to report exit status 0 after q")
    assert "/phoenix" not in pane.screen()
    wait_until(lambda: not still_alive(pids), "every process of the launch to be gone")


def test_ctrl_c_stops_the_launch(pane: Pane, tui_env: dict[str, str], tmp_path: Path) -> None:
    """Ctrl-C in the monitor shuts the launch down like roslaunch and returns to the shell with status 0."""
    launch = write_launch(tmp_path / "ctrlc.launch", '<node pkg="tuitest" type="stubborn" name="mule"/>')
    pane.type(launch_line(tui_env, "--tui", "--sigint-timeout", "1", str(launch)))
    pane.wait_until(lambda: row(pane, "/mule")[0] == "running", "/mule running on screen")
    wait_until(lambda: len(launcher_tree(launch)) >= 3, "the mule and its child")
    pids = launcher_tree(launch)
    pane.keys("C-c")
    pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "the shell to report exit status 0 after Ctrl-C")
    wait_until(lambda: not still_alive(pids), "every process of the launch to be gone")


def test_bad_file_is_one_line_and_exit_1(pane: Pane, tui_env: dict[str, str], tmp_path: Path) -> None:
    """A launch file that does not exist: one error line, exit status 1, no screen opened."""
    missing = tmp_path / "missing.launch"
    pane.type(launch_line(tui_env, "--tui", str(missing)))
    pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}1"), "exit status 1")
    screen = pane.screen()
    errors = [line for line in screen.splitlines() if line.startswith("rostui launch:")]
    assert len(errors) == 1 and "missing.launch" in errors[0], screen


def test_without_a_terminal_is_one_line_and_exit_1(tui_env: dict[str, str], tmp_path: Path) -> None:
    """--tui with no terminal: one line saying so, exit status 1, nothing started."""
    launch = write_launch(tmp_path / "one.launch", '<node pkg="tuitest" type="quiet" name="n"/>')
    result = subprocess.run([sys.executable, "-m", "rostui", "launch", "--tui", str(launch)], env=tui_env,
                            capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=60)
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        "ERROR: rostui launch --tui draws in a terminal: stdin and stdout must be a TTY "
        "(run without --tui to launch without the monitor)"]
    assert result.stdout == ""


def test_closing_the_terminal_stops_the_launch(pane: Pane, tui_env: dict[str, str], tmp_path: Path) -> None:
    """The terminal goes away (SIGHUP) while a node ignores SIGINT: every node is stopped, the launcher exits."""
    launch = write_launch(tmp_path / "hangup.launch", """
  <node pkg="tuitest" type="stubborn" name="mule"/>
  <node pkg="tuitest" type="quiet" name="calm"/>""")
    pane.type(launch_line(tui_env, "--tui", "--sigint-timeout", "1", "--sigterm-timeout", "1", str(launch)))
    pane.wait_until(lambda: row(pane, "/mule")[0] == "running" and row(pane, "/calm")[0] == "running",
                    "both nodes running on screen")
    wait_until(lambda: len(launcher_tree(launch)) >= 4, "the launcher, the mule, its child and calm")
    pids = launcher_tree(launch)
    pane.close()
    wait_until(lambda: not still_alive(pids), "the launcher and every node to be gone", timeout=60)
