"""Ctrl-C ends `rostui turtlesim`, `rostui console` and `rostui graph` in a real terminal, cleanly (issue 21).

Each command runs in a shell in a detached 80x24 tmux pane against a `rostui
core` master.  The test waits for the app's key line (`? help  q quit`, so it
is visible at 80 columns in a real terminal too), sends Ctrl-C with `tmux
send-keys`, and checks that the shell reports exit status 0 with its prompt
back, that no process is left under the shell, and that the master no longer
lists any node the app registered.
"""

from __future__ import annotations

import shlex
import sys
from typing import Any, Iterator

import psutil
import pytest

from conftest import wait_until
from tmux_helpers import Pane, shell_pane

from rostui.core.xmlrpc import call_sync, ros_result

EXIT_MARK = "CTRL_C_EXIT="

#: The command after `rostui`, and a node it registers (None: it registers none).
COMMANDS = {
    "turtlesim": (["turtlesim"], "/turtlesim"),
    "console": (["console"], None),
    "graph": (["graph", "--period", "0.5"], None),
}


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("ctrlc", 80, 24) as pane:
        yield pane


def master_nodes(env: dict[str, str]) -> set[str]:
    """Every node the master lists."""
    state = ros_result(call_sync(env["ROS_MASTER_URI"], "getSystemState", "/ctrl_c_test", timeout=5.0))
    return {node for kind in state for _name, nodes in kind for node in nodes}


def shell_children(pane: Pane) -> list[psutil.Process]:
    """Every process running under the pane's shell."""
    pid = int(pane.tmux("display-message", "-p", "-t", pane.session, "#{pane_pid}").strip())
    return psutil.Process(pid).children(recursive=True)


@pytest.mark.parametrize("name", list(COMMANDS))
def test_ctrl_c_ends_the_app_cleanly(pane: Pane, rostui_core: Any, ros_env: dict[str, str], name: str) -> None:
    """Ctrl-C: exit status 0, the prompt back, nothing left running, the app's nodes gone from the master."""
    args, node = COMMANDS[name]
    before = master_nodes(ros_env)
    values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    command = " ".join(shlex.quote(word) for word in [sys.executable, "-m", "rostui", *args])
    pane.type(f"env -u COLUMNS -u LINES {assignments} {command}; echo {EXIT_MARK}$?")
    pane.wait_until(lambda: "? help  q quit" in pane.screen(), f"{name}'s key line with ? help and q quit")
    if node is not None:
        wait_until(lambda: node in master_nodes(ros_env), f"{node} registered")
    elif name != "graph":  # an anonymous node: its name is not known, only that it is new
        wait_until(lambda: master_nodes(ros_env) - before, f"{name}'s node registered")
    during = master_nodes(ros_env)
    assert shell_children(pane), f"{name} is not running under the shell"
    pane.keys("C-c")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after Ctrl-C")
    screen = pane.screen()
    assert "Do you want to quit" not in screen
    assert "? help  q quit" not in screen, "the app's screen was left behind"
    assert screen.rstrip().endswith("$"), "no shell prompt after Ctrl-C"
    wait_until(lambda: not shell_children(pane), "no process left under the shell")
    if name != "graph":
        assert during - before, f"{name} registered no node, so the master check checks nothing"
    left = master_nodes(ros_env) - before
    assert not left, f"still registered after Ctrl-C: {sorted(left)}"
