"""Real turtlesim rospy scripts, unmodified, drive rostui's headless turtlesim the same under both rospys.

Each script in tests/python_compat/turtlesim_real (sources and licences in its SOURCES.md) runs under
`rostui python` (rostui's rospy) and under Debian's rospy (/usr/bin/python3), each time against a fresh
headless `rostui run turtlesim turtlesim_node`, on rostui core and on a real roscore. What the test compares
is what a user would see in turtlesim: the turtle's poses (as `rostui topic echo -p` prints them), the
poses where it came to rest, the node names, and what the scripts print. Both runs must agree exactly where
nothing but the script decides (a wall stops the turtle), and within :data:`TIMED_TOLERANCE` where the
script times the motion by the clock: a connection made a few milliseconds later (the first messages of a
new publisher are lost until then) or a late wake-up moves a timed turtle by a few centimetres.
"""

from __future__ import annotations

import math
import os
import pty
import re
import subprocess
import sys
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, stop_process, wait_until
from interop_helpers import Peer
from test_interop_turtlesim import turtlesim_python  # noqa: F401  (the fixture: genpy's turtlesim for Debian)

CORPUS = REPO / "tests" / "python_compat" / "turtlesim_real"
PACKAGE_PATH = CORPUS / "ros_package_path"
CENTRE = 5.544444561004639
SIDES = ("shim", "real")
BACKGROUND, RED, GREEN = (69, 86, 255), (225, 0, 0), (0, 255, 0)
#: How far apart the two runs may put a turtle whose motion the script times (m, rad): the scripts here
#: drive at up to 1 m/s or 1 rad/s, so 0.15 is 0.15 s of motion, a late wake-up or a slow connection.
TIMED_TOLERANCE = 0.15
#: Where turtlesim's walls stop a turtle driving right: turtlesim clamps x to 11.088889 (its window).
EAST_WALL = 11.088889122009277


@dataclass(frozen=True)
class Pose:
    """One turtlesim/Pose sample."""

    x: float
    y: float
    theta: float
    linear: float
    angular: float

    def near(self, other: Pose, tolerance: float) -> bool:
        """Whether position and heading agree within *tolerance*."""
        turn = math.remainder(self.theta - other.theta, 2 * math.pi)
        return abs(self.x - other.x) <= tolerance and abs(self.y - other.y) <= tolerance and abs(turn) <= tolerance


@pytest.fixture
def sides(ros_env: dict[str, str], turtlesim_python: dict[str, str]) -> dict[str, dict[str, str]]:  # noqa: F811
    """The environment of each side: ``shim`` (rostui python --rostui) and ``real`` (Debian's rospy)."""
    base = {k: v for k, v in ros_env.items() if k != "PYTHONPATH" and not k.startswith("ROSTUI_PYTHON")}
    shim = dict(base, ROS_PACKAGE_PATH=str(PACKAGE_PATH))
    real = dict(base, PYTHONPATH=turtlesim_python["PYTHONPATH"],
                ROS_PACKAGE_PATH=os.pathsep.join([str(PACKAGE_PATH), turtlesim_python["ROS_PACKAGE_PATH"]]))
    return {"shim": shim, "real": real}


def command(side: str, script: Path, *args: str) -> list[str]:
    """How *side* runs *script*: `rostui python --rostui` or Debian's python3."""
    if side == "shim":
        return [sys.executable, "-m", "rostui", "python", "--rostui", str(script), *args]
    return [SYSTEM_PYTHON, str(script), *args]


class PoseLog:
    """`rostui topic echo -p TOPIC` running in the background, its CSV rows parsed."""

    def __init__(self, env: dict[str, str], topic: str) -> None:
        self.peer = Peer([sys.executable, "-m", "rostui", "topic", "echo", "-p", topic], env, f"echo {topic}")

    def poses(self) -> list[Pose]:
        """Every pose printed so far."""
        out = []
        for line in self.peer.output.splitlines():
            fields = line.split(",")
            if len(fields) == 6 and not line.startswith("%"):
                out.append(Pose(*(float(f) for f in fields[1:])))
        return out

    def rests(self) -> list[Pose]:
        """The poses where the turtle came to rest, in order (the first is where it started)."""
        out: list[Pose] = []
        for pose in self.poses():
            if pose.linear == 0.0 and pose.angular == 0.0 and (not out or not pose.near(out[-1], 1e-4)):
                out.append(pose)
        return out

    def last(self) -> Pose:
        """The latest pose (waits for the first)."""
        wait_until(lambda: bool(self.poses()), "a pose to be printed")
        return self.poses()[-1]


