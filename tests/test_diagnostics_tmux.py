"""`rostui diagnostics` end to end in a real terminal (tmux, 80x24), against Debian's diagnostics.

A rospy diagnostic_updater node and Debian's aggregator run under `rostui core` (tests/diagnostics_helpers.py). A
shell in a detached tmux pane starts `rostui diagnostics -l warn`; the test waits for the aggregator's groups at
WARN and worse, presses l (ERROR and worse: the motor goes), and q returns to the shell with status 0.
"""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from diagnostics_helpers import clean_env, need_debian_diagnostics, start_aggregator, start_publisher
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "DIAGNOSTICS_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("diagnostics", 80, 24) as pane:
        yield pane


def test_diagnostics_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """The aggregator's groups at WARN and worse, l raises it to ERROR, q quits with 0."""
    need_debian_diagnostics()
    env = clean_env(ros_env)
    publisher = start_publisher(env, tmp_path / "publisher.log")
    aggregator = start_aggregator(env, tmp_path / "aggregator.log")
    try:
        values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
        values["TERM"] = "xterm-256color"
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env {assignments} {shlex.quote(sys.executable)} -m rostui diagnostics -l warn; "
                  f"echo {EXIT_MARK}$?")
        pane.wait_until(lambda: pane.shows("/diagnostics_agg tree", "Power", "robot_driver: battery charge",
                                           "robot_driver: motor temperature", "showing 4 of 6 rows: WARN and worse"),
                        "the aggregator's groups at WARN and worse")
        assert "laser connection" not in pane.screen()
        pane.keys("l")
        pane.wait_until(lambda: pane.shows("showing 2 of 6 rows: ERROR and worse") and "motor temperature" not in pane.screen(),
                        "only the errors")
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
        assert "/diagnostics_agg tree" not in pane.screen(), "the app's screen was left behind"
    finally:
        aggregator.interrupt()
        publisher.interrupt()
