"""`rostui bag play` keys in a real terminal (tmux): space pauses and resumes, s steps one message while paused.

The issue 8 point that had only been tried by hand: stdin is a terminal, so
the player reads keys in cbreak mode. A subscriber process counts what is
published; the status line (rewritten in place) shows [PAUSED] / [RUNNING].
"""

from __future__ import annotations

import shlex
import sys
import time
from pathlib import Path
from typing import Any, Iterator

import pytest

from bag_view_helpers import Counter, write_counts
from conftest import wait_until
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "PLAY_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 120x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("bagplay", 120, 30) as pane:
        yield pane


def play_line(env: dict[str, str], *args: str, cwd: Path) -> str:
    """The shell line that runs `rostui bag play ARGS` in ``cwd`` with the test's ROS environment, then its status."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    command = shlex.join([sys.executable, "-m", "rostui", "bag", "play", *args])
    return f"cd {shlex.quote(str(cwd))} && env {assignments} {command}; echo {EXIT_MARK}$?"


def status_line(pane: Pane) -> str:
    """The last status line on the screen."""
    lines = [line for line in pane.screen().splitlines() if "Bag Time:" in line]
    return lines[-1] if lines else ""


@pytest.mark.parametrize("name", ["counts.bag", "counts.mcap"])
def test_space_pauses_and_s_steps_one_message(name: str, pane: Pane, rostui_core: Any, ros_env: dict[str, str],
                                             tmp_path: Path) -> None:
    write_counts(tmp_path / name, count=300)  # 3 s of /count and /odd
    counter = Counter(ros_env, tmp_path, "/count", "/odd")
    try:
        pane.type(play_line(ros_env, "--pause", "-d", "0.5", name, cwd=tmp_path))
        pane.wait_until(lambda: pane.shows("Hit space to toggle paused, or 's' to step."), "the key hint")
        pane.wait_until(lambda: "[PAUSED ]" in status_line(pane), "the paused status line")
        wait_until(counter.connected, "the counter to connect to the player")
        time.sleep(0.5)
        assert counter.received() == [], "published while paused"
        for n in range(1, 5):
            pane.keys("s")
            wait_until(lambda: len(counter.received()) >= n, f"step {n} at the counter")
            time.sleep(0.4)
            assert len(counter.received()) == n, f"step {n} published more than one message"
        assert counter.received() == [("/count", 0), ("/count", 1), ("/odd", 1), ("/count", 2)]
        assert "[PAUSED ]" in status_line(pane)
        pane.keys("Space")
        pane.wait_until(lambda: "[RUNNING]" in status_line(pane), "running after space")
        wait_until(lambda: len(counter.values("/count")) >= 30, "playback going on")
        pane.keys("Space")
        pane.wait_until(lambda: "[PAUSED ]" in status_line(pane), "paused again after space")
        time.sleep(0.3)
        held = len(counter.received())
        time.sleep(0.6)
        assert len(counter.received()) == held, "published while paused"
        assert held < 450, "the whole bag went out despite the pause"
        pane.keys("Space")
        pane.wait_until(lambda: pane.shows(f"{EXIT_MARK}0"), "the end of the bag and exit status 0")
        assert "Done." in pane.screen()
        wait_until(lambda: len(counter.received()) >= 450, "every message")
        assert counter.values("/count") == list(range(300))
    finally:
        counter.close()
