"""The book's example programs (package agitr) against a live master: each does what the book says.

Programs start with ``rostui run agitr NAME`` as a user would; those that need
a simulator get a headless rostui turtlesim.
"""

from __future__ import annotations

import math
import re
import statistics
import time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Iterator

import pytest
from live_helpers import Program, Watcher, log_lines, log_stamps, start_headless_sim, stop_all, wait_until

from rostui.core import packages
from rostui.tools.run import resolve

CENTRE = 5.544445
LAUNCH_FILES = ["example.launch", "doublesim.launch", "reverse.launch", "triplesim.launch", "fast_yellow.launch"]


class Session:
    """A watcher node and everything a test started, stopped at the end."""

    def __init__(self, env: dict[str, str], tmp: Path) -> None:
        self.env = env
        self.tmp = tmp
        self.watcher = Watcher()
        self.items: list[Any] = [self.watcher]

    def run(self, executable: str, *args: str, label: str | None = None) -> Program:
        """Start ``rostui run agitr EXECUTABLE ARGS``."""
        program = Program(self.env, self.tmp, "agitr", executable, *args, label=label)
        self.items.append(program)
        return program

    def sim(self) -> None:
        """Start a headless turtlesim and wait for turtle1's pose."""
        self.items.append(start_headless_sim(self.env, self.tmp))
        self.watcher.record("/turtle1/pose", "turtlesim/Pose").wait_for_count(1, "turtlesim's first pose")


