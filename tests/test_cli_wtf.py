"""`rostui wtf` against rostui core and a real roscore: dead nodes, type mismatches, unconnected subscribers."""

from __future__ import annotations

import json
import os
import re
import threading
from pathlib import Path
from typing import Any, Iterator
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from cli_helpers import rostui
from interop_helpers import run_tool
from rostui.core.xmlrpc import call_sync


class FakeNode:
    """A node's slave API that answers getPid, getPublications and getSubscriptions."""

    def __init__(self, name: str, pubs: list[list[str]], subs: list[list[str]]) -> None:
        self.name = name
        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
        self.server.register_function(lambda caller: [1, "", os.getpid()], "getPid")
        self.server.register_function(lambda caller: [1, "", pubs], "getPublications")
        self.server.register_function(lambda caller: [1, "", subs], "getSubscriptions")
        self.server.register_function(lambda *a: [1, "", 0], "publisherUpdate")
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


@pytest.fixture
def fake_nodes() -> Iterator[list[FakeNode]]:
    nodes: list[FakeNode] = []
    yield nodes
    for n in nodes:
        n.close()


def register(env: dict[str, str], node: str, uri: str, pubs: list[list[str]] = [], subs: list[list[str]] = []) -> None:  # noqa: B006
    master = env["ROS_MASTER_URI"]
    for topic, type_name in pubs:
        assert call_sync(master, "registerPublisher", node, topic, type_name, uri)[0] == 1
    for topic, type_name in subs:
        assert call_sync(master, "registerSubscriber", node, topic, type_name, uri)[0] == 1


def wtf(env: dict[str, str], *args: str) -> tuple[int, list[str]]:
    r = rostui(["wtf", *args], env)
    assert r.stderr == ""
    return r.returncode, r.stdout.splitlines()


def test_finds_dead_node_mismatch_and_unconnected(any_master: str, ros_env: dict[str, str],
                                                  fake_nodes: list[FakeNode]) -> None:
    talker = FakeNode("/talker", [["/chatter", "std_msgs/String"]], [])
    listener = FakeNode("/listener", [], [["/chatter", "std_msgs/Int32"]])
    fake_nodes += [talker, listener]
    register(ros_env, "/talker", talker.uri, pubs=[["/chatter", "std_msgs/String"]])
    register(ros_env, "/listener", listener.uri, subs=[["/chatter", "std_msgs/Int32"]])
    register(ros_env, "/deadnode", "http://127.0.0.1:1/", subs=[["/lonely", "std_msgs/Int32"]])

    code, lines = wtf(ros_env)
    assert code == 1
    assert ("ERROR node /deadnode is registered but does not answer at http://127.0.0.1:1/: connection refused "
            "(hint: it probably died; 'rostui node cleanup' unregisters it)") in lines
    assert ("ERROR topic /chatter is used with different types: std_msgs/Int32 (/listener subscribes); "
            "std_msgs/String (/talker publishes) "
            "(hint: nodes with different types never connect; make them use one message type)") in lines
    assert ("WARNING topic /lonely is subscribed by /deadnode but nobody publishes it "
            "(hint: check the topic name and remappings ('rostui topic list'), or start the publisher)") in lines
    assert not any("/talker" in l and "does not answer" in l for l in lines)
    assert lines[-1] == "Found 2 error(s) and 2 warning(s)."  # the 2nd warning: /rosout's own subscription

    code, out = wtf(ros_env, "--json")
    report = json.loads("\n".join(out))
    assert code == 1 and report["online"] and report["errors"] == 2
    assert {f["check"] for f in report["findings"]} == {"dead_node", "type_mismatch", "unconnected"}


def test_healthy_system_exits_zero(any_master: str, ros_env: dict[str, str], fake_nodes: list[FakeNode]) -> None:
    pub = FakeNode("/pub", [["/rosout", "rosgraph_msgs/Log"], ["/data", "std_msgs/String"]], [])
    sub = FakeNode("/sub", [], [["/data", "std_msgs/String"]])
    fake_nodes += [pub, sub]
    register(ros_env, "/pub", pub.uri, pubs=[["/rosout", "rosgraph_msgs/Log"], ["/data", "std_msgs/String"]])
    register(ros_env, "/sub", sub.uri, subs=[["/data", "std_msgs/String"]])
    code, lines = wtf(ros_env)
    assert (code, lines) == (0, ["No errors or warnings"])


def test_warnings_alone_exit_zero(rostui_core: Any, ros_env: dict[str, str]) -> None:
    code, lines = wtf(ros_env)
    assert code == 0
    assert lines[0].startswith("WARNING topic /rosout is subscribed by /rosout but nobody publishes it")
    assert lines[-1] == "Found 0 error(s) and 1 warning(s)."


