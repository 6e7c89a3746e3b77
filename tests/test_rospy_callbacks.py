"""rospy's Subscriber callbacks under rostui's rospy run as under Debian's: on threads of their own.

tests/python_compat/rospy_callbacks.py makes a Publisher and sleeps inside a callback, and has a callback
that raises; both rospys print the same `= ` lines, and log the failing callback as rospy does.
"""

from __future__ import annotations

import re
import subprocess

import pytest

from conftest import REPO, SYSTEM_PYTHON, have_rospy, need_peer, rostui_cmd

SCRIPT = REPO / "tests" / "python_compat" / "rospy_callbacks.py"


@pytest.mark.parametrize("any_master", ["rostui", "real"], indirect=True)
def test_callbacks_block_and_fail_as_in_rospy(any_master: str, ros_env: dict[str, str]) -> None:
    """Not on the main thread; a Publisher made and a sleep inside a callback; a raising callback logged."""
    need_peer(have_rospy(), "rospy (Debian python3-rospy)")
    env = {k: v for k, v in ros_env.items() if k != "PYTHONPATH" and not k.startswith("ROSTUI_PYTHON")}
    seen = {}
    for side, cmd in (("real", [SYSTEM_PYTHON, str(SCRIPT)]), ("shim", rostui_cmd("python", "--rostui", str(SCRIPT)))):
        out = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
        assert out.returncode == 0, out.stdout + out.stderr
        said = sorted(line for line in out.stdout.splitlines() if line.startswith("= "))
        errors = [re.sub(r"^\[ERROR\] \[\d+\.\d+\]: ", "", re.sub(r" at 0x[0-9a-f]+", "", line))
                  for line in out.stderr.splitlines() if line.startswith("[ERROR]") or line.startswith("ValueError")]
        seen[side] = (said, errors)
    assert seen["shim"] == seen["real"]
    assert seen["shim"] == (["= chatter callback on the main thread: False", "= echoed: HELLO", "= heard back: True"],
                            ["bad callback: <function bad>", "ValueError: boom hello"])
