"""`rostui node` against `rosnode` on the same live system (rostui core or a real roscore)."""

from __future__ import annotations

import re
import xmlrpc.client

import pytest

from cli_helpers import normalize, rostui
from conftest import apply_ros_env, free_port
from interop_helpers import Peer, Spawn, example, peers, run_tool, spawn, wait_for_node, wait_until  # noqa: F401


def start_graph(spawn: Spawn, env: dict[str, str]) -> tuple[Peer, Peer, Peer]:
    """rostui talker /mouth, listener /ears, toggle_server /toggle_server, connected."""
    listener = spawn(example("listener.py", "__name:=ears"), label="listener")
    wait_for_node(env, "/ears", listener)
    talker = spawn(example("talker.py", "__name:=mouth"), label="talker")
    server = spawn(example("toggle_server.py"), label="toggle_server")
    listener.wait_for(r"I heard: hello world \d+$")
    wait_for_node(env, "/toggle_server", server)
    return talker, listener, server


@pytest.fixture
def graph(any_master, spawn, ros_env):
    """The graph of :func:`start_graph`, for a test that changes it (kills or adds nodes)."""
    return start_graph(spawn, ros_env)


@pytest.fixture(scope="module")
def shared(module_master, module_ros_env):
    """The graph of :func:`start_graph` and its environment, shared by the module's tests that only look at it."""
    with peers(module_ros_env) as spawn:
        yield start_graph(spawn, module_ros_env), module_ros_env


def same(ours, theirs):
    assert normalize(ours.stdout) == normalize(theirs.stdout), f"ours:\n{ours.stdout}\ntheirs:\n{theirs.stdout}"


@pytest.mark.parametrize("args", [["list"], ["list", "-u"], ["list", "-a"], ["list", "/ears"], ["list", "/nons"],
                                  ["list", "ears"]])
def test_list(shared, args):
    _, env = shared
    theirs = run_tool(["rosnode", *args], env)
    ours = rostui(["node", *args], env)
    assert ours.returncode == 0, ours.stderr
    if "-u" in args or "-a" in args:  # URIs are ephemeral: compare as sets of lines
        assert sorted(ours.stdout.splitlines()) == sorted(theirs.stdout.splitlines())
    else:
        assert ours.stdout == theirs.stdout


def test_list_json(shared):
    _, env = shared
    import json

    ours = json.loads(rostui(["node", "list", "--json"], env).stdout)
    assert [e["node"] for e in ours] == ["/ears", "/mouth", "/rosout", "/toggle_server"]
    assert all(e["uri"].startswith("http://") for e in ours)


@pytest.mark.parametrize("node", ["/mouth", "/ears", "/toggle_server", "/nope"])
def test_info(shared, node):
    _, env = shared
    theirs = run_tool(["rosnode", "info", node], env)
    ours = rostui(["node", "info", node], env)
    assert ours.returncode == theirs.returncode
    # Connection lists come in the node's own order; compare sorted blocks.
    assert normalize(ours.stdout).split("Connections:")[0] == normalize(theirs.stdout).split("Connections:")[0]
    assert sorted(normalize(ours.stdout).splitlines()) == sorted(normalize(theirs.stdout).splitlines())
    assert ours.stderr == theirs.stderr


def test_info_quiet_and_json(shared):
    graph, env = shared
    import json

    same(rostui(["node", "info", "-q", "/toggle_server"], env),
         run_tool(["rosnode", "info", "-q", "/toggle_server"], env))
    talker = graph[0]
    data = json.loads(rostui(["node", "info", "--json", "/mouth"], env).stdout)
    assert data["pid"] == talker.proc.pid
    assert {"topic": "/chatter", "type": "std_msgs/String"} in data["publications"]


def test_ping(shared):
    _, env = shared
    theirs = run_tool(["rosnode", "ping", "-c", "2", "/ears"], env)
    ours = rostui(["node", "ping", "-c", "2", "/ears"], env)
    assert ours.returncode == 0
    mask = lambda t: re.sub(r"[\d.]+ms", "Xms", normalize(t))  # noqa: E731
    assert mask(ours.stdout) == mask(theirs.stdout)
    assert ours.stdout.count("xmlrpc reply from ") == 2 and "ping average: " in ours.stdout
    theirs = run_tool(["rosnode", "ping", "-c", "1", "/nope"], env, check=False)
    ours = rostui(["node", "ping", "-c", "1", "/nope"], env)
    assert (ours.stdout, ours.stderr, ours.returncode) == (theirs.stdout, theirs.stderr, theirs.returncode)


