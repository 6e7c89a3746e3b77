"""rospy's SubscribeListener on a latched topic, under rostui's rospy and Debian's: the same order on the wire.

A subscriber first gets what ``peer_subscribe`` sends it alone, then the latched message, which rospy
has made that same message; leaving calls ``peer_unsubscribe`` with no subscriber left. The script is
tests/python_compat/rospy_latched_listener.py.
"""

from __future__ import annotations

import subprocess

from conftest import REPO
from test_rospy_tutorials import MASTERS, SIDES, Start, envs, generated, start  # noqa: F401  (fixtures)

SCRIPT = REPO / "tests" / "python_compat" / "rospy_latched_listener.py"


@MASTERS
def test_peer_publish_then_latched_message(any_master: str, start: Start,
                                                       envs: dict[str, dict[str, str]]) -> None:
    """rostopic echo gets "welcome" (peer_publish), then again (now latched); the script sees it come and go."""
    said = {}
    for side in SIDES:
        talker = start(side, SCRIPT, name=f"talker-{side}")
        talker.wait_for("ready")
        echo = subprocess.run(["rostopic", "echo", "-n", "2", "/latched"], env=envs["real"],
                              capture_output=True, text=True, timeout=60)
        talker.wait_for("unsubscribed")
        said[side] = (echo.stdout, talker.interrupt())
    assert said["shim"] == said["real"]
    assert said["real"] == ('data: "welcome"\n---\ndata: "welcome"\n---\n',
                            "ready\nsubscribed /latched\nunsubscribed /latched 0\n")

