"""A rospy script whose init_node waits for a master that does not answer, under `rostui python`.

Ctrl-C or SIGTERM during the wait ends it quietly, as rospy's does (the wait's ROSInterruptException is
raised in the script's thread, never on the engine's); a master that comes later ends the wait and the
script goes on to publish.
"""

from __future__ import annotations

import signal
import subprocess
import threading
from pathlib import Path

import pytest

from conftest import free_port, rostui_cmd, start_rostui_core, stop_process, wait_until

SCRIPT = """\
import rospy
from std_msgs.msg import String
pub = rospy.Publisher('chatter', String, queue_size=10)
rospy.init_node('talker', anonymous=True)
print("started", flush=True)
"""


def _start(tmp_path: Path, env: dict[str, str]) -> tuple[subprocess.Popen[str], list[str]]:
    script = tmp_path / "talker.py"
    script.write_text(SCRIPT)
    proc = subprocess.Popen(rostui_cmd("python", str(script)), env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    said: list[str] = []
    assert proc.stderr is not None
    threading.Thread(target=lambda: said.extend(proc.stderr), daemon=True).start()  # type: ignore[arg-type]
    wait_until(lambda: any("Unable to contact the master" in line for line in said), lambda: "".join(said))
    return proc, said


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_ends_the_wait(ros_env: dict[str, str], tmp_path: Path, signum: int) -> None:
    env = dict(ros_env, ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}/")
    proc, said = _start(tmp_path, env)
    try:
        proc.send_signal(signum)
        proc.wait(timeout=30)
    finally:
        stop_process(proc)
    assert "started" not in (proc.stdout.read() if proc.stdout else "")
    assert not any("Exception in thread" in line or "Traceback" in line for line in said), "".join(said)


def test_a_master_that_comes_later_ends_the_wait(ros_env: dict[str, str], tmp_path: Path) -> None:
    proc, said = _start(tmp_path, ros_env)
    core = start_rostui_core(ros_env)
    try:
        proc.wait(timeout=60)
        out = proc.stdout.read() if proc.stdout else ""
    finally:
        stop_process(proc)
        stop_process(core)
    assert proc.returncode == 0 and out.strip() == "started", "".join(said)
