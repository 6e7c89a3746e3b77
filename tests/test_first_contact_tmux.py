"""Issue 31, first contact: what a new user tripped on, each seen again in a real terminal (tmux).

Every test types the command the tester typed into a shell in a detached tmux pane and reads the
screen, against a `rostui core` master of its own.
"""

from __future__ import annotations

import re
import signal
from pathlib import Path
from typing import Any
from xmlrpc.client import ServerProxy

from cli_helpers import rostui
from conftest import wait_until
from tmux_helpers import Pane, rostui_line, shell_pane

EXIT_MARK = "FIRST_CONTACT_EXIT="


def run_to_exit(pane: Pane, env: dict[str, str], *args: str) -> str:
    """Type `rostui ARGS` into the pane's shell and wait for it to end; the screen then."""
    pane.clear()
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
            pane.clear()
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
        assert "[ WARN] /teleop_turtle is already running (turtlesim's arrow keys" in teleop.screen().replace("\n", "")
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


def write_one_topic(path: Path, type_name: str, md5sum: str, definition: str, payloads: list[bytes]) -> Path:
    """A bag (by its extension: .bag or MCAP) of ``payloads`` on /thing, 0.1 s apart, recorded as ``type_name``."""
    from rostui.core.bag.files import open_writer
    from rostui.core.bag.model import Connection

    writer = open_writer(str(path))
    writer.add_connection(Connection(id=0, topic="/thing", type=type_name, md5sum=md5sum, definition=definition))
    for i, payload in enumerate(payloads):
        writer.write(0, 1_700_000_000_000_000_000 + i * 100_000_000, payload)
    writer.close()
    return path


#: The md5sum of a definition with no fields.
EMPTY_MD5 = "d41d8cd98f00b204e9800998ecf8427e"


def test_no_silent_empty_results_from_odd_bags(tmp_path: Path, ros_env: dict[str, str]) -> None:
    """5: a definition with no fields over messages that hold bytes, a bag cut before its first message, and a
    real empty message each say what they are in `topic echo -b` and in bag view's inspector."""
    hollow = write_one_topic(tmp_path / "hollow.bag", "my_pkg/Thing", EMPTY_MD5, "\n", [b"\x03\x00\x00\x00abc"] * 3)
    empty = write_one_topic(tmp_path / "empty.mcap", "std_msgs/Empty", EMPTY_MD5, "", [b""] * 3)
    whole = write_one_topic(tmp_path / "whole.bag", "std_msgs/Int32", "da5909fbe378aeaf85e547e830cc1bb7",
                            "int32 data\n", [bytes(4)] * 200)
    cut = tmp_path / "cut.bag"
    cut.write_bytes(whole.read_bytes()[:whole.stat().st_size // 2])
    with shell_pane("odd_bags", 240, 30) as pane:  # wide: the lines quote long paths
        screen = run_to_exit(pane, ros_env, "topic", "echo", "-b", str(hollow), "/thing")
        assert exit_status(screen) == 1 and "its definition has no fields, but the message holds 7 bytes" in screen
        screen = run_to_exit(pane, ros_env, "topic", "echo", "-b", str(cut), "/thing")
        assert exit_status(screen) == 1 and "was cut short and holds no messages" in screen, screen
        screen = run_to_exit(pane, ros_env, "topic", "echo", "-b", str(empty), "/thing")
        assert exit_status(screen) == 0 and screen.count("---") == 3, screen
        for bag, shown in ((hollow, "its definition has no fields, but the message holds 7 bytes"),
                           (empty, "(no fields: std_msgs/Empty is an empty message)")):
            pane.clear()
            pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "view", str(bag)))
            pane.wait_until(lambda: "/thing" in pane.screen() and "PAUSED" in pane.screen(), "bag view")
            pane.keys("End")
            pane.wait_until(lambda: shown in pane.screen().replace("\n", ""), f"the inspector to say {shown!r}")
            pane.keys("q")
            pane.wait_until(lambda: exit_status(pane.screen()) == 0, "bag view to quit")


