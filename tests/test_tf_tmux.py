"""`rostui tf tree` and `rostui view /tf` end to end in a real terminal (tmux, 100x24).

Debian's rospy tf2_ros broadcaster sends map -> odom -> base_link at 20 Hz and tf2_ros's
static_transform_publisher latches base_link -> laser, on a real roscore. Each command must draw
that tree with the broadcasters, a rate and "static", and q must return to the shell with status 0.
"""

from __future__ import annotations

import re
from typing import Any, Iterator

import pytest

from interop_helpers import Spawn, spawn  # noqa: F401  (fixture)
from tf_chain import BROADCASTERS
from tmux_helpers import Pane, rostui_line, shell_pane

EXIT_MARK = "TF_EXIT="


@pytest.fixture
def pane() -> Iterator[Pane]:
    """A detached 100x24 tmux session running /bin/sh with a plain prompt."""
    with shell_pane("tf", 100, 24) as pane:
        yield pane


def command(env: dict[str, str], *args: str) -> str:
    """The shell line that runs `rostui ARGS` with the test's ROS environment, then prints its exit status."""
    return rostui_line(env, EXIT_MARK, *args)


def tree_drawn(screen: str) -> bool:
    lines = screen.splitlines()
    wanted = [
        r"^\W*map\s*\W?$",
        r"└─ odom\s+/rospy_tf_chain\s+\d+\.\d Hz\s+-?\d+\.\d\d s",
        r"^\W*└─ base_link\s+/rospy_tf_chain\s+\d+\.\d Hz",
        r"^\W*└─ laser\s+/static_transform_publisher\S*\s+static",
    ]
    found = [next((i for i, line in enumerate(lines) if re.search(p, line)), None) for p in wanted]
    return None not in found and found == sorted(found)  # type: ignore[type-var]


@pytest.mark.parametrize("args", [("tf", "tree"), ("view", "/tf")])
def test_tf_tree_in_tmux(args: tuple[str, ...], pane: Pane, real_roscore: Any, ros_env: dict[str, str],
                         rospy_available: None, spawn: Spawn) -> None:
    BROADCASTERS["rospy"](spawn)
    pane.type(command(ros_env, *args))
    pane.wait_until(lambda: tree_drawn(pane.screen()), "the map -> odom -> base_link -> laser tree")
    pane.wait_until(lambda: pane.shows("4 frames, 1 tree, 1 static"), "the summary line")
    indent = {name: line.index(name) for line in pane.screen().splitlines()
              for name in ("└─ odom", "└─ base_link", "└─ laser") if name in line}
    assert indent["└─ odom"] < indent["└─ base_link"] < indent["└─ laser"], pane.screen()
    pane.keys("q")
    pane.wait_until(lambda: f"{EXIT_MARK}0" in pane.screen(), "exit status 0 after q")
    assert "base_link" not in pane.screen().split(EXIT_MARK)[-1]
