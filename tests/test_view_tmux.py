"""`rostui view /camera/image_raw` end to end in a real terminal: a tmux pane runs the real command.

The pattern camera (rostui's client running tests/view/image_pattern_pub.py)
publishes on a `rostui core` master; the test types the command into a shell
in a detached 100x40 tmux pane.  Nothing forces the drawing: the app asks the
terminal what it draws, and tmux (no kitty graphics, no sixel in Debian's
build) gets half blocks.  The test reads the figures line and the picture's
colours off the screen (capture-pane with escapes), then quits with q back
to the prompt with exit status 0, and the master no longer lists the viewer.
"""

from __future__ import annotations

import re
import shlex
import sys
import xmlrpc.client
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import stop_process
from tmux_helpers import Pane, shell_pane
from view_helpers import start_camera

EXIT_MARK = "VIEW_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 100x40 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("view", 100, 40) as pane:
        yield pane


def colours_on_screen(pane: Pane) -> set[tuple[int, int, int]]:
    """Every truecolor (foreground or background) the screen uses."""
    text = pane.tmux("capture-pane", "-p", "-e", "-t", pane.session)
    return {(int(r), int(g), int(b)) for r, g, b in re.findall(r"[34]8;2;(\d+);(\d+);(\d+)", text)}


def viewers(env: dict[str, str]) -> list[str]:
    """rostui view's nodes among the camera topic's subscribers, as the master lists them."""
    _, _, (_, subs, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/view_tmux")
    nodes = next((n for t, n in subs if t == "/camera/image_raw"), [])
    return [n for n in nodes if n.startswith("/rostui_view")]


def test_view_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    camera = start_camera(ros_env, tmp_path, "/camera/image_raw", "rgb8", rate=10)
    try:
        values = {key: ros_env[key] for key in ("ROS_MASTER_URI", "ROS_HOME", "ROS_IP")}
        values.update(TERM="xterm-256color", COLORTERM="truecolor")
        assignments = " ".join(f"{k}={shlex.quote(v)}" for k, v in values.items())
        pane.type(f"env -u COLUMNS -u LINES -u ROSTUI_VIEW_GRAPHICS {assignments} {shlex.quote(sys.executable)} "
                  f"-m rostui view /camera/image_raw; echo {EXIT_MARK}$?")
        pane.wait_until(lambda: re.search(r"64x48 rgb8  \d+\.\d fps \(\d+\.\d drawn\)  latency \d+ ms  halfblock",
                                          pane.screen()) is not None, "the figures line")
        screen = pane.screen()
        assert "● master" in screen and "/camera/image_raw" in screen and "sensor_msgs/Image" in screen
        assert screen.count("▀") > 500  # the picture, in half blocks
        assert {(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (255, 255, 0)} <= colours_on_screen(pane)
        assert len(viewers(ros_env)) == 1
        pane.keys("q")
        pane.wait_for_text(f"{EXIT_MARK}0")
        assert viewers(ros_env) == []
    finally:
        stop_process(camera)


def test_bad_topic_name_is_one_line(pane: Pane, ros_env: dict[str, str]) -> None:
    pane.type(f"{shlex.quote(sys.executable)} -m rostui view 'not a topic'; echo {EXIT_MARK}$?")
    pane.wait_for_text(f"{EXIT_MARK}1")
    errors = [line for line in pane.screen().splitlines() if line.startswith("ERROR")]
    assert len(errors) == 1 and "not a topic" in errors[0], pane.screen()
