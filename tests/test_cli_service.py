"""`rostui service` against `rosservice` on the same live system (rostui core or a real roscore)."""

from __future__ import annotations

import json

import pytest

from cli_helpers import normalize, rostui
from interop_helpers import example, run_tool, spawn, wait_for_node  # noqa: F401


@pytest.fixture
def server(any_master, spawn, ros_env):
    """examples/toggle_server.py (std_srvs/SetBool on /toggle) and a listener."""
    peer = spawn(example("toggle_server.py"), label="toggle_server")
    spawn(example("listener.py", "__name:=ears"), label="listener")
    wait_for_node(ros_env, "/toggle_server")
    wait_for_node(ros_env, "/ears")
    return peer


def check_same(args, env):
    theirs = run_tool(["rosservice", *args], env, check=False)
    ours = rostui(["service", *args], env)
    assert normalize(ours.stdout) == normalize(theirs.stdout), f"ours:\n{ours.stdout}\ntheirs:\n{theirs.stdout}"
    return ours, theirs


@pytest.mark.parametrize("args", [["list"], ["list", "-n"], ["list", "/toggle_server"], ["list", "/nons"],
                                  ["info", "/toggle"], ["node", "/toggle"], ["type", "/toggle"],
                                  ["args", "/toggle"], ["uri", "/toggle"], ["type", "/ears/get_loggers"],
                                  ["call", "/toggle", "false"], ["call", "/toggle", "data: true"],
                                  ["call", "/toggle", "{data: false}"], ["call", "/ears/get_loggers"],
                                  ["call", "/ears/set_logger_level", "ros", "info"],
                                  ["call", "-v", "/toggle", "true"]])
def test_same_output(server, ros_env, args):
    ours, theirs = check_same(args, ros_env)
    assert ours.returncode == theirs.returncode == 0, ours.stderr


def test_find(server, ros_env):
    for t in ("std_srvs/SetBool", "roscpp/GetLoggers", "nope/Nope"):
        theirs = run_tool(["rosservice", "find", t], ros_env)
        ours = rostui(["service", "find", t], ros_env)
        assert sorted(ours.stdout.splitlines()) == sorted(theirs.stdout.splitlines())


@pytest.mark.parametrize("cmd,expected", [
    ("info", "ERROR: unknown service"), ("node", "Unknown service: /nope"), ("type", "Unknown service [/nope]"),
    ("uri", "Unknown service: /nope"), ("args", "ERROR: Service [/nope] is not available."),
    ("call", "ERROR: Service [/nope] is not available.")])
def test_unknown_service(server, ros_env, cmd, expected):
    theirs = run_tool(["rosservice", cmd, "/nope"], ros_env, check=False)
    ours = rostui(["service", cmd, "/nope"], ros_env)
    assert ours.stderr == theirs.stderr == expected + "\n"
    assert ours.returncode == 1 and ours.stdout == ""


def test_handler_error(server, ros_env):
    """ROS's words; rosservice on Python 3 shows the text as b"..."; rostui shows the text (as the book)."""
    theirs = run_tool(["rosservice", "call", "/ears/set_logger_level", "ros", "BAD"], ros_env, check=False)
    ours = rostui(["service", "call", "/ears/set_logger_level", "ros", "BAD"], ros_env)
    assert ours.returncode == 1 and ours.stdout == ""
    assert ours.stderr.startswith("ERROR: service [/ears/set_logger_level] responded with an error: ")
    assert len(ours.stderr.splitlines()) == 1
    text = ours.stderr.split("responded with an error: ", 1)[1].strip()
    assert text and text in theirs.stderr


def test_bad_arguments(server, ros_env):
    for args in (["1", "2"], ["{data: ["], ["{data: true, extra: 1}"]):
        ours = rostui(["service", "call", "/toggle", *args], ros_env)
        assert ours.returncode == 1 and ours.stdout == ""
        assert len(ours.stderr.splitlines()) == 1 and ours.stderr.startswith("ERROR: "), ours.stderr


def test_stdin_requests(server, ros_env):
    import subprocess
    import sys

    from conftest import REPO

    text = "data: true\n---\ndata: false\n"
    ours = subprocess.run([sys.executable, "-m", "rostui", "service", "call", "/toggle"], env=ros_env, cwd=REPO,
                          input=text, capture_output=True, text=True, timeout=30)
    theirs = subprocess.run(["rosservice", "call", "/toggle"], env=ros_env, input=text, capture_output=True,
                            text=True, timeout=30)
    assert ours.stdout == theirs.stdout and ours.returncode == 0


def test_json(server, ros_env):
    assert "/toggle" in json.loads(rostui(["service", "list", "--json"], ros_env).stdout)
    info = json.loads(rostui(["service", "info", "--json", "/toggle"], ros_env).stdout)
    assert info["node"] == "/toggle_server" and info["type"] == "std_srvs/SetBool" and info["args"] == ["data"]
    assert json.loads(rostui(["service", "find", "--json", "std_srvs/SetBool"], ros_env).stdout) == ["/toggle"]


def test_no_master(ros_env):
    for args in (["list"], ["info", "/x"], ["call", "/x"], ["type", "/x"], ["find", "std_srvs/Empty"]):
        ours = rostui(["service", *args], ros_env)
        assert ours.returncode == 1 and ours.stdout == ""
        assert ours.stderr.startswith("ERROR: Unable to communicate with master at http://127.0.0.1:")
        assert len(ours.stderr.splitlines()) == 1


def test_completion(server, ros_env):
    from rostui.cli.service_cmd import complete_service_types, complete_services

    assert complete_services("/tog") == ["/toggle", "/toggle_server/get_loggers", "/toggle_server/set_logger_level"]
    assert "std_srvs/SetBool" in complete_service_types("std_srvs/")


def test_completion_without_master(ros_env):
    from rostui.cli.service_cmd import complete_services

    assert complete_services("/") == []
