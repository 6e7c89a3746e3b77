"""Real ROS 1 command-line tools against `rostui core` and rostui nodes.

rosnode, rostopic, rosservice and rosparam from Debian's ros-core talk to a
`rostui core` master and to nodes written with rostui's client API; each test
asserts the text a user would read.
"""

from __future__ import annotations

import re

import pytest
import yaml

from interop_helpers import example, rostui_peer, run_tool, spawn, wait_for_node  # noqa: F401

URI = r"http://127\.0\.0\.1:\d+/"


@pytest.fixture
def chatter(rostui_core, spawn, ros_env):
    """A rostui talker /mouth and listener /ears connected on /chatter."""
    listener = spawn(example("listener.py", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    talker = spawn(example("talker.py", "__name:=mouth"), label="rostui talker")
    listener.wait_for(r"I heard: hello world \d+$")
    return talker, listener


def lines(text: str) -> list[str]:
    return [line.rstrip() for line in text.splitlines()]


def test_rosnode_list(chatter, ros_env):
    assert sorted(run_tool(["rosnode", "list"], ros_env).stdout.split()) == ["/ears", "/mouth", "/rosout"]


def test_rosnode_info(chatter, ros_env):
    talker, listener = chatter
    out = lines(run_tool(["rosnode", "info", "/mouth"], ros_env).stdout)
    assert "Node [/mouth]" in out
    pubs = out.index("Publications:")
    assert out[pubs + 1: pubs + 3] == [" * /chatter [std_msgs/String]", " * /rosout [rosgraph_msgs/Log]"]
    assert "Subscriptions: None" in out
    srvs = out.index("Services:")
    assert out[srvs + 1: srvs + 3] == [" * /mouth/get_loggers", " * /mouth/set_logger_level"]
    assert f"Pid: {talker.proc.pid}" in out
    conns = out[out.index("Connections:"):]
    assert " * topic: /chatter" in conns
    assert "    * to: /ears" in conns
    assert "    * direction: outbound" in conns
    assert "    * transport: TCPROS" in conns

    out = lines(run_tool(["rosnode", "info", "/ears"], ros_env).stdout)
    assert "Node [/ears]" in out
    pubs = out.index("Publications:")
    assert out[pubs + 1: pubs + 3] == [" * /rosout [rosgraph_msgs/Log]", ""]
    subs = out.index("Subscriptions:")
    assert out[subs + 1] == " * /chatter [std_msgs/String]"
    assert f"Pid: {listener.proc.pid}" in out
    conns = out[out.index("Connections:"):]
    assert any(re.fullmatch(r"    \* to: /mouth( \(" + URI + r"\))?", line) for line in conns), out
    assert "    * direction: inbound" in conns


def test_rostopic_list_and_info(chatter, ros_env):
    topics = run_tool(["rostopic", "list"], ros_env).stdout.split()
    assert {"/chatter", "/rosout", "/rosout_agg"} <= set(topics)
    out = lines(run_tool(["rostopic", "info", "/chatter"], ros_env).stdout)
    assert out[0] == "Type: std_msgs/String"
    pubs, subs = out.index("Publishers:"), out.index("Subscribers:")
    assert re.fullmatch(r" \* /mouth \(" + URI + r"\)", out[pubs + 1]), out
    assert re.fullmatch(r" \* /ears \(" + URI + r"\)", out[subs + 1]), out
    assert pubs < subs


def test_rostopic_echo_latched(rostui_core, spawn, ros_env):
    latcher = spawn(rostui_peer("latch", "/greeting", "hello"), label="rostui latcher")
    latcher.wait_for(r"^ready$")
    out = run_tool(["rostopic", "echo", "-n", "1", "/greeting"], ros_env).stdout
    assert lines(out) == ['data: "hello"', "---"]


def test_rostopic_echo_live(chatter, ros_env):
    out = lines(run_tool(["rostopic", "echo", "-n", "1", "/chatter"], ros_env).stdout)
    assert len(out) == 2 and out[1] == "---", out
    assert re.fullmatch(r'data: "hello world \d+"', out[0]), out


def test_rostopic_pub_once(rostui_core, spawn, ros_env):
    listener = spawn(example("listener.py", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    out = run_tool(["rostopic", "pub", "-1", "/chatter", "std_msgs/String", "data: hello"], ros_env).stdout
    assert "publishing and latching message" in out
    listener.wait_for(r"^\[ INFO\] \[\d+\.\d+\]: I heard: hello$")


def test_rosservice_list_info_call(rostui_core, spawn, ros_env):
    server = spawn(example("toggle_server.py"), label="rostui toggle_server")
    wait_for_node(ros_env, "/toggle_server")
    assert "/toggle" in run_tool(["rosservice", "list"], ros_env).stdout.split()
    assert run_tool(["rosservice", "type", "/toggle"], ros_env).stdout.strip() == "std_srvs/SetBool"
    info = lines(run_tool(["rosservice", "info", "/toggle"], ros_env).stdout)
    assert "Node: /toggle_server" in info
    assert "Type: std_srvs/SetBool" in info
    assert "Args: data" in info
    assert any(re.fullmatch(r"URI: rosrpc://127\.0\.0\.1:\d+", line) for line in info), info
    out = run_tool(["rosservice", "call", "/toggle", "data: false"], ros_env).stdout
    assert lines(out) == ["success: True", 'message: "got false"']
    server.wait_for(r"toggle: now off$")
    out = run_tool(["rosservice", "call", "/toggle", "data: true"], ros_env).stdout
    assert lines(out) == ["success: True", 'message: "got true"']


def test_rosparam_set_get_list_dump(rostui_core, ros_env, tmp_path):
    run_tool(["rosparam", "set", "/foo", "42"], ros_env)
    run_tool(["rosparam", "set", "/robot/name", "hal"], ros_env)
    run_tool(["rosparam", "set", "/robot/speed", "1.5"], ros_env)
    run_tool(["rosparam", "set", "/robot/wheels", "[1, 2, 3]"], ros_env)
    assert run_tool(["rosparam", "get", "/foo"], ros_env).stdout.strip() == "42"
    assert run_tool(["rosparam", "get", "/robot/name"], ros_env).stdout.strip() == "hal"
    assert yaml.safe_load(run_tool(["rosparam", "get", "/robot"], ros_env).stdout) == {
        "name": "hal", "speed": 1.5, "wheels": [1, 2, 3]}
    names = run_tool(["rosparam", "list"], ros_env).stdout.split()
    assert {"/foo", "/robot/name", "/robot/speed", "/robot/wheels", "/rosdistro", "/rosversion",
            "/run_id"} <= set(names)
    dump = tmp_path / "params.yaml"
    run_tool(["rosparam", "dump", str(dump), "/robot"], ros_env)
    assert yaml.safe_load(dump.read_text()) == {"name": "hal", "speed": 1.5, "wheels": [1, 2, 3]}
    run_tool(["rosparam", "delete", "/robot/speed"], ros_env)
    assert "/robot/speed" not in run_tool(["rosparam", "list"], ros_env).stdout.split()
    missing = run_tool(["rosparam", "get", "/robot/speed"], ros_env, check=False)
    assert missing.returncode != 0
    assert "/robot/speed" in missing.stderr



def test_rosnode_ping_and_kill(any_master, spawn, ros_env):
    """`rosnode ping` reaches a rostui node; `rosnode kill` makes it exit and unregister.

    Repeated a few times: a node that exits before its unregister calls are
    done leaves a stale entry that `rosnode list` keeps showing.
    """
    for attempt in range(4):
        listener = spawn(example("listener.py", "__name:=ears"), label=f"rostui listener #{attempt}")
        wait_for_node(ros_env, "/ears")
        ping = run_tool(["rosnode", "ping", "-c", "1", "/ears"], ros_env).stdout
        assert re.search(r"reply from " + URI + r"\ttime=", ping), ping
        out = run_tool(["rosnode", "kill", "/ears"], ros_env).stdout
        assert "killed" in out, out
        listener.wait_exit()
        assert "Shutdown request received" in listener.output, listener.describe()
        assert "/ears" not in run_tool(["rosnode", "list"], ros_env).stdout.split(), (
            f"attempt {attempt}: /ears still registered after it exited\n{listener.describe()}")
