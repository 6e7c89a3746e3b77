"""turtle_teleop_key in a real terminal (a detached tmux pane) against `rostui core`.

Arrow keys typed with ``tmux send-keys`` must publish one Twist on
/turtle1/cmd_vel and one turtlesim/Velocity on /turtle1/command_velocity per
press, with ROS's default scale of 2.0; ``q`` quits and leaves the terminal
as it found it.
"""

from __future__ import annotations

import shlex
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator

import pytest

from rostui.turtlesim.teleop import BANNER, KeyDecoder, key_to_command

from conftest import REPO, rostui_cmd
from live_helpers import DEADLINE, Program, Watcher, start_headless_sim, stop_all, wait_until
from tmux_helpers import Pane

pytestmark = pytest.mark.skipif(shutil.which("tmux") is None, reason="tmux is not installed")


@dataclass
class TeleopPane(Pane):
    """A command in a detached tmux pane; around it, the pane's shell records the terminal mode and exit status."""

    records: Path

    @classmethod
    def run(cls, env: dict[str, str], tmp: Path, command: list[str]) -> TeleopPane:
        """``command`` in a 100x30 pane with ``env``, started in the repository; the records go to ``tmp``."""
        before, after, status = tmp / "stty.before", tmp / "stty.after", tmp / "status"
        # The shell traps Ctrl-C (instead of dying of it) so that it can record what follows.
        script = (f"trap true INT; stty -g > {before}; {shlex.join(command)}; echo $? > {status}; "
                  f"stty -g > {after}; sleep 600")
        return cls.start("teleop", 100, 30, ["sh", "-c", script], env=env, cwd=REPO, records=tmp)

    @property
    def before(self) -> Path:
        """The file with ``stty -g`` of the terminal before the command ran."""
        return self.records / "stty.before"

    @property
    def after(self) -> Path:
        """The file with ``stty -g`` of the terminal after the command ended."""
        return self.records / "stty.after"

    @property
    def status(self) -> Path:
        """The file with the command's exit status."""
        return self.records / "status"

    def terminal_mode(self) -> str:
        """``stty -a`` of the pane's terminal, read from outside."""
        tty = self.tmux("display-message", "-p", "-t", self.session, "#{pane_tty}").strip()
        return subprocess.run(["stty", "-a", "-F", tty], capture_output=True, text=True, check=True).stdout

    def exit_status(self) -> int:
        """Wait for the command to end; its exit status."""
        wait_until(lambda: self.status.exists() and self.status.read_text().strip() != "", "the teleop to exit")
        wait_until(lambda: self.after.exists() and self.after.read_text().endswith("\n"),
                   "the terminal mode after exit")
        return int(self.status.read_text())


@pytest.fixture
def watcher(rostui_core: Any) -> Iterator[Watcher]:
    """A test node on the live master."""
    w = Watcher()
    try:
        yield w
    finally:
        w.close()


def start_teleop(env: dict[str, str], tmp: Path, *args: str) -> TeleopPane:
    """`rostui run turtlesim turtle_teleop_key ARGS` in a tmux pane, banner shown."""
    pane = TeleopPane.run(env, tmp, rostui_cmd("run", "turtlesim", "turtle_teleop_key", *args))
    try:
        pane.wait_for_text(BANNER[-1])
    except AssertionError:
        screen = pane.screen()
        pane.close()
        raise AssertionError(f"the teleop did not show its banner:\n{screen}") from None
    return pane


def twist_values(msg: Any) -> tuple[float, float]:
    """``(linear.x, angular.z)`` of a Twist."""
    return msg.linear.x, msg.angular.z


def test_key_bindings_follow_ros() -> None:
    assert key_to_command("up") == (2.0, 0.0)
    assert key_to_command("down") == (-2.0, 0.0)
    assert key_to_command("left") == (0.0, 2.0)
    assert key_to_command("right") == (0.0, -2.0)
    assert key_to_command("up", scale_linear=0.5) == (0.5, 0.0)
    assert key_to_command("x") is None