def test_bag_play_status_fits_an_80_column_terminal_and_short_bags_get_readable_ticks(
        tmp_path: Path, rostui_core: Any, ros_env: dict[str, str]) -> None:
    """6: at 80 columns `bag play`'s status line (rosbag's is about 90) is rewritten in place instead of wrapping
    and scrolling the terminal, and the terminal is left blocking as the shell had it; bag view's ruler over a 50 ms bag reads in milliseconds, not `0.0s 0.0s`."""
    from bag_view_helpers import write_counts

    long_bag = write_counts(tmp_path / "counts.bag", 400)  # 4 s
    with shell_pane("play80", 80, 24) as pane:
        pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "play", str(long_bag)))
        pane.wait_until(lambda: "Duration: 1." in pane.screen(), "a second of playing")
        pane.wait_until(lambda: "Duration: 2." in pane.screen(), "two seconds of playing")
        rows = [line for line in pane.screen().splitlines() if "Bag Time:" in line]
        assert len(rows) == 1, pane.screen()
        pane.wait_until(lambda: exit_status(pane.screen()) == 0, "bag play to finish")
        pane.type("echo SHELL_READ_AGAIN")  # the shell reads its next line from the terminal bag play used
        pane.wait_until(lambda: pane.screen().count("SHELL_READ_AGAIN") == 2, "the shell's next command")
        assert "NDELAY" not in pane.screen(), pane.screen()  # stdin left non-blocking: "turning off NDELAY mode"
    short_bag = write_counts(tmp_path / "short.mcap", 6)  # 50 ms
    with shell_pane("ticks", 100, 24) as pane:
        pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "view", str(short_bag)))
        pane.wait_until(lambda: "┊" in pane.screen(), "bag view's ruler")
        ruler = next(line for line in pane.screen().splitlines() if "┊" in line)
        labels = re.findall(r"┊(\S+)", ruler)
        assert len(labels) >= 3 and len(set(labels)) == len(labels) and all(l.endswith("ms") for l in labels), ruler
        pane.keys("q")
        pane.wait_until(lambda: exit_status(pane.screen()) == 0, "bag view to quit")


def test_bag_record_writes_rosbags_format_and_says_so(tmp_path: Path, rostui_core: Any,
                                                      ros_env: dict[str, str]) -> None:
    """8: `bag record -a` writes what a teammate's rosbag opens (.bag, named by date and time as rosbag names
    it), and says the file and its format when it starts and when it ends; --mcap is one flag away."""
    import subprocess
    import sys

    from conftest import need_command

    talker = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "pub", "-r", "20", "/chatter",
                               "std_msgs/String", "data: hi"], env=ros_env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    try:
        with shell_pane("record", 160, 20) as pane:
            pane.type(f"cd {tmp_path}")
            for flags, ending in (((), ".bag'."), (("--mcap",), ".mcap' (MCAP, not readable")):
                pane.clear()
                pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "record", "-a", *flags))
                pane.wait_until(lambda: ending in pane.screen(), f"the start line to say {ending!r}")
                pane.wait_until(lambda: re.search(r": [1-9]\d* msgs, ", pane.screen()) is not None,
                                "the status line to count /chatter's messages")
                pane.keys("C-c")
                pane.wait_until(lambda: exit_status(pane.screen()) == 0, "bag record to end on Ctrl-C")
                status = [line for line in pane.screen().splitlines() if " msgs, " in line]
                assert status and status[-1].rstrip().endswith("^C"), pane.screen()  # the echo fits the line
                said = "rosbag v2.0 .bag" if not flags else "MCAP, not readable by rosbag"
                assert re.search(rf"Recorded \d+ messages to \d{{4}}(-\d\d){{5}}\.(bag|mcap) \({said}", pane.screen())
    finally:
        talker.terminate()
        talker.wait(10)
    bags, mcaps = list(tmp_path.glob("*.bag")), list(tmp_path.glob("*.mcap"))
    assert len(bags) == 1 and len(mcaps) == 1, list(tmp_path.iterdir())
    need_command("rosbag")
    theirs = subprocess.run(["rosbag", "info", str(bags[0])], capture_output=True, text=True, timeout=120)
    assert theirs.returncode == 0 and "/chatter" in theirs.stdout, theirs.stderr


def test_quitting_the_turtlesim_that_hosts_the_master_says_who_loses_it(ros_env: dict[str, str]) -> None:
    """9: with a talker on the master `rostui turtlesim` started, q says the talker uses it and quits on a second
    q; the shell then reads which nodes were left without a master."""
    import subprocess
    import sys

    with shell_pane("host", 200, 30) as pane:  # wide: the farewell line names a long node name
        pane.type(rostui_line(ros_env, EXIT_MARK, "turtlesim"))
        pane.wait_until(lambda: "embedded master" in pane.screen() and "turtle1 x" in pane.screen(), "turtlesim")
        talker = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "pub", "-r", "5", "/chatter",
                                   "std_msgs/String", "data: hi"], env=ros_env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            names: list[str] = []

            def talker_listed() -> bool:
                names[:] = [n for n in rostui(["node", "list"], ros_env).stdout.split() if n.startswith("/rostopic")]
                return bool(names)
            wait_until(talker_listed, "the talker on turtlesim's master")
            pane.keys("q")
            pane.wait_until(lambda: f"{names[0]} use the master turtlesim started: q again quits" in pane.screen(),
                            "turtlesim to say the talker uses its master")
            assert exit_status(pane.screen()) is None, "one q quit turtlesim"
            pane.keys("q")
            pane.wait_until(lambda: exit_status(pane.screen()) == 0, "turtlesim to quit on the second q")
            said = pane.screen().replace("\n", "")
            assert f"{names[0]} is left without a master" in said, pane.screen()
        finally:
            talker.terminate()
            talker.wait(10)