@dataclass
class World:
    """A fresh headless turtlesim and the processes a run started, stopped at the end."""

    env: dict[str, str]
    peers: list[Peer]

    @property
    def sim(self) -> Peer:
        """The headless turtlesim (what it prints: its spawns and kills)."""
        return self.peers[0]

    def echo(self, topic: str) -> PoseLog:
        """Start printing *topic*'s poses."""
        log = PoseLog(self.env, topic)
        self.peers.append(log.peer)
        return log

    def run(self, argv: list[str], env: dict[str, str], label: str) -> Peer:
        """Start a script in the background."""
        peer = Peer(argv, env, label)
        self.peers.append(peer)
        return peer

    def topics(self) -> list[str]:
        """`rostui topic list`."""
        out = subprocess.run([sys.executable, "-m", "rostui", "topic", "list"], env=self.env, capture_output=True,
                             text=True, timeout=60)
        return out.stdout.split()


@pytest.fixture
def world(any_master: str, ros_env: dict[str, str]) -> Iterator[callable]:
    """``world()`` starts a fresh headless rostui turtlesim (the previous one stopped first)."""
    worlds: list[World] = []

    def stop_all() -> None:
        for w in worlds:
            for peer in reversed(w.peers):
                peer.stop()
        worlds.clear()

    def start() -> World:
        stop_all()
        sim = Peer([sys.executable, "-m", "rostui", "run", "turtlesim", "turtlesim_node", "--headless"], ros_env,
                   "rostui turtlesim")
        sim.wait_for(r"Spawning turtle \[turtle1\]")
        w = World(ros_env, [sim])
        worlds.append(w)
        return w

    try:
        yield start
    finally:
        stop_all()


class Terminal:
    """A script on a pseudo-terminal: what it prints is collected, keys are typed into it."""

    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        self.master, slave = pty.openpty()
        self.proc = subprocess.Popen(argv, env=env, stdin=slave, stdout=slave, stderr=slave, start_new_session=True)
        os.close(slave)
        self.text = ""
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        while True:
            try:
                chunk = os.read(self.master, 4096)
            except OSError:
                return
            if not chunk:
                return
            self.text += chunk.decode(errors="replace")

    def type(self, keys: str) -> None:
        """Type *keys*."""
        os.write(self.master, keys.encode())

    def close(self) -> None:
        """Stop the script (if still running) and close the terminal."""
        stop_process(self.proc)
        os.close(self.master)


def test_teleop_twist_keyboard_drives_the_turtle(world, sides: dict[str, dict[str, str]]) -> None:
    """teleop_twist_keyboard.py on a terminal, remapped to turtle1: `i` drives 0.5 m/s forward until the key
    times out (0.5 s), `j` turns left the same way, Ctrl-C ends it; both rospys leave the turtle at the same
    place."""
    script = CORPUS / "teleop_twist_keyboard" / "teleop_twist_keyboard.py"
    ends: dict[str, list[Pose]] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        term = Terminal(command(side, script, "cmd_vel:=/turtle1/cmd_vel"), sides[side])
        try:
            wait_until(lambda: "currently:\tspeed 0.5\tturn 1.0" in term.text or term.proc.poll() is not None,
                       "teleop_twist_keyboard's banner", timeout=60)
            assert term.proc.poll() is None, term.text
            for key in ("i", "j"):
                before = len(log.rests())
                term.type(key)
                wait_until(lambda: len(log.rests()) > before, f"the turtle to stop after {key!r}")
            term.type("\x03")
            term.proc.wait(timeout=30)
        finally:
            term.close()
        assert term.proc.returncode == 0, term.text
        ends[side] = log.rests()
    shim, real = ends["shim"], ends["real"]
    assert len(shim) == len(real) == 3, (shim, real)
    assert all(a.near(b, TIMED_TOLERANCE) for a, b in zip(shim, real)), (shim, real)
    assert shim[1].x > CENTRE + 0.1 and shim[1].y == pytest.approx(CENTRE, abs=1e-4) and shim[1].theta == 0.0
    assert shim[2].theta > 0.1 and (shim[2].x, shim[2].y) == (shim[1].x, shim[1].y)


