"""`rostui loggers` end to end in a real terminal (tmux, 80x24).

The book's count_and_log runs under `rostui core`.  A shell in a detached
tmux pane starts `rostui loggers`; the test waits for the node list, where
/count_and_log (the first node) is selected without any arrow key, presses d, and reads the level back through the
node's get_loggers service (ros.agitr at debug), as `rosservice call
/count_and_log/get_loggers` would.  q returns to the shell with status 0.
"""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from live_helpers import Program, Watcher, wait_for_service
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "LOGGERS_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("loggers", 80, 24) as pane:
        yield pane


def loggers_command(env: dict[str, str]) -> str:
    """The shell line that starts `rostui loggers` with the test's ROS environment."""
    values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    return f"env {assignments} {shlex.quote(sys.executable)} -m rostui loggers"


def agitr_level(watcher: Watcher) -> str:
    """ros.agitr's level as /count_and_log's get_loggers service answers it."""
    response = watcher.call("/count_and_log/get_loggers", "roscpp/GetLoggers")
    return {logger.name: logger.level for logger in response.loggers}["ros.agitr"]


def test_loggers_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """count_and_log (the first node) is selected at start, d sets ros.agitr to DEBUG (read back), q quits with 0."""
    count = Program(ros_env, tmp_path, "agitr", "count")
    watcher = None
    try:
        for service in ("get_loggers", "set_logger_level"):  # listed, so first in the list when the app opens
            wait_for_service(ros_env, f"/count_and_log/{service}")
        pane.type(f"{loggers_command(ros_env)}; echo {EXIT_MARK}$?")
        pane.wait_until(lambda: pane.shows("/count_and_log", "/rosout", "2 nodes serve"), "the node list")
        pane.wait_until(lambda: pane.shows("Loggers · /count_and_log", "ros.agitr", "2 loggers"),
                        "count_and_log's loggers")
        watcher = Watcher()
        assert agitr_level(watcher) == "info"
        pane.keys("d")
        pane.wait_until(lambda: pane.shows("ros.agitr set to"), "the level notice")
        assert agitr_level(watcher) == "debug"
        assert "DEBUG" in pane.screen()
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
        screen = pane.screen()
        assert "Loggers ·" not in screen, "the app's screen was left behind"
        assert screen.rstrip().endswith("$"), "no shell prompt after the app quit"
    finally:
        if watcher is not None:
            watcher.close()
        count.stop()
