"""Real turtlesim rospy scripts, unmodified, drive rostui's headless turtlesim the same under both rospys.

Each script in tests/python_compat/turtlesim_real (sources in its SOURCES.md) runs under `rostui python`
(rostui's rospy) and under Debian's rospy (/usr/bin/python3), each time against a fresh headless
`rostui run turtlesim turtlesim_node`, on rostui core and on a real roscore. What the test compares is what
a user would see in turtlesim: the turtles there, their poses (as `rostui topic echo -p` prints them),
the poses where a turtle came to rest, and what the scripts print. Both runs must agree, within the same
tolerance where the script's timing decides how far the turtle goes.
"""

from __future__ import annotations

import math
import os
import pty
import re
import subprocess
import sys
import threading
import time
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
#: How far apart the two runs may put a turtle whose motion the script times (m, rad).
TIMED_TOLERANCE = 0.15


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


def test_draw_square_rests_at_the_same_corners(world, sides: dict[str, dict[str, str]]) -> None:
    """turtle_commander's square.py: forward 2 m, turn 1.56 rad, every 2 s; the corners where the turtle rests
    agree between both rospys."""
    corners: dict[str, list[Pose]] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        script = w.run(command(side, CORPUS / "turtle_commander" / "square.py"), sides[side], f"square {side}")
        wait_until(lambda: len(log.rests()) >= 5 or script.proc.poll() is not None, "four legs of the square",
                   timeout=90)
        script.stop()
        corners[side] = log.rests()[:5]
        assert len(corners[side]) == 5, script.describe()
        assert "Traceback" not in script.output, script.describe()
    shim, real = corners["shim"], corners["real"]
    assert all(a.near(b, TIMED_TOLERANCE) for a, b in zip(shim, real)), (shim, real)
    assert shim[0].near(Pose(CENTRE, CENTRE, 0.0, 0, 0), 1e-6)
    assert shim[1].x > CENTRE + 1.5 and shim[1].y == pytest.approx(CENTRE, abs=1e-4), shim  # forward first
    assert shim[2].theta == pytest.approx(1.56, abs=TIMED_TOLERANCE), shim  # then a quarter turn left


def test_service_scripts_spawn_and_teleport(world, sides: dict[str, dict[str, str]]) -> None:
    """hello_turtleMia's turtleSpawn.py and turtlePos.py (no init_node) and turtle_commander's spawner.py
    (a private parameter): the same turtles at the same poses, the same output."""
    seen: dict[str, dict[str, object]] = {}
    for side in SIDES:
        w = world()
        env = sides[side]
        said = []
        for script, args in ((CORPUS / "hello_turtleMia" / "turtleSpawn.py", []),
                             (CORPUS / "hello_turtleMia" / "turtlePos.py", ["--x", "2", "--y", "3", "--ang", "1.0"]),
                             (CORPUS / "turtle_commander" / "spawner.py", ["_spawned_name:=leo"])):
            out = subprocess.run(command(side, script, *args), env=env, capture_output=True, text=True, timeout=120,
                                 stdin=subprocess.DEVNULL)
            assert out.returncode == 0, f"{script.name} ({side}):\n{out.stdout}{out.stderr}"
            said.append(out.stdout)
        poses = {name: w.echo(f"/{name}/pose").last() for name in ("turtle1", "turtle2", "leo")}
        turtles = sorted(t.split("/")[1] for t in w.topics() if t.endswith("/pose"))
        seen[side] = {"said": said, "poses": poses, "turtles": turtles}
    assert seen["shim"] == seen["real"]
    assert seen["shim"]["turtles"] == ["leo", "turtle1", "turtle2"]
    assert seen["shim"]["said"][1] == "Teleported to x: 2.0, y: 3.0, ang: 1.0\n"
    poses = seen["shim"]["poses"]
    assert (poses["turtle1"].x, poses["turtle1"].y, poses["turtle1"].theta) == (2.0, 3.0, 1.0)
    assert (poses["turtle2"].x, poses["turtle2"].y) == (5.0, 5.0) and (poses["leo"].x, poses["leo"].y) == (2.0, 8.0)


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


def _colours(log: Peer) -> list[tuple[int, int, int]]:
    """The colours a `rostui topic echo -p .../color_sensor` printed, each run of equal ones once."""
    out: list[tuple[int, int, int]] = []
    for line in log.output.splitlines():
        fields = line.split(",")
        if len(fields) == 4 and not line.startswith("%"):
            colour = (int(fields[1]), int(fields[2]), int(fields[3]))
            if not out or out[-1] != colour:
                out.append(colour)
    return out


