"""Chapter 7, Parameters: rosparam list/get/set/dump/load, turtlesim's background colour (the world turns
yellow only after /clear), set_bg_color, pubvel_with_max's private ~max_vel, and fast_yellow.launch.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from book_helpers import (
    Desk, Terminal, cli, desk, dot_edges, lines, log_lines, ok, poll, start_core, start_turtlesim_view,
)

__all__ = ["desk"]

pytestmark = pytest.mark.timeout(300)  # one chapter, start to end, on a busy machine

DUCKS = {"huey": "red", "dewey": "blue", "louie": "green", "webby": "pink"}
BLUE = (69, 86, 255)  # the book (groovy) prints 69, 85, 255; turtlesim has used 86 since
YELLOW = (255, 255, 0)


def colour_seen(env: dict[str, str]) -> tuple[int, int, int]:
    """What turtle1's colour sensor reads under the turtle: the background where it has not drawn."""
    text = ok("topic echo -n 1 /turtle1/color_sensor", env)
    values = dict(re.findall(r"^(r|g|b): (\d+)$", text, re.MULTILINE))
    return int(values["r"]), int(values["g"]), int(values["b"])


def world_shows(sim: Terminal, rgb: tuple[int, int, int]) -> bool:
    """True when the turtlesim app paints cells in colour ``rgb`` (a truecolor terminal)."""
    code = ";".join(str(c) for c in rgb)
    return f"48;2;{code}m" in sim.colours() or f"38;2;{code}m" in sim.colours()


def test_parameters_of_chapter_7(desk: Desk, tmp_path: Path) -> None:
    env = desk.env
    start_core(desk)

    # 7.1: the master's own parameters.
    assert lines(ok("param list", env)) == ["/rosdistro", "/rosversion", "/run_id"]
    assert yaml.safe_load(ok("param get /rosdistro", env)).strip() == "noetic"  # the book (groovy era) prints groovy
    assert set(yaml.safe_load(ok("param get /", env))) == {"rosdistro", "rosversion", "run_id"}

    # Setting parameters one by one, then as one YAML dictionary typed over two lines; dump and load.
    for duck, colour in DUCKS.items():
        ok(f"param set /duck_colors/{duck} {colour}", env)
    assert yaml.safe_load(ok("param get /duck_colors", env)) == DUCKS
    ok("param delete /duck_colors", env)
    shell = desk.terminal("shell")
    shell.run('rostui param set /duck_colors "huey: red\ndewey: blue\nlouie: green\nwebby: pink"')
    assert shell.exit_status() == 0
    assert yaml.safe_load(ok("param get /duck_colors", env)) == DUCKS
    shell.run("rostui param dump ducks.yaml /duck_colors && rostui param delete /duck_colors")
    assert shell.exit_status() == 0
    assert yaml.safe_load((tmp_path / "ducks.yaml").read_text()) == DUCKS
    assert cli("param get /duck_colors", env).returncode != 0
    shell.run("rostui param load ducks.yaml /duck_colors")
    assert shell.exit_status() == 0
    assert yaml.safe_load(ok("param get /duck_colors/webby", env)) == "pink"

    # 7.2: turtlesim's background parameters; a change shows only after /clear.
    sim = start_turtlesim_view(desk)
    assert {"/background_b", "/background_g", "/background_r"} <= set(lines(ok("param list", env)))
    assert tuple(int(ok(f"param get /background_{c}", env)) for c in "rgb") == BLUE
    poll(lambda: world_shows(sim, BLUE), "the blue world on screen")
    for channel, value in zip("rgb", YELLOW):
        ok(f"param set /background_{channel} {value}", env)
    assert colour_seen(env) == BLUE and world_shows(sim, BLUE)
    assert ok("service call /clear", env) == "\n"
    poll(lambda: colour_seen(env) == YELLOW, "the colour sensor to read yellow")
    poll(lambda: world_shows(sim, YELLOW) and not world_shows(sim, BLUE), "the yellow world on screen")

    # 7.3: set_bg_color does the same from a program.
    for channel, value in zip("rgb", BLUE):
        ok(f"param set /background_{channel} {value}", env)
    ok("service call /clear", env)
    poll(lambda: world_shows(sim, BLUE), "the blue world again")
    shell.run("rostui run agitr set_bg_color")
    assert shell.exit_status() == 0
    poll(lambda: world_shows(sim, YELLOW), "set_bg_color's yellow world")

    # pubvel_with_max needs ~max_vel: FATAL without it; then from rosparam set, or _max_vel:=1.
    shell.run("rostui run agitr pubvel_with_max")
    assert shell.exit_status() == 1
    assert log_lines(shell.screen(100), "FATAL") == ["Could not get parameter ~max_vel"]
    ok("param set /publish_velocity/max_vel 0.1", env)
    pubvel = desk.terminal("pubvel")
    pubvel.run("rostui run agitr pubvel_with_max")
    speeds = [float(v) for v in re.findall(r"^linear: (\S+)$",
                                          ok("topic echo -n 3 /turtle1/command_velocity", env), re.MULTILINE)]
    assert len(speeds) == 3 and all(0.0 <= v <= 0.1 for v in speeds), speeds
    assert pubvel.interrupt() == 0
    pubvel.run("rostui run agitr pubvel_with_max _max_vel:=1")
    poll(lambda: ok("param get /publish_velocity/max_vel", env).strip() in ("1", "1.0"), "_max_vel:=1 to be set")
    assert pubvel.interrupt() == 0
    sim.keys("q")
    assert sim.exit_status() == 0

    # 7.4: fast_yellow.launch sets ~max_vel to 3 and turns its turtlesim's background yellow.
    for channel, value in zip("rgb", BLUE):
        ok(f"param set /background_{channel} {value}", env)
    fast = desk.terminal("fast")
    fast.run("rostui launch agitr fast_yellow.launch")
    poll(lambda: "/publish_velocity" in lines(ok("node list", env)), "fast_yellow's nodes")
    assert ok("param get /publish_velocity/max_vel", env).strip() == "3"
    assert {("/publish_velocity", "/turtlesim", "/turtle1/command_velocity")} <= dot_edges(ok("graph --dot", env))
    poll(lambda: colour_seen(env) == YELLOW, "fast_yellow's yellow background")
    assert fast.interrupt(timeout=90) in (0, 130)