def _timeless(lines: list[str]) -> list[str]:
    """rospy's console lines with the time stamp replaced by T (it differs from run to run)."""
    return [re.sub(r"^\[(\w+)\] \[\d+\.\d{6}\]: ", r"[\1] [T]: ", line) for line in lines]


def test_timed_out_and_back_rests_at_the_same_places(world, sides: dict[str, dict[str, str]]) -> None:
    """rbx1's timed_out_and_back.py (ROS by Example), remapped to turtle1: 1 m forward at 0.2 m/s, a half turn
    at 1 rad/s, 1 m back, a half turn, each timed by a 50 Hz rospy.Rate; the four places the turtle rests
    agree between both rospys, and so does what the script prints."""
    script = CORPUS / "rbx1" / "timed_out_and_back.py"
    rests: dict[str, list[Pose]] = {}
    said: dict[str, list[str]] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        out = subprocess.run(command(side, script, "/cmd_vel:=/turtle1/cmd_vel"), env=sides[side],
                             capture_output=True, text=True, timeout=180, stdin=subprocess.DEVNULL)
        assert out.returncode == 0, out.stdout + out.stderr
        wait_until(lambda: len(log.rests()) >= 5, f"the turtle to rest after the last half turn ({side})")
        rests[side] = log.rests()
        said[side] = _timeless(out.stdout.splitlines())
    shim, real = rests["shim"], rests["real"]
    assert len(shim) == len(real) == 5, (shim, real)
    assert all(a.near(b, TIMED_TOLERANCE) for a, b in zip(shim, real)), (shim, real)
    assert shim[0].near(Pose(CENTRE, CENTRE, 0.0, 0, 0), 1e-6)
    assert shim[1].near(Pose(CENTRE + 1.0, CENTRE, 0.0, 0, 0), TIMED_TOLERANCE), shim  # out
    assert shim[2].near(Pose(shim[1].x, shim[1].y, math.pi, 0, 0), TIMED_TOLERANCE), shim  # turned round
    assert shim[3].near(Pose(CENTRE, CENTRE, math.pi, 0, 0), 2 * TIMED_TOLERANCE), shim  # and back
    assert said["shim"] == said["real"] == ["[INFO] [T]: Stopping the robot..."], said


def test_turtle_move_keeps_one_circle(world, sides: dict[str, dict[str, str]]) -> None:
    """ros_study_unita's turtle_move.py (no `if __name__` block): 1 m/s at 1 rad/s at 5 Hz keeps the turtle on
    the circle of radius 1 above its start, under both rospys, as the node `/turtle_move`."""
    centre = (CENTRE, CENTRE + 1.0)
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        script = w.run(command(side, CORPUS / "ros_study_unita" / "turtle_move.py"), sides[side],
                       f"turtle_move {side}")

        def went_round() -> bool:
            thetas = [p.theta for p in log.poses() if p.linear > 0]
            return bool(thetas) and max(thetas) - min(thetas) > 5.0

        wait_until(lambda: went_round() or script.proc.poll() is not None, f"a turn of the circle ({side})",
                   timeout=60)
        assert script.proc.poll() is None, script.describe()
        nodes = subprocess.run([sys.executable, "-m", "rostui", "node", "list"], env=w.env, capture_output=True,
                               text=True, timeout=60).stdout.split()
        script.stop()
        radii = [math.hypot(p.x - centre[0], p.y - centre[1]) for p in log.poses() if p.linear > 0]
        assert all(abs(r - 1.0) < 0.05 for r in radii), (side, min(radii), max(radii))
        assert "/turtle_move" in nodes, (side, nodes)
        assert "Traceback" not in script.output, script.describe()


