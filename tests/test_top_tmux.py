"""`rostui top` end to end in a real terminal (tmux, 80x24), against a rospy and a roscpp node.

A shell in a detached tmux pane starts `rostui top --sort name`; the test waits for both nodes with their pids, presses
s (the order becomes CPU), then q, which returns to the shell with status 0.
"""

from __future__ import annotations

import shlex
import sys
from typing import Any, Iterator

import pytest

from interop_helpers import roscpp_peer_bin, spawn  # noqa: F401  (fixtures)
from tmux_helpers import Pane, shell_pane
from top_helpers import start_nodes

EXIT_MARK = "TOP_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("top", 80, 24) as pane:
        yield pane


def test_top_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], spawn: Any, roscpp_peer_bin: Any) -> None:
    rospy_node, rospy_name, roscpp_node, roscpp_name = start_nodes(spawn, roscpp_peer_bin, ros_env)
    values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
    values["TERM"] = "xterm-256color"
    assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
    pane.type(f"env {assignments} {shlex.quote(sys.executable)} -m rostui top --sort name; echo {EXIT_MARK}$?")
    pane.wait_until(lambda: pane.shows(rospy_name, str(rospy_node.proc.pid), roscpp_name, str(roscpp_node.proc.pid),
                                       "by name"), "both nodes with their pids")
    pane.keys("s")
    pane.wait_until(lambda: pane.shows("by cpu"), "the order by CPU")
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
    assert "by cpu" not in pane.screen(), "the app's screen was left behind"
