"""What the action tests share: actionlib_tutorials' Fibonacci server, unmodified, under Debian's actionlib
(``real``) or rostui's (``shim``) on rostui core, and rostui's action commands knowing its types (the tutorial and its
messages as test_actionlib_scripts.py runs them; sources: tests/python_compat/real/SOURCES.md).
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Iterator

from conftest import rostui_cmd, wait_until
from rospy_scripts import Running, script_command
from test_actionlib_scripts import PACKAGE, TUTORIALS


def rostui_action(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """`rostui action ARGS` knowing actionlib_tutorials' types."""
    return subprocess.run(rostui_cmd("action", *args), env=env, capture_output=True, text=True, timeout=90)


def fibonacci_server(side: str, ros_env: dict[str, str], tutorials_python: Path, log: Path) -> Iterator[dict[str, str]]:
    """The tutorial's server (node /fibonacci) under ``side`` while the generator runs; it yields the environment
    rostui's tools get (actionlib_tutorials on ROS_PACKAGE_PATH), once the server is listed."""
    base = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    ours = dict(base, ROS_PACKAGE_PATH=str(TUTORIALS))
    server_env = ours if side == "shim" else dict(base, PYTHONPATH=os.pathsep.join(
        filter(None, [str(tutorials_python), base.get("PYTHONPATH")])))
    server = Running(script_command(side, PACKAGE / "scripts" / "fibonacci_server.py"), server_env, log)
    try:
        wait_until(lambda: rostui_action(ours, "list").stdout == "/fibonacci\n", "the server listed")
        yield ours
    finally:
        server.interrupt()
