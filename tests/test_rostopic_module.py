"""The rostopic and rosservice Python modules, and genpy's fill_message_args, answer as Debian's do.

tests/python_compat/own/topic_service_lookups.py (written for this test) publishes an Odometry and offers a
Trigger service, then asks get_topic_class for the topic, for field paths into it (``/odom/pose/pose``),
for a missing field and a missing topic; asks rosservice for the service's class and type (by probing the
service) and for a missing one; and fills a message from ``rostopic pub``-style arguments. It runs under
Debian's rospy and under `rostui python`, on rostui core and on a real roscore: the same lines.
"""

from __future__ import annotations

import subprocess

import pytest

from conftest import REPO, SYSTEM_PYTHON, have_rospy, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "python_compat" / "own" / "topic_service_lookups.py"


@pytest.mark.parametrize("any_master", ["rostui", "real"], indirect=True)
def test_lookups_answer_as_debians(any_master: str, ros_env: dict[str, str]) -> None:
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    theirs = subprocess.run([SYSTEM_PYTHON, str(SCRIPT)], env=env, capture_output=True, text=True, timeout=120)
    ours = subprocess.run(rostui_cmd("python", "--rostui", str(SCRIPT)), env=env, capture_output=True, text=True,
                          timeout=120)
    assert theirs.returncode == 0, theirs.stderr
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout.splitlines() == theirs.stdout.splitlines()
    assert "/odom/twist/twist/angular/z -> nav_msgs/Odometry /odom -0.25" in ours.stdout
