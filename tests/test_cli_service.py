"""`rostui service` against `rosservice` on the same live system (rostui core or a real roscore)."""

from __future__ import annotations

import json

import pytest

from cli_helpers import normalize, rostui
from conftest import apply_ros_env
from interop_helpers import example, peers, run_tool, wait_for_node


@pytest.fixture(scope="module")
def served(module_master, module_ros_env):
    """examples/toggle_server.py (std_srvs/SetBool on /toggle) and a listener: the module's shared graph.

    Its tests only look at the graph or call services that answer the same whatever was called before.
    """
    with peers(module_ros_env) as spawn:
        spawn(example("toggle_server.py"), label="toggle_server")
        spawn(example("listener.py", "__name:=ears"), label="listener")
        wait_for_node(module_ros_env, "/toggle_server")
        wait_for_node(module_ros_env, "/ears")
        yield module_ros_env


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
def test_same_output(served, args):
    ours, theirs = check_same(args, served)
    assert ours.returncode == theirs.returncode == 0, ours.stderr


def test_find(served):
    for t in ("std_srvs/SetBool", "roscpp/GetLoggers", "nope/Nope"):
        theirs = run_tool(["rosservice", "find", t], served)
        ours = rostui(["service", "find", t], served)
        assert sorted(ours.stdout.splitlines()) == sorted(theirs.stdout.splitlines())


@pytest.mark.parametrize("cmd,expected", [
    ("info", "ERROR: unknown service"), ("node", "Unknown service: /nope"), ("type", "Unknown service [/nope]"),
    ("uri", "Unknown service: /nope"), ("args", "ERROR: Service [/nope] is not available."),
    ("call", "ERROR: Service [/nope] is not available.")])
def test_unknown_service(served, cmd, expected):
    theirs = run_tool(["rosservice", cmd, "/nope"], served, check=False)
    ours = rostui(["service", cmd, "/nope"], served)
    assert ours.stderr == theirs.stderr == expected + "\n"
    assert ours.returncode == 1 and ours.stdout == ""


def test_handler_error(served):
    """ROS's words; rosservice on Python 3 shows the text as b"..."; rostui shows the text (as the book)."""
    theirs = run_tool(["rosservice", "call", "/ears/set_logger_level", "ros", "BAD"], served, check=False)
    ours = rostui(["service", "call", "/ears/set_logger_level", "ros", "BAD"], served)
    assert ours.returncode == 1 and ours.stdout == ""
    assert ours.stderr.startswith("ERROR: service [/ears/set_logger_level] responded with an error: ")
    assert len(ours.stderr.splitlines()) == 1
    text = ours.stderr.split("responded with an error: ", 1)[1].strip()
    assert text and text in theirs.stderr


def test_bad_arguments(served):
    for args in (["1", "2"], ["{data: ["], ["{data: true, extra: 1}"]):
        ours = rostui(["service", "call", "/toggle", *args], served)
        assert ours.returncode == 1 and ours.stdout == ""
        assert len(ours.stderr.splitlines()) == 1 and ours.stderr.startswith("ERROR: "), ours.stderr


def test_stdin_requests(served):
    import subprocess
    import sys

    from conftest import REPO

    text = "data: true\n---\ndata: false\n"
    ours = subprocess.run([sys.executable, "-m", "rostui", "service", "call", "/toggle"], env=served, cwd=REPO,
                          input=text, capture_output=True, text=True, timeout=30)
    theirs = subprocess.run(["rosservice", "call", "/toggle"], env=served, input=text, capture_output=True,
                            text=True, timeout=30)
    assert ours.stdout == theirs.stdout and ours.returncode == 0


def test_json(served):
    assert "/toggle" in json.loads(rostui(["service", "list", "--json"], served).stdout)
    info = json.loads(rostui(["service", "info", "--json", "/toggle"], served).stdout)
    assert info["node"] == "/toggle_server" and info["type"] == "std_srvs/SetBool" and info["args"] == ["data"]
    assert json.loads(rostui(["service", "find", "--json", "std_srvs/SetBool"], served).stdout) == ["/toggle"]


def test_no_master(ros_env):
    for args in (["list"], ["info", "/x"], ["call", "/x"], ["type", "/x"], ["find", "std_srvs/Empty"]):
        ours = rostui(["service", *args], ros_env)
        assert ours.returncode == 1 and ours.stdout == ""
        assert ours.stderr.startswith("ERROR: Unable to communicate with master at http://127.0.0.1:")
        assert len(ours.stderr.splitlines()) == 1


def test_completion(served, monkeypatch):
    apply_ros_env(monkeypatch, served)
    from rostui.cli.service_cmd import complete_service_types, complete_services

    assert complete_services("/tog") == ["/toggle", "/toggle_server/get_loggers", "/toggle_server/set_logger_level"]
    assert "std_srvs/SetBool" in complete_service_types("std_srvs/")


def test_completion_without_master(ros_env):
    from rostui.cli.service_cmd import complete_services

    assert complete_services("/") == []