def test_wtf_resolves_localhost_without_etc_hosts_and_help_wraps_at_the_terminal(
        rostui_core: Any, ros_env: dict[str, str]) -> None:
    """9: on a machine whose resolver knows no localhost (a root with no /etc/hosts; tests/no_localhost.py),
    `rostui wtf` reaches ROS_MASTER_URI=http://localhost:PORT as every other command does; `bag view --help`
    at 80 columns wraps its paragraphs at the terminal's width, not also at the docstring's line ends."""
    import shlex
    import sys

    from conftest import REPO

    port = ros_env["ROS_MASTER_URI"].rstrip("/").rsplit(":", 1)[1]
    env = {**ros_env, "ROS_MASTER_URI": f"http://localhost:{port}/"}
    line = rostui_line(env, EXIT_MARK, "wtf").replace(
        f"{shlex.quote(sys.executable)} -m rostui", f"{shlex.quote(sys.executable)} {REPO / 'tests' / 'no_localhost.py'}")
    assert "no_localhost.py wtf" in line
    with shell_pane("nohosts", 160, 30) as pane:
        pane.type(line)
        pane.wait_until(lambda: exit_status(pane.screen()) is not None, "rostui wtf")
        screen = pane.screen()
        assert "cannot resolve" not in screen and "Found 0 error(s)" in screen, screen
    with shell_pane("help80", 80, 60) as pane:
        pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "view", "--help").replace("; echo", " | head -12; echo", 1))
        pane.wait_until(lambda: "Keys:" in pane.screen(), "bag view's help")
        paragraph = pane.screen().split("Keys:", 1)[1].split("\n\n", 1)[0]
        rows = [row.rstrip() for row in ("Keys:" + paragraph).splitlines()]
        assert all(len(row) > 60 for row in rows[:-1]), "a line ends mid-paragraph:\n" + "\n".join(rows)


