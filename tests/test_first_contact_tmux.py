"""Issue 31, first contact: what a new user tripped on, each seen again in a real terminal (tmux).

Every test types the command the tester typed into a shell in a detached tmux pane and reads the
screen, against a `rostui core` master of its own.
"""

from __future__ import annotations

import re
from typing import Any
from xmlrpc.client import ServerProxy

from tmux_helpers import Pane, rostui_line, shell_pane

EXIT_MARK = "FIRST_CONTACT_EXIT="


def run_to_exit(pane: Pane, env: dict[str, str], *args: str) -> str:
    """Type `rostui ARGS` into the pane's shell and wait for it to end; the screen then."""
    pane.tmux("clear-history", "-t", pane.session)
    pane.type("clear")
    pane.type(rostui_line(env, EXIT_MARK, *args))
    pane.wait_until(lambda: exit_status(pane.screen()) is not None, f"`rostui {' '.join(args)}` to end")
    return pane.screen()


def exit_status(screen: str) -> int | None:
    """The status the shell echoed after the command (the typed line says ``$?`` there)."""
    found = re.search(rf"{EXIT_MARK}(\d+)", screen.replace("\n", ""))
    return int(found.group(1)) if found else None


def test_did_you_mean_offers_only_topics_that_exist_now(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """3: `/pose` was published once and is gone (the master keeps its type, as rosmaster does); a misspelt
    `/nope` gets no "did you mean /pose?", while a topic someone subscribes to now is still offered."""
    master = ServerProxy(ros_env["ROS_MASTER_URI"])
    master.registerPublisher("/gone", "/pose", "geometry_msgs/Pose2D", "http://127.0.0.1:9/")
    master.unregisterPublisher("/gone", "/pose", "http://127.0.0.1:9/")
    master.registerSubscriber("/listener", "/chatter", "std_msgs/String", "http://127.0.0.1:9/")
    assert ["/pose", "geometry_msgs/Pose2D"] in master.getTopicTypes("/test")[2]
    with shell_pane("did_you_mean", 100, 30) as pane:
        for command in ("info", "type"):
            screen = run_to_exit(pane, ros_env, "topic", command, "/nope")
            assert exit_status(screen) == 1 and "did you mean" not in screen, screen  # not "/pose?"
            screen = run_to_exit(pane, ros_env, "topic", command, "/chattr")
            assert "did you mean /chatter?" in screen and exit_status(screen) == 1, screen
        for command in ("echo", "hz"):
            pane.type("clear")
            pane.type(rostui_line(ros_env, EXIT_MARK, "topic", command, "/nope"))
            pane.wait_for_text("WARNING: topic [/nope] does not appear to be published yet")
            pane.keys("C-c")
            pane.wait_until(lambda: exit_status(pane.screen()) is not None, f"topic {command} to end on Ctrl-C")
            assert "did you mean" not in pane.screen(), pane.screen()


POSE = re.compile(r"turtle1 x (-?\d+\.\d+) y (-?\d+\.\d+)")


def turtle_x(pane: Pane) -> float:
    """turtle1's x as turtlesim's status line shows it (0 when it is not on screen)."""
    found = POSE.search(pane.screen())
    return float(found.group(1)) if found else 0.0


def test_a_second_teleop_says_it_took_the_arrow_keys_and_gives_them_back(ros_env: dict[str, str]) -> None:
    """2: `rostui teleop` beside `rostui turtlesim` takes the node name /teleop_turtle (ROS shuts the older
    node down); turtlesim's key line says its arrow keys are off, and once the teleop ends they drive again."""
    with shell_pane("sim", 100, 30) as sim, shell_pane("teleop", 80, 12) as teleop:
        sim.type(rostui_line(ros_env, EXIT_MARK, "turtlesim"))
        sim.wait_until(lambda: "turtle1 x 5.54" in sim.screen() and "↑↓←→ drive" in sim.screen(), "turtlesim")
        teleop.type(rostui_line(ros_env, EXIT_MARK, "teleop"))
        teleop.wait_until(lambda: "Use arrow keys to move the turtle." in teleop.screen(), "the teleop banner")
        sim.wait_until(lambda: "↑↓←→ off: another /teleop_turtle runs" in sim.screen(),
                       "turtlesim to say another teleop has the arrow keys' node")
        sim.keys("Up")
        teleop.keys("Up")
        sim.wait_until(lambda: turtle_x(sim) > 6.0, "the other teleop to drive turtle1")
        teleop.keys("C-c")
        teleop.wait_until(lambda: exit_status(teleop.screen()) is not None, "the teleop to end")
        sim.wait_until(lambda: "↑↓←→ drive" in sim.screen(), "turtlesim's arrow keys back")
        moved_to = turtle_x(sim)
        sim.keys("Up")
        sim.wait_until(lambda: turtle_x(sim) > moved_to + 0.5, "turtlesim's own arrow keys to drive again")
        sim.keys("q")
        sim.wait_until(lambda: exit_status(sim.screen()) == 0, "turtlesim to quit with status 0")
