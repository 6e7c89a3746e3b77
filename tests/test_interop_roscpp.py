"""Topics and services between rostui and a real roscpp node (bench/roscpp_peer.cpp).

The peer is compiled once per session against Debian's libroscpp-dev; each
test runs under both `rostui core` and a real roscore.
"""

from __future__ import annotations

from interop_helpers import example, roscpp_peer_bin, rostui_peer, spawn, wait_for_node  # noqa: F401

COUNT = 5


def test_roscpp_talker_to_rostui_listener(any_master, roscpp_peer_bin, spawn, ros_env):
    listener = spawn(example("listener.py", "__name:=ears"), label="rostui listener")
    wait_for_node(ros_env, "/ears")
    talker = spawn([str(roscpp_peer_bin), "talk", "/chatter", str(COUNT), "20"], label="roscpp talker")
    for n in range(COUNT):
        listener.wait_for(rf"^\[ INFO\] \[\d+\.\d+\]: I heard: hello {n}$")
    assert talker.wait_exit() == 0, talker.describe()
    assert listener.count("I heard: ") == COUNT, listener.describe()


def test_rostui_talker_to_roscpp_listener(any_master, roscpp_peer_bin, spawn):
    listener = spawn([str(roscpp_peer_bin), "listen", "/chatter", str(COUNT)], label="roscpp listener")
    talker = spawn(example("talker.py", "--count", str(COUNT)), label="rostui talker")
    assert listener.wait_exit() == 0, listener.describe() + "\n" + talker.describe()
    heard = [line for line in listener.lines if line.startswith("hello")]
    assert heard == [f"hello world {n}" for n in range(COUNT)], listener.describe()
    assert talker.wait_exit() == 0, talker.describe()


def test_roscpp_client_to_rostui_server(any_master, roscpp_peer_bin, spawn):
    server = spawn(rostui_peer("serve", "/toggle"), label="rostui server")
    server.wait_for(r"^ready$")
    client = spawn([str(roscpp_peer_bin), "call", "/toggle"], label="roscpp client")
    assert client.wait_exit() == 0, client.describe() + "\n" + server.describe()
    assert "success=1 message=got true" in client.lines, client.describe()
    server.wait_for(r"^request data=True$")


def test_rostui_client_to_roscpp_server(any_master, roscpp_peer_bin, spawn):
    spawn([str(roscpp_peer_bin), "serve", "/toggle"], label="roscpp server")
    for value, expect in (("true", "got true"), ("false", "got false")):
        client = spawn(example("toggle_client.py", value), label="rostui toggle_client")
        assert client.wait_exit() == 0, client.describe()
        assert client.lines[-1] == f"success=True message={expect}", client.describe()