def make_package(folder: Path, name: str, scripts: dict[str, str]) -> Path:
    """A package ``name`` in ``folder`` (package.xml) with executable shell scripts ``{file: text printed}``."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f'<?xml version="1.0"?>\n<package format="2"><name>{name}</name>'
                                        "<version>0.0.0</version><description>test</description>"
                                        "<maintainer email='a@b.c'>a</maintainer><license>BSD</license>"
                                        "</package>\n")
    for file, said in scripts.items():
        script = folder / file
        script.write_text(f"#!/bin/sh\necho {said}\n")
        script.chmod(0o755)
    return folder


def test_run_and_launch_take_the_installed_executable_first_as_rosrun_and_roslaunch_do(
        tmp_path: Path, ros_env: dict[str, str]) -> None:
    """10: a package both in the workspace (ROS_PACKAGE_PATH) and installed in a catkin prefix (lib/<pkg>, as
    Debian's /usr/lib/<pkg>): `rostui run` and `rostui launch` start the installed node, as rosrun and
    roslaunch (roslib's find_node) do; a node only the workspace has still comes from the workspace."""
    from conftest import need_command

    need_command("rosrun")
    prefix = tmp_path / "install"
    (prefix / ".catkin").parent.mkdir(parents=True)
    (prefix / ".catkin").write_text("")
    make_package(prefix / "share" / "twice_pkg", "twice_pkg", {})
    make_package(prefix / "lib" / "twice_pkg", "twice_pkg", {"node": "from-the-installed-prefix"})
    (prefix / "lib" / "twice_pkg" / "package.xml").unlink()
    make_package(tmp_path / "ws" / "src" / "twice_pkg", "twice_pkg",
                 {"node": "from-the-workspace", "only_here": "only-in-the-workspace"})
    launch = tmp_path / "twice.launch"
    launch.write_text('<launch><node pkg="twice_pkg" type="node" name="twice" output="screen"/></launch>\n')
    env = {**ros_env, "ROS_PACKAGE_PATH": str(tmp_path / "ws" / "src"), "CMAKE_PREFIX_PATH": str(prefix)}
    exports = " ".join(f"{k}={v}" for k, v in env.items() if k in ("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH"))
    with shell_pane("twice", 200, 40) as pane:
        pane.type(f"export {exports}")
        lists = []
        for command in ("rosrun twice_pkg node", rostui_line(env, EXIT_MARK, "run", "twice_pkg", "node")):
            pane.clear()
            pane.type(command)
            pane.wait_until(lambda: "#?" in pane.screen(), f"{command.split(';')[0]} to ask which executable")
            lists.append(re.findall(r"^\d\) (\S+)$", pane.screen(), re.MULTILINE))
            pane.type("1")
            pane.wait_until(lambda: "from-the-installed-prefix" in pane.screen(), "the installed node, picked first")
        assert lists[0] == lists[1] and "install/lib/twice_pkg/node" in lists[1][0], lists
        screen = run_to_exit(pane, env, "run", "twice_pkg", "only_here")
        assert "only-in-the-workspace" in screen and exit_status(screen) == 0, screen
        pane.clear()
        pane.type(rostui_line(env, EXIT_MARK, "launch", str(launch)))
        pane.wait_until(lambda: "from-the-installed-prefix" in pane.screen(), "the launched node's line")
        assert "from-the-workspace" not in pane.screen(), pane.screen()
        pane.keys("C-c")
        pane.wait_until(lambda: exit_status(pane.screen()) is not None, "the launch to end")


SUMMARY_LAUNCH = """<launch>
  <param name="speed" value="2.5"/>
  <param name="long_text" value="a string that is far longer than twenty"/>
  <group ns="robot">
    <node pkg="rosbag" type="play" name="player" args="--help"/>
    <node pkg="nope_pkg" type="nope" name="bad"/>
  </group>
  <node pkg="rosbag" type="record" name="rec" args="--help"/>
</launch>
"""


def summary_block(text: str) -> list[str]:
    """The lines from SUMMARY to the blank line that ends NODES, with /rosdistro's and /rosversion's values
    (each launcher's own) left out."""
    lines = text.splitlines()
    start = lines.index("SUMMARY")
    end = next(i for i in range(lines.index("NODES", start), len(lines)) if not lines[i].strip())
    return [re.sub(r"^( \* /ros(distro|version)): .*$", r"\1: ...", line) for line in lines[start:end]]


def test_launch_prints_roslaunchs_summary_and_starts_the_nodes_beside_a_bad_one(
        tmp_path: Path, ros_env: dict[str, str]) -> None:
    """7: the SUMMARY / PARAMETERS / NODES block roslaunch users read before anything runs, line for line as
    Debian's roslaunch prints it; a node whose package does not exist is reported and the others start."""
    import subprocess

    from conftest import free_port, need_command

    need_command("roslaunch")
    launch = tmp_path / "summary.launch"
    launch.write_text(SUMMARY_LAUNCH)
    theirs_env = {**ros_env, "ROS_MASTER_URI": f"http://127.0.0.1:{free_port()}", "ROS_HOME": str(tmp_path / "rl")}
    out = tmp_path / "roslaunch.out"
    with out.open("w") as sink:
        theirs = subprocess.Popen(["roslaunch", str(launch)], env=theirs_env, stdout=sink, stderr=subprocess.STDOUT,
                                  stdin=subprocess.DEVNULL)
    try:
        wait_until(lambda: "process[rec-4]: started" in out.read_text(), "roslaunch to start the last node")
    finally:
        theirs.send_signal(signal.SIGINT)
        theirs.wait(60)
    plain = re.sub(r"\x1b\[[0-9;]*m|\x1b\]2;[^\x07]*\x07", "", out.read_text())
    expected = summary_block(plain)
    assert "    bad (nope_pkg/nope)" in expected, plain
    with shell_pane("summary", 120, 60) as pane:
        pane.type(rostui_line(ros_env, EXIT_MARK, "launch", str(launch)))
        pane.wait_until(lambda: "process[rec-3]: started" in pane.screen(), "the node after the bad one to start")
        screen = pane.screen()
        assert summary_block(screen) == expected, screen
        assert "ERROR: cannot launch node of type [nope_pkg/nope]" in screen
        assert "process[robot-player-1]: started" in screen
        pane.keys("C-c")
        pane.wait_until(lambda: exit_status(pane.screen()) is not None, "the launch to end on Ctrl-C")


def test_bag_view_says_it_publishes_nothing_on_a_line_of_its_own_at_80_columns(
        tmp_path: Path, ros_env: dict[str, str]) -> None:
    """1, as the tutorial walk at 80x24 saw it: the header's "not publishing: t publishes the selected topic, a
    every topic" wrapped after "t", away from what t does; too long for the header's line, it takes its own."""
    from bag_view_helpers import write_counts

    bag = write_counts(tmp_path / "square.bag", 40)
    with shell_pane("view80", 80, 24) as pane:
        pane.type(rostui_line(ros_env, EXIT_MARK, "bag", "view", str(bag)))
        pane.wait_until(lambda: "PAUSED" in pane.screen(), "bag view")
        lines = [line.strip() for line in pane.screen().splitlines()]
        assert "not publishing: t publishes the selected topic, a every topic" in lines, pane.screen()
        pane.keys("q")
        pane.wait_until(lambda: exit_status(pane.screen()) == 0, "bag view to quit")