def test_escape_sequences_decode_whole_and_split() -> None:
    decoder = KeyDecoder()
    assert decoder.feed(b"\x1b[A\x1bOD\x1b[1;5C") == ["up", "left", "right"]
    assert decoder.feed(b"\x1b") == [] and decoder.feed(b"[") == [] and decoder.feed(b"B") == ["down"]
    assert decoder.feed(b"\x1b[200~q") == ["q"]  # an unknown sequence is swallowed whole
    assert decoder.feed(b"\x1b") == [] and decoder.flush() == ["escape"]
    assert decoder.feed(b"A") == ["A"]  # a capital A is not the Up key


def test_arrow_keys_publish_twist_and_velocity(watcher: Watcher, ros_env: dict[str, str], tmp_path: Path) -> None:
    twists = watcher.record("/turtle1/cmd_vel", "geometry_msgs/Twist")
    velocities = watcher.record("/turtle1/command_velocity", "turtlesim/Velocity")
    pane = start_teleop(ros_env, tmp_path)
    try:
        screen = pane.screen()
        for line in BANNER:
            assert line in screen
        assert "-icanon" in pane.terminal_mode().split()
        twists.wait_connected()
        velocities.wait_connected()
        pane.keys("Up")
        twists.wait_for_count(1)
        pane.keys("Left")
        twists.wait_for_count(2)
        pane.keys("Down")
        twists.wait_for_count(3)
        pane.keys("Right")
        twists.wait_for_count(4)
        velocities.wait_for_count(4)
        pane.keys("x")  # not bound: nothing is published
        pane.keys("q")
        assert pane.exit_status() == 0
        assert [twist_values(m) for m in twists.messages] == [(2.0, 0.0), (0.0, 2.0), (-2.0, 0.0), (0.0, -2.0)]
        assert [(m.linear, m.angular) for m in velocities.messages] == [
            (2.0, 0.0), (0.0, 2.0), (-2.0, 0.0), (0.0, -2.0)]
        assert pane.before.read_text() == pane.after.read_text()
        assert not watcher.lookup_node("/teleop_turtle")
    finally:
        pane.close()


def test_scale_param_and_remaps(watcher: Watcher, ros_env: dict[str, str], tmp_path: Path) -> None:
    twists = watcher.record("/foo/cmd_vel", "geometry_msgs/Twist")
    velocities = watcher.record("/foo/command_velocity", "turtlesim/Velocity")
    pane = start_teleop(ros_env, tmp_path, "_scale_linear:=0.5", "turtle1/cmd_vel:=/foo/cmd_vel",
                        "turtle1/command_velocity:=/foo/command_velocity")
    try:
        twists.wait_connected()
        velocities.wait_connected()
        pane.keys("Up")
        pane.keys("Left")
        twists.wait_for_count(2)
        velocities.wait_for_count(2)
        assert [twist_values(m) for m in twists.messages] == [(0.5, 0.0), (0.0, 2.0)]
        assert [(m.linear, m.angular) for m in velocities.messages] == [(0.5, 0.0), (0.0, 2.0)]
        assert watcher.get_param("/teleop_turtle/scale_linear") == 0.5
        pane.keys("q")
        assert pane.exit_status() == 0
    finally:
        pane.close()