def test_no_master_is_one_error_line(ros_env: dict[str, str]) -> None:
    code, lines = wtf(ros_env)
    uri = ros_env["ROS_MASTER_URI"] + "/"
    assert code == 1
    assert lines == [
        f"ERROR the master at ROS_MASTER_URI [{uri}] does not answer: connection refused "
        "(hint: start one with 'rostui core', or point ROS_MASTER_URI at the running master)",
        "Found 1 error(s) and 0 warning(s).",
    ]


def test_environment_checks(ros_env: dict[str, str]) -> None:
    env = dict(ros_env, ROS_IP="192.0.2.77", ROS_HOSTNAME="no-such-host.invalid")
    code, lines = wtf(env)
    assert code == 1
    assert lines[0].startswith("ERROR ROS_IP [192.0.2.77] is not an address of this machine (hint: ")
    assert lines[1].startswith("ERROR ROS_HOSTNAME [no-such-host.invalid] does not resolve (hint: ")
    assert any(l.startswith("WARNING both ROS_HOSTNAME [no-such-host.invalid] and ROS_IP [192.0.2.77] are set")
               for l in lines)
    code, lines = wtf(dict(ros_env, ROS_IP="not-an-ip", ROS_MASTER_URI="localhost:11311"))
    assert "ERROR ROS_MASTER_URI [localhost:11311/] is not of the form http://host:port/ (hint: set it to e.g. " \
           "http://localhost:11311)" in lines
    assert any(l.startswith("ERROR ROS_IP [not-an-ip] is not an IP address") for l in lines)


def test_big_log_directory_warns(rostui_core: Any, ros_env: dict[str, str]) -> None:
    log = Path(ros_env["ROS_HOME"]) / "log"
    log.mkdir(exist_ok=True)
    with open(log / "huge.log", "wb") as fh:  # sparse: apparent size over 1 GB, no disk used
        fh.truncate(1_100_000_000)
    code, lines = wtf(ros_env)
    assert code == 0
    assert f"WARNING log directory [{log}] uses 1.1G, over 1.0G (hint: free space with 'rostui clean purge')" in lines


def test_live_completions(rostui_core: Any, ros_env: dict[str, str], fake_nodes: list[FakeNode]) -> None:
    from rostui.cli import complete

    assert "/rosout" in complete.complete_nodes("/ros")
    assert complete.complete_topics("/rosout") == ["/rosout", "/rosout_agg"]
    assert "/rosout/get_loggers" in complete.complete_services("/rosout/")
    assert "/run_id" in complete.complete_params("/r")


def test_live_completions_without_master(ros_env: dict[str, str]) -> None:
    from rostui.cli import complete

    assert complete.complete_nodes("") == [] and complete.complete_topics("") == []
    assert complete.complete_services("") == [] and complete.complete_params("") == []


def _roswtf_findings(text: str) -> tuple[set[str], set[tuple[str, str]]]:
    """Dead nodes and unconnected (node, topic) subscriptions from real roswtf's report."""
    text = re.sub(r"\x1b\[[0-9;]*m", "", text)
    dead: set[str] = set()
    unconnected: set[tuple[str, str]] = set()
    section, node = "", ""
    for line in text.splitlines():
        if "Could not contact the following nodes" in line:
            section = "dead"
        elif "node subscriptions are unconnected" in line:
            section = "unconnected"
        elif not line.strip() or not line.startswith(" "):
            section = section if line.startswith(" ") else ""
        elif section == "dead" and line.startswith(" * "):
            dead.add(line[3:].strip())
        elif section == "unconnected" and line.startswith(" * "):
            node = line[3:].strip().rstrip(":")
        elif section == "unconnected" and line.strip().startswith("* "):
            unconnected.add((node, line.strip()[2:]))
    return dead, unconnected


def test_same_findings_as_real_roswtf(any_master: str, ros_env: dict[str, str]) -> None:
    register(ros_env, "/deadnode", "http://127.0.0.1:1/", subs=[["/lonely", "std_msgs/Int32"]])
    real = run_tool(["roswtf"], ros_env, timeout=120, check=False)
    dead, unconnected = _roswtf_findings(real.stdout + real.stderr)
    assert dead == {"/deadnode"} and ("/deadnode", "/lonely") in unconnected

    code, out = wtf(ros_env, "--json")
    findings = json.loads("\n".join(out))["findings"]
    ours_dead = {re.match(r"node (\S+)", f["message"]).group(1) for f in findings if f["check"] == "dead_node"}
    ours_unconnected = {tuple(reversed(re.match(r"topic (\S+) is subscribed by (\S+)", f["message"]).groups()))
                        for f in findings if f["check"] == "unconnected"}
    assert code == 1
    assert (ours_dead, ours_unconnected) == (dead, unconnected)