def test_ping_all(shared):
    _, env = shared
    ours = rostui(["node", "ping", "-a"], env)
    theirs = run_tool(["rosnode", "ping", "-a"], env)
    strip = lambda t: sorted(re.sub(r"[\d.]+ms", "Xms", normalize(t)).splitlines())  # noqa: E731
    assert strip(ours.stdout) == strip(theirs.stdout)


def test_kill(graph, spawn, ros_env):
    spawn(example("talker.py", "__name:=victim", "__ns:=/grp"), label="victim")
    spawn(example("talker.py", "__name:=victim2"), label="victim2")
    wait_for_node(ros_env, "/grp/victim")
    wait_for_node(ros_env, "/victim2")
    theirs = run_tool(["rosnode", "kill", "/grp/victim"], ros_env)
    ours = rostui(["node", "kill", "/victim2"], ros_env)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == theirs.stdout.replace("/grp/victim", "/victim2")
    nodes = lambda: run_tool(["rosnode", "list"], ros_env).stdout.split()  # noqa: E731
    wait_until(lambda: "/victim2" not in nodes() and "/grp/victim" not in nodes(), "killed nodes to unregister")
    theirs = run_tool(["rosnode", "kill", "/nope"], ros_env, check=False)
    ours = rostui(["node", "kill", "/nope"], ros_env)
    assert (ours.stdout, ours.stderr, ours.returncode) == (theirs.stdout, theirs.stderr, 1)


def register_dead_node(env, name):
    """Leave ``name`` on the master as a node killed without unregistering leaves it: a publisher of /chatter
    whose slave URI no one answers.  The port is from this worker's own block, which nothing else binds; a
    killed process's own port is an ephemeral one, which another test's node may take (and answer on) at
    once."""
    master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
    code, status, _ = master.registerPublisher(name, "/chatter", "std_msgs/String", f"http://127.0.0.1:{free_port()}/")
    assert code == 1, status


def test_cleanup(graph, spawn, ros_env):
    for name in ("/deadA", "/deadB"):
        register_dead_node(ros_env, name)
    # "n": nothing purged, rosnode's words.
    ours = rostui(["node", "cleanup"], ros_env, input="n\n")
    theirs = run_tool_input(["rosnode", "cleanup"], ros_env, "n\n")
    assert sorted(ours.stdout.splitlines()) == sorted(theirs.stdout.splitlines())  # rosnode: set order
    assert "Please type y or n to continue:\naborting\n" in ours.stdout
    # stdin at EOF: rosnode would loop forever; rostui aborts.
    ours = rostui(["node", "cleanup"], ros_env)
    assert ours.stdout.endswith("aborting\n") and ours.returncode == 0
    assert "/deadA" in run_tool(["rosnode", "list"], ros_env).stdout
    ours = rostui(["node", "cleanup"], ros_env, input="y\n")
    assert ours.stdout.endswith("Unregistering /deadA\nUnregistering /deadB\ndone\n"), ours.stdout
    assert "ERROR: connection refused to [http://" in ours.stderr
    assert {"/deadA", "/deadB"}.isdisjoint(run_tool(["rosnode", "list"], ros_env).stdout.split())
    assert rostui(["node", "cleanup", "-y"], ros_env).stdout == ""


def run_tool_input(argv, env, text):
    import subprocess

    return subprocess.run(argv, env=env, input=text, capture_output=True, text=True, timeout=30)


def test_no_master(ros_env):
    for args in (["list"], ["info", "/x"], ["ping", "-c", "1", "/x"], ["kill", "/x"], ["cleanup"]):
        ours = rostui(["node", *args], ros_env)
        assert ours.returncode == 1
        assert ours.stderr.startswith("ERROR: Unable to communicate with master at http://127.0.0.1:")
        assert len(ours.stderr.splitlines()) == 1 and ours.stdout in ("", "rosnode: node is [/x]\n")


def test_completion_without_master(ros_env):
    from rostui.cli.node_cmd import complete_nodes

    assert complete_nodes("/") == []


def test_completion_live(shared, monkeypatch):
    _, env = shared
    apply_ros_env(monkeypatch, env)
    from rostui.cli.node_cmd import complete_nodes

    assert complete_nodes("/m") == ["/mouth"]
