"""diagnostic_updater's own example under `rostui python` and under Debian's python3-diagnostic-updater.

The example (tests/python_compat/real/diagnostics, sources in tests/python_compat/real/SOURCES.md) adds
function, method, composite and DiagnosticTask-subclass tasks, broadcasts, watches its ``topic1`` rate with a
HeaderlessTopicDiagnostic, forces an update, removes a task and then updates once a second. Debian's
``rostopic echo /diagnostics`` watches each run; from the topic watcher's first status on, the distinct
messages are the same under both (stamps, sequence numbers and measured values masked), on rostui core and on
a real roscore.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, SYSTEM_PYTHON, need_peer, wait_until
from rospy_scripts import Running, script_command

PACKAGE_PATH = REPO / "tests" / "python_compat" / "real" / "diagnostics"
EXAMPLE = PACKAGE_PATH / "diagnostic_updater" / "src" / "example.py"
WATCHER = "topic1 topic status"
MASKS = [
    (re.compile(r"^( *)(seq|secs|nsecs): +\d+$", re.M), r"\1\2: N"),  # rostopic aligns nsecs
    (re.compile(r'^( *value: ").*(")$', re.M), lambda m: m.group(1) + re.sub(r"-?\d+(\.\d+)?", "N", m.group(0)[len(m.group(1)):-1]) + '"'),
    (re.compile(r"Launch in -?\d+\.\d+ seconds"), "Launch in N seconds"),
]


def distinct_messages(echoed: str) -> set[str]:
    """The distinct masked messages rostopic echo printed, from the first one that holds the topic watcher's."""
    # rostopic echo says so while /diagnostics is not published yet; the line joins the first message it prints
    echoed = "\n".join(line for line in echoed.splitlines() if not line.startswith("WARNING: topic ["))
    blocks = [block.strip() for block in echoed.split("\n---")]
    first = next((i for i, block in enumerate(blocks) if WATCHER in block), len(blocks))
    found = set()
    for block in blocks[first:]:
        if block:
            for pattern, repl in MASKS:
                block = pattern.sub(repl, block)
            found.add(block)
    return found


def watch_example(side: str, env: dict[str, str], work: Path) -> set[str]:
    """Run the example while Debian's rostopic echo records /diagnostics; the distinct messages it saw."""
    work.mkdir()
    # rostopic echo subscribes once the topic is published; the example waits two seconds before it starts
    # watching topic1, the messages compared
    echo = Running(["rostopic", "echo", "/diagnostics"], env, work / "echo.log")
    example = None
    try:
        example = Running(script_command(side, EXAMPLE), env, work / "example.log")
        wait_until(lambda: echo.output().count(WATCHER) >= 5 or example.proc.poll() is not None,
                   lambda: f"five messages of the topic watcher; the example printed:\n{example.output()}", timeout=60)
    finally:
        if example is not None:
            said = example.interrupt()
            assert "Traceback" not in said, said
        echoed = echo.interrupt()
    return distinct_messages(echoed)


def test_example_publishes_what_it_publishes_under_debian(any_master: str, ros_env: dict[str, str],
                                                          tmp_path: Path) -> None:
    need_peer(subprocess.run([SYSTEM_PYTHON, "-c", "import diagnostic_updater"], capture_output=True).returncode == 0,
              "diagnostic_updater (Debian python3-diagnostic-updater)")
    env = {k: v for k, v in ros_env.items() if not k.startswith("ROSTUI_PYTHON")}
    env["ROS_PACKAGE_PATH"] = str(PACKAGE_PATH)
    debian = watch_example("real", env, tmp_path / "debian")
    ours = watch_example("shim", env, tmp_path / "rostui")
    joined = "\n".join(sorted(ours))
    assert 'message: "Node starting up"' in joined and 'message: "Frequency too high.; Too low"' in joined, joined
    assert 'name: "diagnostic_updater_example: Bound check"' in joined  # in the forced update, before its removal
    assert ours == debian