def test_book_reverse_remap_drives_the_turtle_backwards(watcher: Watcher, ros_env: dict[str, str],
                                                        tmp_path: Path) -> None:
    """The book's reverse.launch by hand: Up through reverse_cmd_vel moves the turtle backwards.

    turtlesim also listens on cmd_vel, so the teleop must not send its Twist
    around the translator that listens on the book's topic.
    """
    sim = start_headless_sim(ros_env, tmp_path, "turtle1/command_velocity:=turtle1/command_velocity_reversed")
    reverse = Program(ros_env, tmp_path, "agitr", "reverse_cmd_vel")
    items: list[Program | Watcher] = [sim, reverse]
    twists = watcher.record("/turtle1/cmd_vel", "geometry_msgs/Twist")
    reversed_commands = watcher.record("/turtle1/command_velocity_reversed", "turtlesim/Velocity")
    poses = watcher.record("/turtle1/pose", "turtlesim/Pose")
    pane = start_teleop(ros_env, tmp_path)
    try:
        start = poses.wait_for_count(1)[-1]
        wait_until(lambda: "/reverse_velocity" in watcher.connected_subscribers(
            "/teleop_turtle", "/turtle1/command_velocity") and "/turtlesim" in watcher.connected_subscribers(
            "/teleop_turtle", "/turtle1/cmd_vel"), "the book's graph to connect")
        pane.keys("Up")
        reversed_commands.wait_for(lambda m: m.linear == -2.0, "a reversed command")
        poses.wait_for(lambda p: p.x < start.x - 0.5, "the turtle to back up")
        assert all(p.x <= start.x + 1e-6 for p in poses.messages), "the turtle went forward"
        assert twists.messages == [], "the teleop sent a Twist around reverse_cmd_vel"
        pane.keys("q")
        assert pane.exit_status() == 0
    finally:
        pane.close()
        stop_all(items)


def test_ctrl_c_restores_the_terminal(watcher: Watcher, ros_env: dict[str, str], tmp_path: Path) -> None:
    pane = start_teleop(ros_env, tmp_path)
    try:
        wait_until(lambda: watcher.lookup_node("/teleop_turtle"), "the teleop node to register")
        pane.keys("C-c")
        pane.exit_status()
        assert pane.before.read_text() == pane.after.read_text()
        wait_until(lambda: not watcher.lookup_node("/teleop_turtle"), "the teleop node to unregister")
    finally:
        pane.close()


def test_bad_scale_is_one_line_and_exit_1(watcher: Watcher, ros_env: dict[str, str], tmp_path: Path) -> None:
    pane = TeleopPane.run(ros_env, tmp_path, rostui_cmd("run", "turtlesim", "turtle_teleop_key", "_scale_linear:=fast"))
    try:
        assert pane.exit_status() == 1
        assert "parameter ~scale_linear must be a number, got 'fast'" in pane.screen()
        assert pane.before.read_text() == pane.after.read_text()
    finally:
        pane.close()


def test_stdin_not_a_terminal_is_one_line_and_exit_1(ros_env: dict[str, str]) -> None:
    result = subprocess.run(rostui_cmd("run", "turtlesim", "turtle_teleop_key"), env=ros_env, cwd=REPO,
                            stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=DEADLINE)
    assert result.returncode == 1
    assert result.stdout == ""
    assert result.stderr.splitlines() == [
        "turtle_teleop_key: standard input is not a terminal; run it in a terminal to read the arrow keys"]


def test_rostui_teleop_topic_publishes_only_twist_there(watcher: Watcher, ros_env: dict[str, str],
                                                        tmp_path: Path) -> None:
    twists = watcher.record("/foo/cmd_vel", "geometry_msgs/Twist")
    pane = TeleopPane.run(ros_env, tmp_path, rostui_cmd("teleop", "/foo/cmd_vel"))
    try:
        pane.wait_for_text(BANNER[-1])
        twists.wait_connected()
        pane.keys("Down")
        twists.wait_for_count(1)
        assert twist_values(twists.messages[0]) == (-2.0, 0.0)
        wait_until(lambda: watcher.lookup_node("/teleop_turtle"), "the teleop node")
        publications = watcher.engine.run(watcher.node.master_call("getSystemState"))[0]
        published = {topic for topic, nodes in publications if "/teleop_turtle" in nodes}
        assert published == {"/foo/cmd_vel", "/rosout"}
        pane.keys("q")
        assert pane.exit_status() == 0
    finally:
        pane.close()
