"""Parameters shared between rostui nodes and the real `rosparam`, under both masters."""

from __future__ import annotations

import yaml

from interop_helpers import example, rostui_peer, run_tool, spawn, wait_for_node  # noqa: F401


def test_private_params_from_command_line(any_master, spawn, ros_env):
    """`_rate:=5.5 _greeting:=hi _on:=true` become YAML-typed /ears/... parameters."""
    spawn(example("listener.py", "__name:=ears", "_rate:=5.5", "_greeting:=hi", "_on:=true", "_n:=7"),
          label="rostui listener")
    wait_for_node(ros_env, "/ears")
    assert run_tool(["rosparam", "get", "/ears/rate"], ros_env).stdout.strip() == "5.5"
    assert run_tool(["rosparam", "get", "/ears/greeting"], ros_env).stdout.strip() == "hi"
    assert run_tool(["rosparam", "get", "/ears/on"], ros_env).stdout.strip() == "true"
    assert run_tool(["rosparam", "get", "/ears/n"], ros_env).stdout.strip() == "7"


def test_rostui_reads_what_rosparam_set(any_master, spawn, ros_env):
    run_tool(["rosparam", "set", "/robot/speed", "2.5"], ros_env)
    run_tool(["rosparam", "set", "/robot/name", "hal"], ros_env)
    reader = spawn(rostui_peer("getparam", "/robot/speed"), label="rostui reader")
    assert reader.wait_exit() == 0, reader.describe()
    assert reader.lines[-1] == "/robot/speed = 2.5", reader.describe()
    reader = spawn(rostui_peer("getparam", "/robot"), label="rostui reader")
    assert reader.wait_exit() == 0, reader.describe()
    assert reader.lines[-1] == '/robot = {"name": "hal", "speed": 2.5}', reader.describe()
    missing = spawn(rostui_peer("getparam", "/robot/colour"), label="rostui reader")
    assert missing.wait_exit() == 1, missing.describe()
    assert missing.lines[-1] == "KeyError: '/robot/colour'", missing.describe()


def test_rosparam_reads_what_rostui_set(any_master, spawn, ros_env):
    writer = spawn(rostui_peer("setparam", "/gains", "{p: 1.0, i: 0.5, names: [a, b]}"), label="rostui writer")
    assert writer.wait_exit() == 0, writer.describe()
    assert run_tool(["rosparam", "get", "/gains/p"], ros_env).stdout.strip() == "1.0"
    assert yaml.safe_load(run_tool(["rosparam", "get", "/gains/names"], ros_env).stdout) == ["a", "b"]
    names = run_tool(["rosparam", "list", "/gains"], ros_env).stdout.split()
    assert sorted(names) == ["/gains/i", "/gains/names", "/gains/p"]
