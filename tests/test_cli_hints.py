"""The two hints of issue 21: a bare negative number gets one line that says to put `--` first (and the line that
works); a misspelt topic, service, node or parameter gets "did you mean …?" from the master's current names."""

from __future__ import annotations

import sys

import pytest
import typer.main

from rostui.cli.main import app
from rostui.cli.negative import bare_negative
from rostui.tools.suggest import closest_names, did_you_mean, with_namespaces

from cli_helpers import rostui
from interop_helpers import Peer, Spawn, rospy_peer, spawn, wait_for_publisher  # noqa: F401

ROOT = typer.main.get_command(app)


# ----------------------------------------------------------------------------- negative numbers
@pytest.mark.parametrize("argv, word, fixed", [
    ("param set /p -3", "-3", "rostui param set -- /p -3"),
    ("topic pub /x std_msgs/Float64 -1.5", "-1.5", "rostui topic pub -- /x std_msgs/Float64 -1.5"),
    ("topic pub /x std_msgs/Float64 -1.5 -r 2", "-1.5", "rostui topic pub -r 2 -- /x std_msgs/Float64 -1.5"),
    ("topic pub -1 /p geometry_msgs/Point 1 -2e-3 .5", "-2e-3", "rostui topic pub -1 -- /p geometry_msgs/Point 1 -2e-3 .5"),
    ("service call -v -.5", "-.5", "rostui service call -v -- -.5"),
    ("param set -v /p -3 --", "-3", "rostui param set -v -- /p -3"),
], ids=lambda v: v if " " in str(v) else None)
def test_bare_negative_is_found_with_the_line_that_works(argv: str, word: str, fixed: str) -> None:
    assert bare_negative(ROOT, argv.split()) == (word, fixed)


@pytest.mark.parametrize("argv", [
    "param set -- /p -3",                               # after --
    "topic pub -1 /x std_msgs/Float64 -- -1.5",         # -1 is pub's --once
    "topic hz -w -1 /x",                                # an option's value
    "bag play -s -1 x.bag",
    "topic pub --rate=-1 /x std_msgs/Float64 2",
    "service call /spawn 3 -3 0 Mikey",                 # service call reads no options after its first argument
    "run agitr hello -3",                               # nor does run
    "param set /p 3",
    "nothing here -3",                                  # no such command: Typer's own error
], ids=str)
def test_no_complaint_where_the_parser_reads_the_number_right(argv: str) -> None:
    assert bare_negative(ROOT, argv.split()) is None


def test_param_set_negative_needs_double_dash(rostui_core: object, ros_env: dict[str, str]) -> None:
    ours = rostui(["param", "set", "/offset", "-3"], ros_env)
    assert ours.returncode == 2 and ours.stdout == ""
    assert ours.stderr == ("ERROR: negative numbers need `--` first, as with rostopic and rosparam (-3 reads as an "
                           "option): rostui param set -- /offset -3\n")
    assert rostui(["param", "get", "/offset"], ros_env).returncode == 1  # nothing was set
    assert rostui(["param", "set", "--", "/offset", "-3"], ros_env).returncode == 0
    assert rostui(["param", "get", "/offset"], ros_env).stdout == "-3\n"


def test_topic_pub_negative_needs_double_dash(rostui_core: object, ros_env: dict[str, str], spawn: Spawn) -> None:
    ours = rostui(["topic", "pub", "/x", "std_msgs/Float64", "-1.5"], ros_env)
    assert ours.returncode == 2 and ours.stdout == "" and ours.stderr.count("\n") == 1
    assert ours.stderr.endswith("(-1.5 reads as an option): rostui topic pub -- /x std_msgs/Float64 -1.5\n")
    spawn([sys.executable, "-m", "rostui", "topic", "pub", "/x", "std_msgs/Float64", "--", "-1.5"], label="pub")
    echoed = rostui(["topic", "echo", "-n", "1", "/x"], ros_env)
    assert echoed.returncode == 0, echoed.stderr
    assert echoed.stdout == "data: -1.5\n---\n"


# ----------------------------------------------------------------------------- did you mean
def test_closest_names() -> None:
    names = ["/turtle1/pose", "/turtle1/cmd_vel", "/turtle1/color_sensor", "/rosout"]
    assert closest_names("/turtle1/pos", names) == ["/turtle1/pose"]
    assert did_you_mean("/turtle/pose", ["/turtle1/pose", "/turtle2/pose"]) == \
        "did you mean /turtle1/pose or /turtle2/pose?"
    assert did_you_mean("/nope", names) is None
    assert did_you_mean("/rosout", names) is None  # the name itself is no suggestion
    assert with_namespaces(["/a/b/c", "/d"]) == {"/a", "/a/b", "/a/b/c", "/d"}