@pytest.fixture
def session(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[Session]:
    """A live `rostui core` and a session on it."""
    s = Session(ros_env, tmp_path)
    try:
        yield s
    finally:
        stop_all(s.items)


# -- chapter 3 -------------------------------------------------------------------------------
def test_hello_logs_hello_ros(session: Session) -> None:
    program = session.run("hello")
    assert program.wait_exit() == 0
    assert log_lines(program.stdout, "INFO") == ["Hello, ROS!"]


def test_pubvel_publishes_random_velocities_at_2hz_and_moves_the_turtle(session: Session) -> None:
    session.sim()
    velocities = session.watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    poses = session.watcher.record("/turtle1/pose", "turtlesim/Pose")
    program = session.run("pubvel")
    messages = velocities.wait_for_count(5, "five velocity commands")
    assert all(0.0 <= m.linear <= 1.0 and -1.0 <= m.angular <= 1.0 for m in messages)
    assert len({(m.linear, m.angular) for m in messages}) == len(messages)
    poses.wait_for(lambda p: math.dist((p.x, p.y), (CENTRE, CENTRE)) > 0.2, "the turtle to move")
    logged = [re.fullmatch(r"Sending random velocity command: linear=(\S+) angular=(\S+)", line)
              for line in log_lines(program.stdout, "INFO")]
    assert logged and all(logged)
    sent = {(round(m.linear, 4), round(m.angular, 4)) for m in messages}
    assert sent & {(round(float(m[1]), 4), round(float(m[2]), 4)) for m in logged if m}
    stamps = [float(s) for s in re.findall(r"^\[ INFO\] \[([\d.]+)\]: Sending", program.stdout, re.MULTILINE)]
    assert statistics.median(b - a for a, b in zip(stamps, stamps[1:])) == pytest.approx(0.5, abs=0.1)


def test_subpose_prints_position_and_direction(session: Session) -> None:
    session.sim()
    program = session.run("subpose")
    program.wait_for_output(r"^\[ INFO\] \[[\d.]+\]: position=\(5\.54,5\.54\) direction=0\.00$")


# -- chapter 4 ------------------------------------------------------------------------------
def test_count_logs_at_every_level_but_debug(session: Session) -> None:
    program = session.run("count")
    program.wait_for_output(r"20 is divisible by 20\.$")
    program.stop()
    assert log_lines(program.stdout, "INFO")[:6] == [f"{i} is divisible by 3." for i in (3, 6, 9, 12, 15, 18)]
    assert log_lines(program.stderr, "WARN")[:4] == [f"{i} is divisible by 5." for i in (5, 10, 15, 20)]
    assert log_lines(program.stderr, "ERROR")[:2] == ["10 is divisible by 10.", "20 is divisible by 10."]
    assert log_lines(program.stderr, "FATAL")[:1] == ["20 is divisible by 20."]
    assert "Counted to" not in program.output
    assert "WARN" not in program.stdout and "INFO" not in program.stderr


def test_once_logs_each_level_once(session: Session) -> None:
    program = session.run("once")
    program.wait_for_output(r"^\[FATAL\] \[[\d.]+\]: This appears only once\.$")
    time.sleep(1.0)  # the loop keeps running; nothing more may appear
    program.stop()
    for level in ("INFO", "WARN", "ERROR", "FATAL"):
        assert log_lines(program.output, level) == ["This appears only once."]
    assert log_lines(program.output, "DEBUG") == []


def test_throttle_keeps_each_message_to_its_period(session: Session) -> None:
    program = session.run("throttle")
    wait_until(lambda: len(log_stamps(program.stderr, "FATAL", "This appears every 2.0 seconds.")) >= 3,
               "three FATAL lines")
    program.stop()
    periods = {"INFO": 0.3, "WARN": 0.5, "ERROR": 1.0, "FATAL": 2.0}
    for level, period in periods.items():
        stamps = log_stamps(program.output, level, f"This appears every {period:.1f} seconds.")
        assert len(stamps) >= 3, level
        assert min(b - a for a, b in zip(stamps, stamps[1:])) >= period - 0.01, level
    assert log_lines(program.output, "DEBUG") == []


# -- chapter 5 ---------------------------------------------------------------------------
def test_two_anon_nodes_run_at_once_with_distinct_names(session: Session) -> None:
    first = session.run("anon", label="anon1")
    second = session.run("anon", label="anon2")
    pattern = r"This message is from (/anon_\d+_\d+)$"
    names = {first.wait_for_output(pattern)[1], second.wait_for_output(pattern)[1]}
    assert len(names) == 2
    for name in names:
        assert session.watcher.lookup_node(name)
    assert first.proc.poll() is None and second.proc.poll() is None


# -- chapter 6 ---------------------------------------------------------------------------
def test_reverse_cmd_vel_republishes_negated_commands(session: Session) -> None:
    reversed_ = session.watcher.record("/turtle1/command_velocity_reversed", "turtlesim/Velocity")
    session.run("reverse_cmd_vel")
    reversed_.wait_connected()
    pub = session.watcher.publisher("/turtle1/command_velocity", "turtlesim/Velocity")
    wait_until(lambda: pub.get_num_connections() > 0, "reverse_velocity to subscribe")
    pub.publish(linear=1.5, angular=-0.5)
    message = reversed_.wait_for_count(1)[0]
    assert (message.linear, message.angular) == (-1.5, 0.5)
    assert session.watcher.lookup_node("/reverse_velocity")


# -- chapter 7 ---------------------------------------------------------------------------
def test_set_bg_color_turns_the_background_yellow(session: Session) -> None:
    session.sim()
    colours = session.watcher.record("/turtle1/color_sensor", "turtlesim/Color")
    first = colours.wait_for_count(1)[0]
    assert (first.r, first.g, first.b) != (255, 255, 0)
    program = session.run("set_bg_color")
    assert program.wait_exit() == 0
    assert [session.watcher.get_param(f"/background_{c}") for c in "rgb"] == [255, 255, 0]
    colours.wait_for(lambda c: (c.r, c.g, c.b) == (255, 255, 0), "the colour sensor to see yellow")


def test_pubvel_with_max_is_fatal_without_its_parameter(session: Session) -> None:
    program = session.run("pubvel_with_max")
    assert program.wait_exit() == 1
    assert log_lines(program.stderr, "FATAL") == ["Could not get parameter ~max_vel"]
    assert program.stdout == ""


def test_pubvel_with_max_scales_linear_velocity(session: Session) -> None:
    velocities = session.watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    session.run("pubvel_with_max", "_max_vel:=0.1")
    messages = velocities.wait_for_count(4, "four velocity commands")
    assert all(0.0 <= m.linear <= 0.1 and -1.0 <= m.angular <= 1.0 for m in messages)
    assert any(m.linear > 0.0 for m in messages)
    assert session.watcher.get_param("/publish_velocity/max_vel") == 0.1


# -- chapter 8 ---------------------------------------------------------------------------
def test_spawn_turtle_spawns_leo_once(session: Session) -> None:
    session.sim()
    first = session.run("spawn_turtle", label="spawn1")
    assert first.wait_exit() == 0
    assert log_lines(first.stdout, "INFO") == ["Spawned a turtle named Leo"]
    leo = session.watcher.record("/Leo/pose", "turtlesim/Pose").wait_for_count(1, "Leo's pose")[0]
    assert (leo.x, leo.y) == (2.0, 3.0)
    assert leo.theta == pytest.approx(math.pi / 2, abs=1e-5)
    second = session.run("spawn_turtle", label="spawn2")
    assert second.wait_exit() == 0
    assert log_lines(second.stderr, "ERROR") == ["Failed to spawn."]


def test_pubvel_toggle_switches_between_forward_and_rotate(session: Session) -> None:
    session.sim()
    velocities = session.watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    program = session.run("pubvel_toggle")
    velocities.wait_for(lambda m: (m.linear, m.angular) == (1.0, 0.0), "a forward command")
    session.watcher.call("/toggle_forward", "std_srvs/Empty")
    program.wait_for_output(r"^\[ INFO\] \[[\d.]+\]: Now sending rotate commands\.$")
    count = len(velocities.messages)
    wait_until(lambda: (0.0, 1.0) in [(m.linear, m.angular) for m in velocities.messages[count:]],
               "a rotate command")
    session.watcher.call("/toggle_forward", "std_srvs/Empty")
    program.wait_for_output(r"Now sending forward commands\.$")
    count = len(velocities.messages)
    wait_until(lambda: (1.0, 0.0) in [(m.linear, m.angular) for m in velocities.messages[count:]],
               "forward commands again")


# -- launch files ------------------------------------------------------------------------------
@pytest.mark.parametrize("name", LAUNCH_FILES)
def test_launch_file_is_well_formed_and_every_node_resolves(name: str) -> None:
    path = packages.get_package_path("agitr") / name
    root = ET.parse(path).getroot()
    assert root.tag == "launch"
    nodes = list(root.iter("node"))
    assert nodes
    for node in nodes:
        assert {"pkg", "type", "name"} <= set(node.attrib), node.attrib
        argv = resolve(node.attrib["pkg"], node.attrib["type"])
        assert Path(argv[-1]).name == node.attrib["type"]
        if node.attrib["type"] == "turtle_teleop_key":
            assert node.attrib["launch-prefix"] == "xterm -e"
    for include in root.iter("include"):
        found = re.sub(r"\$\(find (\w+)\)", lambda m: str(packages.get_package_path(m[1])), include.attrib["file"])
        assert Path(found).is_file()


def test_launch_files_say_what_the_book_says() -> None:
    share = packages.get_package_path("agitr")

    def nodes(name: str) -> list[tuple[str, str, str, str]]:
        root = ET.parse(share / name).getroot()
        return [(n.get("pkg", ""), n.get("type", ""), n.get("name", ""), n.get("ns", "")) for n in root.iter("node")]
    assert nodes("example.launch") == [("turtlesim", "turtlesim_node", "turtlesim", ""),
                                       ("turtlesim", "turtle_teleop_key", "teleop_key", ""),
                                       ("agitr", "subpose", "pose_subscriber", "")]
    assert nodes("doublesim.launch") == [("turtlesim", "turtlesim_node", "turtlesim_node", "sim1"),
                                         ("turtlesim", "turtle_teleop_key", "teleop_key", "sim1"),
                                         ("turtlesim", "turtlesim_node", "turtlesim_node", "sim2"),
                                         ("agitr", "pubvel", "velocity_publisher", "sim2")]
    reverse = ET.parse(share / "reverse.launch").getroot()
    remap = reverse.find("node/remap")
    assert remap is not None and remap.attrib == {"from": "turtle1/command_velocity",
                                                  "to": "turtle1/command_velocity_reversed"}
    triple = ET.parse(share / "triplesim.launch").getroot()
    group = triple.find("group")
    assert group is not None and group.attrib == {"ns": "sim3", "if": "$(arg use_sim3)"}
    arg = triple.find("arg")
    assert arg is not None and arg.attrib == {"name": "use_sim3", "default": "0"}
    fast = ET.parse(share / "fast_yellow.launch").getroot()
    param = fast.find("node/param")
    assert param is not None and param.attrib == {"name": "max_vel", "value": "3"}
    assert nodes("fast_yellow.launch")[1:] == [("agitr", "pubvel_with_max", "publish_velocity", ""),
                                               ("agitr", "set_bg_color", "set_bg_color", "")]
