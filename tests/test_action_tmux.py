"""`rostui action` end to end in a real terminal (tmux, 80x24), against the Fibonacci tutorial's server under Debian's
actionlib (tests/action_helpers.py): the server and its goal template appear, Enter goes to the goal, ctrl+s sends it as
it is (order 0) and the result comes; the key line says where q goes; q on the action list returns to the shell
with 0.
"""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from action_helpers import fibonacci_server
from test_actionlib_scripts import tutorials_python  # noqa: F401  (fixture)
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "ACTION_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("action", 80, 24) as pane:
        yield pane


def test_action_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tutorials_python: Path,
                        tmp_path: Path) -> None:
    for env in fibonacci_server("real", ros_env, tutorials_python, tmp_path / "server.log"):
        values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP", "ROS_PACKAGE_PATH")}
        values["TERM"] = "xterm-256color"
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env {assignments} {shlex.quote(sys.executable)} -m rostui action; echo {EXIT_MARK}$?")
        pane.wait_until(lambda: pane.shows("/fibonacci", "order: 0", "actionlib_tutorials/Fibonacci"),
                        "the server and its goal template")
        pane.keys("Enter")
        pane.wait_until(lambda: pane.shows("editing the goal", "Tab back to the actions"), "the goal editor")
        assert "q quit" not in pane.screen()  # q types a q here
        pane.keys("C-s")  # the template as it is: order 0 (editing is the pilot test's, test_action_app.py)
        pane.wait_until(lambda: pane.shows("goal SUCCEEDED", "sequence: [0, 1]"), "the result")
        pane.keys("Tab")  # back to the action list, where q quits
        pane.wait_until(lambda: "q quit" in pane.screen(), "the key line of the action list")
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
