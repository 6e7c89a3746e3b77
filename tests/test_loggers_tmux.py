"""`rostui loggers` end to end in a real terminal (tmux, 80x24).

The book's count_and_log runs under `rostui core`.  A shell in a detached
tmux pane starts `rostui loggers`; the test waits for the node list, selects
/count_and_log with Down, presses d, and reads the level back through the
node's get_loggers service (ros.agitr at debug), as `rosservice call
/count_and_log/get_loggers` would.  q returns to the shell with status 0.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterator

import pytest

from conftest import need_peer
from live_helpers import Program, Watcher

DEADLINE = 30.0
EXIT_MARK = "LOGGERS_EXIT="


def wait_until(predicate: Callable[[], bool], what: str, screen: Callable[[], str],
               timeout: float = DEADLINE) -> None:
    """Poll ``predicate`` until it holds; fail with ``what`` and the screen when it never does."""
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}; the screen:\n{screen()}")
        time.sleep(0.1)


@dataclass
class Pane:
    """One tmux session with a plain shell, on a private tmux server."""

    socket: str
    session: str

    def tmux(self, *args: str) -> str:
        """Run a tmux command against this server; return its stdout."""
        result = subprocess.run(["tmux", "-u", "-L", self.socket, *args], capture_output=True, text=True,
                                timeout=DEADLINE)
        assert result.returncode == 0, f"tmux {' '.join(args)}: {result.stderr}"
        return result.stdout

    def screen(self) -> str:
        """The visible screen text."""
        return self.tmux("capture-pane", "-p", "-t", self.session)

    def type(self, line: str) -> None:
        """Type a command line and Enter."""
        self.tmux("send-keys", "-t", self.session, "-l", line)
        self.tmux("send-keys", "-t", self.session, "Enter")

    def keys(self, *keys: str) -> None:
        """Send key names (``Down``, ``d``, ``q``)."""
        self.tmux("send-keys", "-t", self.session, *keys)

    def shows(self, *texts: str) -> bool:
        """True when every text is on the screen."""
        screen = self.screen()
        return all(text in screen for text in texts)


@pytest.fixture
def pane(tmp_path: Path) -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    need_peer(shutil.which("tmux") is not None, "tmux")
    pane = Pane(socket=f"rostui-loggers-{os.getpid()}-{tmp_path.name}", session="loggers")
    subprocess.run(["tmux", "-u", "-L", pane.socket, "-f", "/dev/null", "new-session", "-d", "-s", pane.session,
                    "-x", "80", "-y", "24", "env PS1='$ ' /bin/sh"], check=True, timeout=DEADLINE)
    try:
        pane.tmux("set-option", "-t", pane.session, "status", "off")
        yield pane
    finally:
        subprocess.run(["tmux", "-L", pane.socket, "kill-server"], capture_output=True, timeout=DEADLINE)


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
    """Down selects count_and_log, d sets ros.agitr to DEBUG (read back from the node), q quits with 0."""
    count = Program(ros_env, tmp_path, "agitr", "count")
    watcher = None
    try:
        pane.type(f"{loggers_command(ros_env)}; echo {EXIT_MARK}$?")
        wait_until(lambda: pane.shows("/count_and_log", "/rosout", "2 nodes serve"), "the node list", pane.screen)
        pane.keys("Down")
        wait_until(lambda: pane.shows("Loggers · /count_and_log", "ros.agitr", "2 loggers"),
                   "count_and_log's loggers", pane.screen)
        watcher = Watcher()
        assert agitr_level(watcher) == "info"
        pane.keys("d")
        wait_until(lambda: pane.shows("ros.agitr set to"), "the level notice", pane.screen)
        assert agitr_level(watcher) == "debug"
        assert "DEBUG" in pane.screen()
        pane.keys("q")
        wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q",
                   pane.screen)
        screen = pane.screen()
        assert "Loggers ·" not in screen, "the app's screen was left behind"
        assert screen.rstrip().endswith("$"), "no shell prompt after the app quit"
    finally:
        if watcher is not None:
            watcher.close()
        count.stop()