def test_parameter_did_you_mean(any_master: str, ros_env: dict[str, str]) -> None:
    assert rostui(["param", "set", "/background_r", "255"], ros_env).returncode == 0
    assert rostui(["param", "set", "/turtlesim/speed", "1"], ros_env).returncode == 0
    for args in (["param", "get", "/backgrond_r"], ["param", "get", "--json", "/backgrond_r"]):  # fast path, Typer
        ours = rostui(args, ros_env)
        assert (ours.returncode, ours.stdout) == (1, "")
        assert ours.stderr == "ERROR: Parameter [/backgrond_r] is not set\ndid you mean /background_r?\n"
    ours = rostui(["param", "get", "/turtlesm"], ros_env)
    assert ours.stderr == "ERROR: Parameter [/turtlesm] is not set\ndid you mean /turtlesim?\n"
    ours = rostui(["param", "delete", "/backgrond_r"], ros_env)
    assert ours.returncode == 1
    assert ours.stderr == "ERROR: parameter [/backgrond_r] is not set\ndid you mean /background_r?\n"
    assert rostui(["param", "get", "/background_r"], ros_env).stdout == "255\n"  # nothing deleted


def test_node_did_you_mean(any_master: str, ros_env: dict[str, str]) -> None:
    ours = rostui(["node", "info", "/rosuot"], ros_env)
    assert ours.stderr == "cannot contact [/rosuot]: unknown node\ndid you mean /rosout?\n"
    assert "Node [/rosuot]" in ours.stdout  # rosnode's report of an unknown node, unchanged
    ours = rostui(["node", "ping", "-c", "1", "/rosuot"], ros_env)
    assert ours.stderr == "cannot ping [/rosuot]: unknown node\ndid you mean /rosout?\n"
    ours = rostui(["node", "kill", "/rosuot"], ros_env)
    assert ours.returncode == 1
    assert ours.stderr == "ERROR: Unknown node(s):\n * /rosuot\ndid you mean /rosout?\n"


def test_topic_info_and_type_did_you_mean(any_master: str, ros_env: dict[str, str]) -> None:
    ours = rostui(["topic", "info", "/rosout_ag"], ros_env)
    assert (ours.returncode, ours.stdout) == (1, "")
    assert ours.stderr == "ERROR: Unknown topic /rosout_ag\ndid you mean /rosout_agg?\n"
    ours = rostui(["topic", "type", "/rosout_ag"], ros_env)
    assert ours.returncode == 1 and ours.stderr.endswith("\ndid you mean /rosout_agg?\n")
    assert ours.stderr.count("\n") == 2


def test_service_did_you_mean(any_master: str, ros_env: dict[str, str], spawn: Spawn,
                              rospy_available: None) -> None:
    spawn(rospy_peer("rospy_setbool_server.py", "/set_flag"), label="server").wait_for("ready")
    ours = rostui(["service", "call", "/set_flga", "true"], ros_env)
    assert (ours.returncode, ours.stdout) == (1, "")
    assert ours.stderr == "ERROR: Service [/set_flga] is not available.\ndid you mean /set_flag?\n"
    ours = rostui(["service", "info", "/set_flga"], ros_env)
    assert ours.stderr == "ERROR: unknown service\ndid you mean /set_flag?\n"
    for command, line in [("node", "Unknown service: /set_flga"), ("uri", "Unknown service: /set_flga"),
                          ("type", "Unknown service [/set_flga]"),
                          ("args", "ERROR: Service [/set_flga] is not available.")]:
        ours = rostui(["service", command, "/set_flga"], ros_env)
        assert (ours.returncode, ours.stderr) == (1, f"{line}\ndid you mean /set_flag?\n"), command
    assert rostui(["service", "call", "/set_flag", "true"], ros_env).stdout == "success: True\nmessage: \"got true\"\n"


def test_topic_echo_hints_while_it_waits(any_master: str, ros_env: dict[str, str], spawn: Spawn,
                                         rospy_available: None) -> None:
    talker = spawn(rospy_peer("rospy_talker.py", "/turtle1/pose", "3", "10"), label="talker")
    wait_for_publisher(ros_env, "/turtle1/pose")
    echo = spawn([sys.executable, "-m", "rostui", "topic", "echo", "/turtle1/pos"], label="echo")
    echo.wait_for(r"^WARNING: topic \[/turtle1/pos\] does not appear to be published yet$")
    echo.wait_for(r"^did you mean /turtle1/pose\?$")
    assert echo.proc.poll() is None  # it waits, as rostopic echo does
    assert talker.proc.poll() is None


def test_service_call_wait_hints_while_it_waits(any_master: str, ros_env: dict[str, str], spawn: Spawn,
                                                rospy_available: None) -> None:
    spawn(rospy_peer("rospy_setbool_server.py", "/set_flag"), label="server").wait_for("ready")
    caller = spawn([sys.executable, "-m", "rostui", "service", "call", "--wait", "/set_flga", "true"], label="call")
    caller.wait_for(r"^did you mean /set_flag\?$")
    assert caller.proc.poll() is None  # still waiting for /set_flga
    spawn(rospy_peer("rospy_setbool_server.py", "/set_flga"), label="late server").wait_for("ready")
    assert caller.wait_exit() == 0
    assert "success: True" in caller.output
