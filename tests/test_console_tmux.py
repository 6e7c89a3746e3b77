"""`rostui console` end to end in a real terminal (tmux), started through the real command line.

A shell runs in a detached 120x30 tmux pane; the test types `rostui console`
there with the test's ROS environment, against `rostui core` with a node
logging once every 0.2 s, and reads the screen with `tmux capture-pane`.
Keys go in with `tmux send-keys`; q must bring the shell back with exit 0.
"""

from __future__ import annotations

import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import REPO, stop_process, wait_until
from console_helpers import write_sample_log
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "CONSOLE_EXIT="

TALKER = r'''
from rostui import client as ros
ros.init_node("tmux_talker")
rate = ros.Rate(5)
n = 0
while not ros.is_shutdown():
    ros.loginfo("tmux hello %d", n)
    if n % 5 == 0:
        ros.logwarn("tmux warning %d", n)
    n += 1
    rate.sleep()
'''


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 120x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("console", 120, 30) as pane:
        yield pane


def console_line(env: dict[str, str], *args: str, cwd: Path = REPO) -> str:
    """The shell line that runs `rostui console ARGS` in ``cwd`` with the test's ROS environment, then its status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    command = shlex.join([sys.executable, "-m", "rostui", "console", *args])
    return f"cd {shlex.quote(str(cwd))} && env {assignments} {command}; echo {EXIT_MARK}$?"


def quit_and_check(pane: Pane, marker: str) -> None:
    """q leaves the app: exit status 0, the screen is the shell's again."""
    pane.keys("q")
    wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "the shell to report exit status 0 after q")
    screen = pane.screen()
    assert marker not in screen, "the app's screen was left behind"
    assert screen.rstrip().endswith("$")


def test_live_console_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """A node logs; the console shows it live; / filters, p pauses, 3 hides WARN; q quits cleanly."""
    script = tmp_path / "tmux_talker.py"
    script.write_text(TALKER)
    talker = subprocess.Popen([sys.executable, str(script)], env=ros_env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    try:
        pane.type(console_line(ros_env, "--min-level", "info"))
        wait_until(lambda: pane.shows("/tmux_talker"), "the talker's messages on screen")
        wait_until(lambda: pane.shows("tmux warning"), "a warning on screen")
        screen = pane.screen()
        assert "FOLLOW" in screen and f"master {ros_env['ROS_MASTER_URI']}" in screen
        assert "1 DEBUG" in screen and "3 WARN" in screen
        pane.keys("/")
        pane.keys("-l", "warning")
        pane.keys("Enter")
        wait_until(lambda: "text warning" in pane.screen() and "tmux hello" not in pane.screen(),
                   "only warnings after the search")
        pane.keys("Escape")
        wait_until(lambda: pane.shows("tmux hello"), "every message again after Escape")
        pane.keys("p")
        wait_until(lambda: pane.shows("PAUSED"), "the paused mode")
        wait_until(lambda: " new" in pane.screen() and " 0 new" not in pane.screen(), "new messages counted")
        pane.keys("p")
        wait_until(lambda: "PAUSED" not in pane.screen(), "resumed")
        pane.keys("3")
        wait_until(lambda: "tmux warning" not in pane.screen().split("Message", 1)[-1],
                   "warnings hidden by 3")
        quit_and_check(pane, "/tmux_talker")
    finally:
        stop_process(talker)


def test_log_file_in_tmux(pane: Pane, ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui console rosout.log` shows the file's messages and its name; Enter opens the details."""
    write_sample_log(tmp_path / "rosout.log")
    pane.type(console_line(ros_env, "rosout.log", cwd=tmp_path))
    wait_until(lambda: pane.shows("20 is divisible by 20."), "the newest message of the file")
    assert "37 shown / 37 kept │ file rosout.log" in pane.screen()
    pane.keys("Enter")
    wait_until(lambda: pane.shows("(file:function:line)"), "the detail pane")
    quit_and_check(pane, "divisible by 20")


def test_unreadable_file_is_one_line_and_exit_1(pane: Pane, ros_env: dict[str, str], tmp_path: Path) -> None:
    """A missing file: one error line in the terminal, exit status 1, no screen opened."""
    pane.type(console_line(ros_env, "missing.log", cwd=tmp_path))
    wait_until(lambda: pane.shows(f"{EXIT_MARK}1"), "exit status 1")
    assert "\nERROR: missing.log: cannot read: No such file or directory\nCONSOLE_EXIT=1\n" in pane.screen()
