"""The same call sequence against real rosmaster and against rostui's master: equal results.

Requires Debian's ros-core (fails instead of skipping when ROSTUI_REQUIRE_INTEROP=1).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest

from conftest import REPO, free_port, need_command, stop_process, wait_for_port
from rostui.core.xmlrpc import XmlRpcFault, call_sync

A = "http://127.0.0.1:1/"  # nothing listens on port 1: notifications fail fast
B = "http://127.0.0.1:2/"
C = "http://127.0.0.1:3/"

BIG_INT_SET = (
    b"<?xml version='1.0'?><methodCall><methodName>setParam</methodName><params>"
    b"<param><value><string>/x</string></value></param>"
    b"<param><value><string>/big</string></value></param>"
    b"<param><value><i8>99999999999</i8></value></param></params></methodCall>"
)

# (method, args...) -- run in order against both masters.
SEQUENCE: list[tuple[Any, ...]] = [
    ("setParam", "/t", "/", {}),  # both start from an empty parameter tree
    ("getUri",),
    ("getUri", "/x", 1),
    ("getUri", 5),
    ("getPid", "/x", "extra"),
    ("shutdown", "/x"),
    ("nosuchmethod", "/x"),
    ("registerSubscriber", "/sub", "chatter", "std_msgs/String", B),
    ("registerPublisher", "/ns/pub", "chatter", "std_msgs/String", A),
    ("registerPublisher", "/pub", "chatter", "std_msgs/String", A),
    ("registerPublisher", "/pub", "chatter", "std_msgs/String", A),
    ("registerSubscriber", "/sub2", "/chatter", "*", C),
    ("registerSubscriber", "/sub3", "/only_sub", "*", C),
    ("registerPublisher", "/pub", "/anytopic", "*", A),
    ("registerPublisher", "/pub2", "/anytopic", "std_msgs/Int8", B),
    ("registerPublisher", "/pub3", "/anytopic", "*", C),
    ("registerPublisher", "/n", "/t", "bad", A),
    ("registerPublisher", "/n", "a b", "std_msgs/String", A),
    ("registerPublisher", "/n", "x:y", "std_msgs/String", A),
    ("registerPublisher", "/n", "/", "std_msgs/String", A),
    ("registerPublisher", "/n", "", "std_msgs/String", A),
    ("registerPublisher", "/n", "/t", "std_msgs/String", "ftp://x"),
    ("registerPublisher", "/n", "/t", "std_msgs/String", 5),
    ("registerPublisher", "/n", "/t", 5, A),
    ("registerSubscriber", "/n", 7, "std_msgs/String", A),
    ("getPublishedTopics", "/x", ""),
    ("getPublishedTopics", "/x", "/ns"),
    ("getPublishedTopics", "/ns/x", "ns"),
    ("getPublishedTopics", "/x", 5),
    ("getTopicTypes", "/x"),
    ("getSystemState", "/x"),
    ("lookupNode", "/x", "/pub"),
    ("lookupNode", "/ns/x", "pub"),
    ("lookupNode", "/x", "nobody"),
    ("lookupNode", "/x", ""),
    ("unregisterPublisher", "/pub", "/chatter", B),
    ("unregisterPublisher", "/pub", "/chatter", A),
    ("unregisterPublisher", "/pub", "/chatter", A),
    ("unregisterPublisher", "/ghost", "/chatter", A),
    ("unregisterSubscriber", "/sub", "/chatter", B),
    ("unregisterSubscriber", "/sub", "/chatter", B),
    ("getSystemState", "/x"),
    ("lookupNode", "/x", "/sub"),
    ("lookupService", "/x", "/add"),
    ("registerService", "/srv", "add", "rosrpc://h:1", A),
    ("registerService", "/srv", "/bad", "http2://h:1", A),
    ("lookupService", "/x", "/add"),
    ("lookupService", "/x", "add"),
    ("registerService", "/srv2", "/add", "rosrpc://h:2", B),
    ("getSystemState", "/x"),
    ("unregisterService", "/srv", "/add", "rosrpc://h:1"),
    ("unregisterService", "/srv2", "/add", "rosrpc://h:2"),
    ("unregisterService", "/nobody", "/add", "rosrpc://h:2"),
    ("lookupService", "/x", "/add"),
    ("registerPublisher", "/node", "/t1", "std_msgs/String", A),
    ("registerSubscriber", "/node", "/t2", "std_msgs/String", A),
    ("registerService", "/node", "/s", "rosrpc://h:1", A),
    ("subscribeParam", "/node", A, "/watched"),
    ("registerPublisher", "/node", "/t3", "std_msgs/String", B),
    ("getSystemState", "/x"),
    ("lookupNode", "/x", "/node"),
    ("lookupService", "/x", "/s"),
    ("setParam", "/n", "a/b", 1),
    ("setParam", "/ns/n", "~priv", "p"),
    ("setParam", "/n", "/d", {"x": 1, "y": {"z": [1, 2]}}),
    ("setParam", "/n", "/types", [True, 1.5, "s", {"k": "v"}, [1, [2]]]),
    ("setParam", "/n", "/k", None),
    ("setParam", "/n", "/", 5),
    ("setParam", "/n", "", 5),
    ("setParam", "/n", 5, 5),
    ("getParam", "/n", "/a"),
    ("getParam", "/n", "/d/y/z"),
    ("getParam", "/n", "d/y"),
    ("getParam", "/ns/n", "~priv"),
    ("getParam", "/n", "/nope"),
    ("getParam", "/n", "/a/b/c"),
    ("getParam", "/n", "//a//b//"),
    ("getParam", "/n", "/types"),
    ("hasParam", "/n", "/d/x"),
    ("hasParam", "/n", "d/q"),
    ("hasParam", "/n", "/"),
    ("setParam", "/n", "/d", {"w": 2}),
    ("getParam", "/n", "/d"),
    ("setParam", "/n", "/a/b/c", 3),
    ("getParam", "/n", "/a"),
    ("getParamNames", "/n"),
    ("deleteParam", "/n", "/a"),
    ("deleteParam", "/n", "/a"),
    ("deleteParam", "/n", "/"),
    ("deleteParam", "/n", "/d/w/x"),
    ("getParam", "/n", "/"),
    ("setParam", "/n", "/robot_description", {"arm": 1, "base": 2}),
    ("setParam", "/n", "/pr2/robot_description", {"base": 3}),
    ("setParam", "/n", "/pr2/foo/node/private", 4),
    ("searchParam", "/pr2/foo", "robot_description"),
    ("searchParam", "/pr2/foo", "robot_description/arm"),
    ("searchParam", "/other/node", "robot_description"),
    ("searchParam", "/pr2/foo/node", "private"),
    ("searchParam", "/pr2/foo/node", "foo"),
    ("searchParam", "/x", "/robot_description"),
    ("searchParam", "/x", "/robot_description/none"),
    ("searchParam", "/x", "missing"),
    ("searchParam", "/x", "~x"),
    ("searchParam", "x", "y"),
    ("searchParam", "/", "pr2"),
    ("subscribeParam", "/s", A, "/p"),
    ("subscribeParam", "/s", A, "robot_description"),
    ("subscribeParam", "/s", "bad", "robot_description"),
    ("lookupNode", "/x", "/s"),
    ("unsubscribeParam", "/s", A, "/p"),
    ("unsubscribeParam", "/s", A, "/never"),
    ("unsubscribeParam", "/s", A, "/robot_description"),
    ("lookupNode", "/x", "/s"),
    ("getParam", "/x", "/big"),
    ("setParam", "/x", "/f", 1.5e300),
    ("getParam", "/x", "/f"),
    ("system.multicall", [{"methodName": "getParam", "params": ["/x", "/f"]},
                          {"methodName": "nope", "params": []},
                          {"methodName": "getUri", "params": []}]),
]


def run_sequence(uri: str) -> list[Any]:
    """Every call's result (or fault), with the master's own URI normalised."""
    results: list[Any] = []
    for method, *args in SEQUENCE:
        try:
            value = call_sync(uri, method, *args)
        except XmlRpcFault as fault:
            value = ("FAULT", fault.code, fault.string)
        if method == "getPid":
            value = value[:2]
        results.append((method, args, _normalise(value, uri)))
    # an i8 value: accepted on set, a fault on get (as rosmaster)
    import http.client
    host, port = uri[len("http://"):].rstrip("/").split(":")
    conn = http.client.HTTPConnection(host, int(port), timeout=10)
    conn.request("POST", "/", BIG_INT_SET, {"Content-Type": "text/xml"})
    results.append(("raw i8 setParam", conn.getresponse().read()))
    conn.close()
    try:
        results.append(("getParam big", call_sync(uri, "getParam", "/x", "/big")))
    except XmlRpcFault as fault:
        results.append(("getParam big", fault.code, fault.string))
    return results


def _normalise(value: Any, uri: str) -> Any:
    if isinstance(value, str):
        return value.replace(uri, "<MASTER>")
    if isinstance(value, (list, tuple)):
        return [_normalise(v, uri) for v in value]
    if isinstance(value, dict):
        return {k: _normalise(v, uri) for k, v in value.items()}
    return value


@pytest.fixture
def rosmaster_uri(ros_env: dict[str, str]) -> Iterator[str]:
    """A real ``rosmaster --core`` on a free port."""
    need_command("rosmaster")
    port = free_port()
    proc = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=ros_env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_port(port, timeout=30, proc=proc)
        yield f"http://127.0.0.1:{port}/"
    finally:
        stop_process(proc)


@pytest.fixture
def rostui_master_uri(ros_env: dict[str, str]) -> Iterator[str]:
    """``python -m rostui.core.master`` on a free port."""
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "rostui.core.master", "-p", str(port)], env=ros_env,
                            cwd=str(REPO), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        wait_for_port(port, proc=proc)
        yield f"http://127.0.0.1:{port}/"
    finally:
        stop_process(proc)


def test_same_results_as_rosmaster(rosmaster_uri: str, rostui_master_uri: str) -> None:
    theirs = run_sequence(rosmaster_uri)
    ours = run_sequence(rostui_master_uri)
    for a, b in zip(theirs, ours):
        assert b == a
    assert len(theirs) == len(ours)


def test_real_rosparam_and_rostopic_against_rostui(rostui_master_uri: str, ros_env: dict[str, str],
                                                   tmp_path: Path) -> None:
    need_command("rosparam")
    env = dict(ros_env, ROS_MASTER_URI=rostui_master_uri)
    run = lambda *cmd: subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=30)  # noqa: E731
    assert run("rosparam", "set", "/demo/value", "42").returncode == 0
    got = run("rosparam", "get", "/demo/value")
    assert got.stdout.strip() == "42", got.stderr
    listing = run("rosparam", "list")
    assert "/demo/value" in listing.stdout.split() and "/run_id" in listing.stdout.split()
    topics = run("rostopic", "list")
    assert topics.returncode == 0, topics.stderr
