"""`rostui reconfigure` end to end in a real terminal (tmux, 80x24).

Debian's dynamic_reconfigure test server runs under `rostui core`. A shell in a detached tmux pane starts
`rostui reconfigure /dynamic_reconfigure_test_server`; the test waits for its parameters, moves to int_,
steps it up with →, and reads the value back with Debian's `dynparam get` (the server keeps ints odd: 1 asked
up to 2 is kept as 3). q returns to the shell with status 0.
"""

from __future__ import annotations

import ast
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import SYSTEM_PYTHON
from reconfigure_helpers import DEBIAN_DYNPARAM, NODE, clean_env, forget_parameters, need_debian_dynamic_reconfigure, \
    start_server
from tmux_helpers import Pane, shell_pane

EXIT_MARK = "RECONFIGURE_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 80x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("reconfigure", 80, 24) as pane:
        yield pane


def int_value(env: dict[str, str]) -> int:
    """int_ as Debian's dynparam reads it."""
    done = subprocess.run([SYSTEM_PYTHON, str(DEBIAN_DYNPARAM), "get", NODE], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return int(ast.literal_eval(done.stdout.strip())["int_"])


def test_reconfigure_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """The named server's parameters, → on int_ changes it on the server, q quits with 0."""
    need_debian_dynamic_reconfigure()
    env = clean_env(ros_env)
    server = start_server("real", env, tmp_path / "server.log")
    try:
        values = {key: env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
        values["TERM"] = "xterm-256color"
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env {assignments} {shlex.quote(sys.executable)} -m rostui reconfigure {NODE}; echo {EXIT_MARK}$?")
        pane.wait_until(lambda: pane.shows(f"Parameters · {NODE}", "int_enum_", "Small (0)"), "the parameters")
        before = int_value(env)
        pane.keys("Tab", "Down")
        pane.wait_until(lambda: pane.shows("int_ (int, -10 … 10, default 0): Int parameter"), "the cursor on int_")
        pane.keys("Right")
        pane.wait_until(lambda: pane.shows(f"int_: asked {before + 1}"), "the server's answer")
        assert int_value(env) == (before + 1) | 1
        pane.keys("q")
        pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "the shell to report exit status 0 after q")
        assert "Parameters ·" not in pane.screen(), "the app's screen was left behind"
    finally:
        server.interrupt()
        forget_parameters(env, NODE)
