"""`rostui view /scan /odom` end to end in a real terminal (tmux, 100x30).

rostui's client publishes a wall scan and odometry in frame "map" (tests/peers/topdown_talker.py)
on a rostui core.  Both topics must share ONE view (one legend naming both), the wall must be
braille dots in the column where 2.05 m lies, the scale bar must say 1 m and the frame map;
arrows pan (the centre moves), and q returns to the shell with status 0.
"""

from __future__ import annotations

import re
import sys
from typing import Any, Iterator

import pytest

from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from tmux_helpers import Pane, rostui_line, shell_pane

EXIT_MARK = "VIEW_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 100x30 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("topdown", 100, 30) as pane:
        yield pane


def command(env: dict[str, str], *args: str) -> str:
    """The shell line that runs `rostui ARGS` with the test's ROS environment, then prints its exit status."""
    return rostui_line(env, EXIT_MARK, *args)


def wall_column(screen: str) -> set[int]:
    """Columns holding braille with dots in the rows of the canvas (grid dots are single: ⠂ patterns)."""
    cols: set[int] = set()
    for line in screen.splitlines()[2:-2]:
        for i, ch in enumerate(line):
            if ch in "⡇⣿⠇⡆⢸⠸⢰⣀⠿⡿⢿⣇⣸":
                cols.add(i)
    return cols


def test_view_scan_and_odom_in_tmux(pane: Pane, rostui_core: Any, ros_env: dict[str, str], spawn: Spawn) -> None:
    talker = spawn([sys.executable, str(PEERS / "topdown_talker.py"), "rostui"], label="topdown talker")
    talker.wait_for("ready")
    pane.type(command(ros_env, "view", "/scan", "/odom"))
    pane.wait_until(lambda: re.search(r"■ /scan\s+■ /odom", pane.screen()) is not None, "one legend for both topics")
    pane.wait_until(lambda: pane.shows("1 m", "frame map", "centre 0.00, 0.00"), "the scale bar and frame")
    screen = pane.screen()
    assert "no transform" not in screen and "waiting" not in screen.split("■ /scan")[1], screen
    # The panel's border takes one column each side: 98 columns show 10 m, the centre is between
    # columns 49 and 50 of the panel; 2.05 m is 2.05 / (10 / 196) = 40.2 dots = 20 cells right of it.
    pane.wait_until(lambda: any(c in wall_column(pane.screen()) for c in (69, 70, 71)), "the wall 2.05 m ahead")
    pane.keys("Right")
    pane.wait_until(lambda: pane.shows("centre 1.22, 0.00"), "the view panned an eighth to the right")
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "exit status 0 after q")