def test_turtle_controller_pen_colours(world, sides: dict[str, dict[str, str]]) -> None:
    """my_robot_controller's turtle controller calls /turtle1/set_pen from its pose callback, red right of
    x=5.5 and green left of it: the colour sensor sees the same pen colours in the same order under both
    rospys, and the script prints the same log lines (rospy's format, times aside)."""
    seen: dict[str, tuple[list[tuple[int, int, int]], list[str]]] = {}
    for side in SIDES:
        w = world()
        sensor = w.run([sys.executable, "-m", "rostui", "topic", "echo", "-p", "/turtle1/color_sensor"], w.env,
                       "color_sensor")
        script = w.run(command(side, CORPUS / "my_robot_controller" / "turlte_controller.py"), sides[side],
                       f"turtle controller {side}")
        wait_until(lambda: GREEN in _colours(sensor) or script.proc.poll() is not None, "a green trail",
                   timeout=90)
        script.stop()
        colours = _colours(sensor)
        assert GREEN in colours, script.describe()
        lines = [re.sub(r"^\[(\w+)\] \[\d+\.\d{6}\]: ", r"[\1] [T]: ", line) for line in script.lines]
        started = "[INFO] [T]: Ros has been started"  # printed on the main thread, the others in the callback
        assert started in lines, script.describe()
        seen[side] = (colours[:colours.index(GREEN) + 1], [line for line in lines if line != started][:4])
    assert seen["shim"] == seen["real"]
    assert seen["shim"][0][:2] == [BACKGROUND, RED], seen
    assert seen["shim"][1] == ["[INFO] [T]: ", "[INFO] [T]: COLOR RED", "[INFO] [T]: ", "[INFO] [T]: COLOR GREEN"]


def test_draw_circle_keeps_one_circle(world, sides: dict[str, dict[str, str]]) -> None:
    """my_robot_controller's draw_circle.py (node name "draw_cirle.py", code after the `if __name__` block):
    3 m/s at 3 rad/s keeps the turtle on the circle of radius 1 above its start, under both rospys."""
    centre = (CENTRE, CENTRE + 1.0)
    warned = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        script = w.run(command(side, CORPUS / "my_robot_controller" / "draw_circle.py"), sides[side],
                       f"draw_circle {side}")
        wait_until(lambda: sum(p.linear > 0 for p in log.poses()) > 250 or script.proc.poll() is not None,
                   "four seconds of driving", timeout=60)
        assert script.proc.poll() is None, script.describe()
        nodes = subprocess.run([sys.executable, "-m", "rostui", "node", "list"], env=w.env, capture_output=True,
                               text=True, timeout=60).stdout.split()
        script.stop()
        driving = [p for p in log.poses() if p.linear > 0]
        radii = [math.hypot(p.x - centre[0], p.y - centre[1]) for p in driving]
        assert all(abs(r - 1.0) < 0.05 for r in radii), (side, min(radii), max(radii))
        assert max(p.theta for p in driving) - min(p.theta for p in driving) > 5.0, side  # went round
        assert "/draw_cirle.py" in nodes, (side, nodes)
        warned[side] = [line for line in script.lines if "Warning" in line]
    assert warned["shim"] == warned["real"] == [
        f"{CORPUS / 'my_robot_controller' / 'draw_circle.py'}:6: UserWarning: 'draw_cirle.py' is not a legal ROS "
        "base name. This may cause problems with other ROS tools."]


