"""`rostui action list | info | send` against actionlib_tutorials' Fibonacci server, unmodified, under Debian's
actionlib (``real``) and under rostui's (``shim``); the tutorial and its messages as test_actionlib_scripts.py
runs them (sources: tests/python_compat/real/SOURCES.md). The server computes one number a second and checks for a
cancel between them, so a goal of order 3 takes about 2 s and a cancelled one ends PREEMPTED.
"""

from __future__ import annotations

import signal
from pathlib import Path
from typing import Any, Iterator

import pytest

from action_helpers import fibonacci_server, rostui_action
from conftest import rostui_cmd
from rospy_scripts import Running
from test_actionlib_scripts import TUTORIALS, tutorials_python  # noqa: F401  (fixture)


@pytest.fixture(params=["real", "shim"])
def fibonacci(request: pytest.FixtureRequest, rostui_core: Any, ros_env: dict[str, str], tutorials_python: Path,
              tmp_path: Path) -> Iterator[dict[str, str]]:
    """The tutorial's server (node /fibonacci) on rostui core, under Debian's actionlib and rostui's."""
    yield from fibonacci_server(str(request.param), ros_env, tutorials_python, tmp_path / "server.log")


def test_list_info_and_a_goal_to_the_end(fibonacci: dict[str, str]) -> None:
    listed = rostui_action(fibonacci, "list", "-v")
    assert listed.stdout == "/fibonacci [actionlib_tutorials/Fibonacci] served by /fibonacci\n", listed.stderr
    info = rostui_action(fibonacci, "info", "fibonacci")
    assert info.returncode == 0, info.stderr
    assert info.stdout.startswith("Action: /fibonacci\nType: actionlib_tutorials/Fibonacci\nServers:\n * /fibonacci\n"
                                  "Clients:\n None\n"), info.stdout
    for part in ("Goal (actionlib_tutorials/FibonacciGoal):\n  int32 order\n",
                 "Result (actionlib_tutorials/FibonacciResult):\n  int32[] sequence\n",
                 "Feedback (actionlib_tutorials/FibonacciFeedback):\n  int32[] sequence\n"):
        assert part in info.stdout, info.stdout
    sent = rostui_action(fibonacci, "send", "/fibonacci", "{order: 3}")
    assert sent.returncode == 0, sent.stdout + sent.stderr
    lines = sent.stdout.splitlines()
    assert lines[0].startswith("goal /rostui_action_") and lines[0].endswith(" sent to /fibonacci "
                                                                             "[actionlib_tutorials/Fibonacci]")
    assert "status: ACTIVE (This goal has been accepted by the simple action server)" in lines, lines
    assert lines[-1] == "goal SUCCEEDED"
    assert "feedback:\n  sequence: [0, 1, 1]\n---\nfeedback:\n  sequence: [0, 1, 1, 2]\n---" in sent.stdout
    assert "result:\n  sequence: [0, 1, 1, 2]\n" in sent.stdout
    for args, said in ((["{order: ["], "is not valid YAML"), (["{oder: 3}"], "oder"),
                       (["-t", "nope/Nope", "{}"], "ERROR: cannot load action type nope/Nope")):
        wrong = rostui_action(fibonacci, "send", "/fibonacci", *args)
        assert wrong.returncode == 1 and len(wrong.stderr.strip().splitlines()) == 1 and said in wrong.stderr, \
            wrong.stderr


@pytest.mark.parametrize("fibonacci", ["real"], indirect=True)
def test_ctrl_c_cancels_the_goal(fibonacci: dict[str, str], tmp_path: Path) -> None:
    sending = Running(rostui_cmd("action", "send", "/fibonacci", "20", "-q"), fibonacci, tmp_path / "send.log")
    try:
        sending.wait_for("status: ACTIVE")
        sending.proc.send_signal(signal.SIGINT)
        assert sending.proc.wait(timeout=60) == 130, sending.output()
    finally:
        sending.interrupt()
    out = sending.output()
    assert "cancelling the goal…" in out and out.rstrip().endswith("goal PREEMPTED"), out
    assert "feedback:" not in out, "-q prints no feedback"


def test_what_cannot_be_sent_is_one_line(rostui_core: Any, ros_env: dict[str, str]) -> None:
    env = dict(ros_env, ROS_PACKAGE_PATH=str(TUTORIALS))
    nothing = rostui_action(env, "send", "/nope", "{}")
    assert nothing.returncode == 1 and nothing.stderr.strip() == "ERROR: no action server /nope on the master"
    assert rostui_action(env, "list").stdout == ""