def test_move_linear_drives_to_the_wall(world, sides: dict[str, dict[str, str]]) -> None:
    """turtlesim_cleaner's practice1_move_linear.py publishes 1 m/s forward in a loop without sleeping until
    Ctrl-C; the wall stops the turtle at the same place under both rospys, and turtlesim says it hit it.

    The turtle starts half a metre from the wall (teleported there), not at the centre: the script's loop takes
    a whole CPU while it drives, and 5.5 m of it cost the suite 20 CPU seconds a run."""
    ends: dict[str, Pose] = {}
    start_x = EAST_WALL - 0.5
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        teleport = subprocess.run([sys.executable, "-m", "rostui", "service", "call", "/turtle1/teleport_absolute",
                                   repr(start_x), repr(CENTRE), "0.0"], env=w.env, capture_output=True, text=True,
                                  timeout=60)
        assert teleport.returncode == 0, teleport.stdout + teleport.stderr
        wait_until(lambda: log.last().x == pytest.approx(start_x, abs=1e-4), f"the turtle near the wall ({side})")
        script = w.run(command(side, CORPUS / "syanyong_turtlesim_cleaner" / "practice1_move_linear.py"),
                       sides[side], f"move_linear {side}")
        wait_until(lambda: log.last().x == pytest.approx(EAST_WALL, abs=1e-4) or script.proc.poll() is not None,
                   f"the turtle to reach the wall ({side})", timeout=60)
        assert script.proc.poll() is None, script.describe()
        script.stop()
        wait_until(lambda: log.last().linear == 0.0, f"the turtle to stop ({side})")
        assert w.peers[0].count(r"Oh no! I hit the wall!") >= 1, w.peers[0].describe()
        ends[side] = log.last()
    assert ends["shim"] == ends["real"], ends
    assert (ends["shim"].x, ends["shim"].y, ends["shim"].theta) == (pytest.approx(EAST_WALL, abs=1e-4), CENTRE, 0.0)


def test_turtlesim_joy_button_drives_a_circle(world, sides: dict[str, dict[str, str]]) -> None:
    """ROS Robotics By Example's turtlesim_joy.py: a sensor_msgs/Joy with the first button pressed (latched on
    /joy) makes its callback log the stick's twist and call move_circle.py's move_circle, 6 s of 1 m/s at
    1 rad/s timed by rospy.Time, then publish the stick's zero twist; both rospys stop the turtle at the same
    place on the circle of radius 1 above its start, and print the same line."""
    centre = (CENTRE, CENTRE + 1.0)
    ends: dict[str, Pose] = {}
    said: dict[str, list[str]] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        w.run([sys.executable, "-m", "rostui", "topic", "pub", "/joy", "sensor_msgs/Joy",
               "{axes: [0.0, 0.0], buttons: [1]}"], w.env, "joy")
        script = w.run(command(side, CORPUS / "ros_robotics_by_example" / "turtlesim_joy.py"), sides[side],
                       f"turtlesim_joy {side}")
        wait_until(lambda: len(log.rests()) >= 2 or script.proc.poll() is not None,
                   f"the turtle to drive and stop ({side})", timeout=60)
        assert script.proc.poll() is None, script.describe()
        script.stop()
        ends[side] = log.rests()[1]
        said[side] = _timeless(script.lines)
    shim, real = ends["shim"], ends["real"]
    assert shim.near(real, TIMED_TOLERANCE), ends
    assert math.hypot(shim.x - centre[0], shim.y - centre[1]) == pytest.approx(1.0, abs=0.05), ends
    assert shim.near(Pose(CENTRE + math.sin(6.0), CENTRE + 1.0 - math.cos(6.0), 6.0, 0, 0), 2 * TIMED_TOLERANCE), ends
    assert said["shim"] == said["real"] == ["[INFO] [T]: twist.linear: 0.000000 ; angular 0.000000"], said