def test_move_straight_line_from_stdin(world, sides: dict[str, dict[str, str]]) -> None:
    """The ROS wiki's "Moving in a Straight Line" as assign4's jinots.py has it (Python 3's int(input())):
    speed 1, distance 2, forward, typed on stdin; it publishes in a loop without sleeping until the time says
    2 m were driven, then stops the turtle; both rospys stop it at the same place."""
    ends: dict[str, Pose] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        proc = subprocess.Popen(command(side, CORPUS / "assign4" / "jinots.py"), env=sides[side],
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            assert proc.stdin is not None
            proc.stdin.write("1\n2\n1\n")
            proc.stdin.flush()
            wait_until(lambda: len(log.rests()) >= 2 or proc.poll() is not None, "the turtle to drive and stop",
                       timeout=60)
        finally:
            stop_process(proc)
        out = proc.stdout.read() if proc.stdout else ""
        assert len(log.rests()) == 2, out
        assert out.startswith("Let's move your robot\nInput your speed:Type your distance:Foward?: "), out
        ends[side] = log.rests()[1]
    assert ends["shim"].near(ends["real"], TIMED_TOLERANCE), ends
    assert ends["shim"].near(Pose(CENTRE + 2.0, CENTRE, 0.0, 0, 0), TIMED_TOLERANCE), ends


def test_set_bg_color_turns_the_background_yellow(world, sides: dict[str, dict[str, str]]) -> None:
    """A course's Python set_bg_color.py (the book's Listing 7.1): it sets background_r/g/b and calls
    /clear; the colour sensor sees the yellow background under both rospys."""
    for side in SIDES:
        for colour in "rgb":  # the first run's yellow stays on the master; each turtlesim starts blue
            subprocess.run([sys.executable, "-m", "rostui", "param", "delete", f"/background_{colour}"],
                           env=sides[side], capture_output=True, timeout=60)
        w = world()
        sensor = w.run([sys.executable, "-m", "rostui", "topic", "echo", "-p", "/turtle1/color_sensor"], w.env,
                       "color_sensor")
        wait_until(lambda: bool(_colours(sensor)), "the colour sensor")
        assert _colours(sensor)[-1] == BACKGROUND
        out = subprocess.run(command(side, CORPUS / "irr_mcs_5403" / "set_bg_color.py"), env=sides[side],
                             capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
        assert out.returncode == 0 and out.stdout == "", out.stdout + out.stderr
        wait_until(lambda: _colours(sensor)[-1] == (255, 255, 0), f"a yellow background ({side})")
        params = subprocess.run([sys.executable, "-m", "rostui", "param", "get", "/background_g"], env=w.env,
                                capture_output=True, text=True, timeout=60).stdout.strip()
        assert params == "255", (side, params)


def test_draw_cc_kills_resets_and_spawns(world, sides: dict[str, dict[str, str]]) -> None:
    """p1_cchang31's draw_cc.py, twice: /reset, /kill turtle1, /spawn turtle2 and turtle3 and drive each
    along three quarters of a circle; both rospys leave the same turtles, turtle2 at the same place, and the
    same log lines."""
    seen: dict[str, tuple[list[str], list[str]]] = {}
    ends: dict[str, Pose] = {}
    for side in SIDES:
        w = world()
        out = subprocess.run(command(side, CORPUS / "p1_cchang31" / "draw_cc.py"), env=sides[side],
                             capture_output=True, text=True, timeout=180, stdin=subprocess.DEVNULL)
        assert out.returncode == 0, out.stdout + out.stderr
        turtles = sorted(t.split("/")[1] for t in w.topics() if t.endswith("/pose"))
        lines = [re.sub(r"^\[(\w+)\] \[\d+\.\d{6}\]: ", r"[\1] [T]: ", line) for line in out.stdout.splitlines()]
        seen[side] = (turtles, lines)
        ends[side] = w.echo("/turtle2/pose").last()
    assert seen["shim"] == seen["real"] == (["turtle2", "turtle3"], ["[INFO] [T]: CC drawn"] * 2)
    assert ends["shim"].near(ends["real"], TIMED_TOLERANCE), ends
    assert not ends["shim"].near(Pose(3.0, 5.0, 0.75 * math.pi, 0, 0), 0.5), ends  # it did drive


def test_go_to_goal_from_stdin(world, sides: dict[str, dict[str, str]]) -> None:
    """ROS_Training_Summer_24's goal.py (a go-to-goal proportional controller): it refuses a goal above 11,
    then drives to (8, 7) typed on stdin and exits; both rospys leave the turtle there."""
    ends: dict[str, Pose] = {}
    said: dict[str, str] = {}
    for side in SIDES:
        w = world()
        log = w.echo("/turtle1/pose")
        log.last()
        out = subprocess.run(command(side, CORPUS / "ros_training_summer_24" / "goal.py"), env=sides[side],
                             input="12\n3\n8\n7\n", capture_output=True, text=True, timeout=180)
        assert out.returncode == 0, out.stdout + out.stderr
        said[side] = out.stdout
        wait_until(lambda: log.last().linear == 0.0 and log.last().angular == 0.0, "the turtle to stop")
        ends[side] = log.last()
    assert said["shim"] == said["real"] == (
        "Enter the x goal to move (<= 11): Enter the y goal to move (<= 11): Both x and y goals must be less than "
        "or equal to 11. Please try again.\nEnter the x goal to move (<= 11): Enter the y goal to move (<= 11): ")
    shim, real = ends["shim"], ends["real"]  # the heading at arrival is the controller's accident, not its goal
    assert math.hypot(shim.x - real.x, shim.y - real.y) < TIMED_TOLERANCE, ends
    assert math.hypot(shim.x - 8.0, shim.y - 7.0) < 0.1, ends
