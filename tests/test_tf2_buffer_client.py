"""tf2_ros.BufferClient under `rostui python` and under Debian's, both asking Debian's tf2 buffer server.

The server (tf2-tools' ``buffer_server``) hears two of Debian's static_transform_publishers (world -> robot and a
separate sea -> island); one probe script (tests/python_compat/own/buffer_client_probe.py) looks transforms up
through the server's action, simply and through a fixed frame, and asks for frames it cannot join or does not
know: it prints the same under both, on rostui core and on a real roscore. Where Debian's client met actionlib's
race (issue 206: its SimpleActionClient drops an answer that beats send_goal and times out), the probe marks the
line, and that line of Debian's is no reference: rostui's is checked against the server's known tree instead.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd
from rospy_scripts import Running

RACE_MARK = "[actionlib#206]"  # as buffer_client_probe.py marks a line made while Debian's client met the race
PROBE = REPO / "tests" / "python_compat" / "own" / "buffer_client_probe.py"
BUFFER_SERVER = Path("/usr/lib/tf2_ros/buffer_server")
STATIC_PUBLISHER = Path("/usr/lib/tf2_ros/static_transform_publisher")


def test_buffer_client_prints_what_it_prints_under_debian(any_master: str, ros_env: dict[str, str],
                                                          tmp_path: Path) -> None:
    need_peer(BUFFER_SERVER.is_file() and STATIC_PUBLISHER.is_file(), "tf2_ros's buffer_server (Debian tf2-tools)")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    helpers = [Running([str(BUFFER_SERVER)], env, tmp_path / "server.log"),
               Running([str(STATIC_PUBLISHER), "1", "2", "3", "0", "0", "0.5", "world", "robot",
                        "__name:=robot_tf"], env, tmp_path / "robot.log"),
               Running([str(STATIC_PUBLISHER), "0", "0", "1", "0", "0", "0", "sea", "island",
                        "__name:=island_tf"], env, tmp_path / "island.log")]
    try:
        runs = [subprocess.run(command, env=env, capture_output=True, text=True, timeout=120)
                for command in ([SYSTEM_PYTHON, str(PROBE)], rostui_cmd("python", "--rostui", str(PROBE)))]
    finally:
        for helper in helpers:
            helper.interrupt()
    for done in runs:
        assert done.returncode == 0, done.stdout + done.stderr
    debian, ours = (done.stdout.splitlines() for done in runs)
    report = "\n".join(["Debian's:", *debian, runs[0].stderr, "rostui's:", *ours, runs[1].stderr])
    assert RACE_MARK not in runs[1].stdout, report
    assert ours[:2] == ["server True", "lookup world robot 1.000000 2.000000 3.000000 0.247404 "
                        "0.000000 0.000000 0.968912"], report  # roll 0.5: the 6 numbers are x y z yaw pitch roll
    # the inverse: -(R^T t) for a roll of 0.5 about x
    assert ours[2] == "back robot world -1.000000 -3.193442 -1.673897 -0.247404 0.000000 0.000000 0.968912", report
    assert ours[3] == ours[2].replace("back", "full", 1), report
    assert [row.split(" error ")[1].split()[:2] for row in ours[4:7]] == [
        ["LookupException", "True"], ["ConnectivityException", "True"], ["InvalidArgumentException", "True"]], report
    assert ours[7] == "can True False True", report
    assert len(debian) == len(ours), report
    assert ours == [mine if RACE_MARK in theirs else theirs for theirs, mine in zip(debian, ours)], report
