"""tf2_ros.BufferClient under `rostui python` and under Debian's, both asking Debian's tf2 buffer server.

The server (tf2-tools' ``buffer_server``) hears two of Debian's static_transform_publishers (world -> robot and a
separate sea -> island); one probe script (tests/python_compat/own/buffer_client_probe.py) looks transforms up
through the server's action, simply and through a fixed frame, and asks for frames it cannot join or does not
know: it prints the same under both, on rostui core and on a real roscore.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import REPO, SYSTEM_PYTHON, need_peer, rostui_cmd
from rospy_scripts import Running

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
        outputs = []
        for command in ([SYSTEM_PYTHON, str(PROBE)], rostui_cmd("python", "--rostui", str(PROBE))):
            done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=120)
            assert done.returncode == 0, done.stdout + done.stderr
            outputs.append(done.stdout)
    finally:
        for helper in helpers:
            helper.interrupt()
    debian, ours = outputs
    assert ours.splitlines()[:2] == ["server True", "lookup world robot 1.000000 2.000000 3.000000 0.247404 "
                                     "0.000000 0.000000 0.968912"], ours  # roll 0.5: the 6 numbers are x y z yaw pitch roll
    assert "error LookupException True" in ours and "error ConnectivityException True" in ours, ours
    assert ours == debian
