"""Every Master and Parameter Server API call, against an in-process Master over XML-RPC."""

from __future__ import annotations

import asyncio
import os
import re
from typing import Awaitable, Callable

from rostui.core.master import Master
from rostui.core.xmlrpc import XmlRpcClient

A = "http://127.0.0.1:40001/"
B = "http://127.0.0.1:40002/"


def with_master(test: Callable[[Master, XmlRpcClient], Awaitable[None]]) -> None:
    """Run ``test(master, client)`` against a fresh Master on a free port."""
    async def main() -> None:
        master = Master("127.0.0.1", 0, run_id="test-run-id")
        await master.start()
        client = XmlRpcClient(master.uri)
        try:
            await test(master, client)
        finally:
            await client.close()
            await master.stop()
    asyncio.run(main())


def test_start_params_uri_pid() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert re.fullmatch(r"http://127\.0\.0\.1:\d+/", m.uri)
        assert await c.call("getUri", "/x") == [1, "", m.uri]
        assert await c.call("getPid", "/x") == [1, "", os.getpid()]
        assert await c.call("getParam", "/x", "/run_id") == [1, "Parameter [/run_id]", "test-run-id"]
        code, _, distro = await c.call("getParam", "/x", "/rosdistro")
        assert code == 1 and distro.endswith("\n")
        code, _, version = await c.call("getParam", "/x", "/rosversion")
        assert code == 1 and version.endswith("\n")
        assert m.run_id == "test-run-id"
    with_master(t)


def test_default_run_id_is_uuid() -> None:
    async def main() -> None:
        m = Master("127.0.0.1", 0)
        await m.start()
        assert re.fullmatch(r"[0-9a-f]{8}-[0-9a-f]{4}-1[0-9a-f]{3}-[0-9a-f]{4}-[0-9a-f]{12}", m.run_id)
        await m.stop()
    asyncio.run(main())


def test_argument_checking() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("getUri") == [-1, "missing required caller_id parameter", ""]
        assert await c.call("getUri", "/x", 1) == [-1, "Error: bad call arity", ""]
        assert await c.call("getUri", 3) == [-1, "caller_id must be a string", ""]
        assert await c.call("shutdown", "/x") == [-1, "Error: bad call arity", 0]
        assert await c.call("registerPublisher", "/n", "/t", "bad", A) == [
            -1, "ERROR: parameter [topic_type] is not a valid package resource name", []]
        assert await c.call("registerPublisher", "/n", "a b", "std_msgs/String", A) == [
            -1, "ERROR: parameter [topic] contains illegal chars", []]
        assert await c.call("registerPublisher", "/n", "/", "std_msgs/String", A) == [
            -1, "ERROR: parameter [topic] cannot be the global namespace", []]
        assert await c.call("registerPublisher", "/n", "/t", "std_msgs/String", "ftp://x") == [
            -1, "ERROR: parameter [caller_api] is not an RPC URI", []]
        assert await c.call("registerPublisher", "/n", "/t", "std_msgs/String", 5) == [
            -1, "ERROR: parameter [caller_api] is not an XMLRPC URI", []]
        assert await c.call("getParam", "/n", 5) == [-1, "ERROR: parameter [key] must be a string", 0]
        assert await c.call("getParam", "/n", "") == [
            -1, "ERROR: parameter [key] must be specified and non-empty", 0]
        assert await c.call("setParam", "/n", "/k", None) == [
            -1, "ERROR: parameter [value] must be specified", 0]
        assert await c.call("setParam", "/n", "/", 5) == [
            -1, "Error: invalid arguments: cannot set root of parameter tree to non-dictionary", 0]
        assert await c.call("getPublishedTopics", "/n", 5) == [
            -1, "ERROR: parameter [subgraph] must be a string", 0]
        assert await c.call("lookupNode", "/n", "") == [
            -1, "ERROR: parameter [node] must be a non-empty string", ""]
        assert await c.call("searchParam", "/n", "~x") == [0, "Internal failure: invalid key", 0]
        assert await c.call("searchParam", "n", "x") == [0, "Internal failure: namespace must be global", 0]
    with_master(t)


def test_publishers_subscribers_and_state() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("registerSubscriber", "/sub", "chatter", "std_msgs/String", B) == [
            1, "Subscribed to [/chatter]", []]
        assert await c.call("registerPublisher", "/ns/pub", "chatter", "std_msgs/String", A) == [
            1, "Registered [/ns/pub] as publisher of [/ns/chatter]", []]
        assert await c.call("registerPublisher", "/pub", "chatter", "std_msgs/String", A) == [
            1, "Registered [/pub] as publisher of [/chatter]", [B]]
        assert await c.call("registerSubscriber", "/sub2", "/chatter", "*", B) == [
            1, "Subscribed to [/chatter]", [A]]
        assert await c.call("getPublishedTopics", "/x", "") == [
            1, "current topics", [["/ns/chatter", "std_msgs/String"], ["/chatter", "std_msgs/String"]]]
        assert await c.call("getPublishedTopics", "/x", "/ns") == [
            1, "current topics", [["/ns/chatter", "std_msgs/String"]]]
        assert await c.call("getTopicTypes", "/x") == [
            1, "current system state", [["/chatter", "std_msgs/String"], ["/ns/chatter", "std_msgs/String"]]]
        assert await c.call("getSystemState", "/x") == [1, "current system state", [
            [["/ns/chatter", ["/ns/pub"]], ["/chatter", ["/pub"]]],
            [["/chatter", ["/sub", "/sub2"]]],
            []]]
        assert await c.call("lookupNode", "/x", "/pub") == [1, "node api", A]
        assert await c.call("lookupNode", "/x", "nobody") == [-1, "unknown node [/nobody]", ""]
        assert await c.call("unregisterPublisher", "/pub", "/chatter", B) == [
            1, "[/pub] is not a known provider of [/chatter]", 0]
        assert await c.call("unregisterPublisher", "/pub", "/chatter", A) == [
            1, "Unregistered [/pub] as provider of [/chatter]", 1]
        assert await c.call("unregisterPublisher", "/ghost", "/chatter", A) == [
            1, "[/ghost] is not a registered node", 0]
        assert await c.call("lookupNode", "/x", "/pub") == [-1, "unknown node [/pub]", ""]
        assert await c.call("unregisterSubscriber", "/sub", "/chatter", B) == [
            1, "Unregistered [/sub] as provider of [/chatter]", 1]
        state = (await c.call("getSystemState", "/x"))[2]
        assert state == [[["/ns/chatter", ["/ns/pub"]]], [["/chatter", ["/sub2"]]], []]
    with_master(t)


def test_any_type_does_not_squash_known_type() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        await c.call("registerSubscriber", "/s", "/t1", "*", B)
        assert (await c.call("getTopicTypes", "/x"))[2] == []
        await c.call("registerPublisher", "/p", "/t1", "*", A)
        assert (await c.call("getTopicTypes", "/x"))[2] == [["/t1", "*"]]
        await c.call("registerPublisher", "/p", "/t1", "std_msgs/Int32", A)
        await c.call("registerPublisher", "/q", "/t1", "*", B)
        assert (await c.call("getTopicTypes", "/x"))[2] == [["/t1", "std_msgs/Int32"]]
    with_master(t)


def test_services() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("lookupService", "/x", "/add") == [-1, "no provider", ""]
        assert await c.call("registerService", "/srv", "add", "rosrpc://h:1", A) == [
            1, "Registered [/srv] as provider of [/add]", 1]
        assert await c.call("lookupService", "/x", "/add") == [1, "rosrpc URI: [rosrpc://h:1]", "rosrpc://h:1"]
        assert await c.call("registerService", "/srv2", "/add", "rosrpc://h:2", B) == [
            1, "Registered [/srv2] as provider of [/add]", 1]
        assert await c.call("getSystemState", "/x") == [1, "current system state", [[], [], [["/add", ["/srv2"]]]]]
        assert await c.call("unregisterService", "/srv", "/add", "rosrpc://h:1") == [
            1, "[rosrpc://h:1] is no longer the current service api handle for [/add]", 0]
        assert await c.call("unregisterService", "/srv2", "/add", "rosrpc://h:2") == [
            1, "Unregistered [/srv2] as provider of [/add]", 1]
        assert await c.call("lookupService", "/x", "/add") == [-1, "no provider", ""]
        assert await c.call("unregisterService", "/nobody", "/add", "rosrpc://h:2") == [
            1, "[/nobody] is not a registered node", 0]
    with_master(t)


def test_params_set_get_delete_names() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("setParam", "/n", "a/b", 1) == [1, "parameter /a/b set", 0]
        assert await c.call("setParam", "/ns/n", "~priv", "p") == [1, "parameter /ns/n/priv set", 0]
        assert await c.call("setParam", "/n", "/d", {"x": 1, "y": {"z": [1, 2]}}) == [1, "parameter /d set", 0]
        assert await c.call("getParam", "/n", "/a") == [1, "Parameter [/a]", {"b": 1}]
        assert await c.call("getParam", "/n", "/d/y/z") == [1, "Parameter [/d/y/z]", [1, 2]]
        assert await c.call("getParam", "/n", "/nope") == [-1, "Parameter [/nope] is not set", 0]
        assert await c.call("getParam", "/n", "/a/b/c") == [-1, "Parameter [/a/b/c] is not set", 0]
        assert await c.call("hasParam", "/n", "/d/x") == [1, "/d/x", True]
        assert await c.call("hasParam", "/n", "d/q") == [1, "/d/q", False]
        # setting a dict replaces the namespace
        await c.call("setParam", "/n", "/d", {"w": 2})
        assert (await c.call("getParam", "/n", "/d"))[2] == {"w": 2}
        # a value on the way is turned into a namespace
        await c.call("setParam", "/n", "/a/b/c", 3)
        assert (await c.call("getParam", "/n", "/a"))[2] == {"b": {"c": 3}}
        names = (await c.call("getParamNames", "/n"))[2]
        assert set(names) == {"/run_id", "/rosdistro", "/rosversion", "/a/b/c", "/ns/n/priv", "/d/w"}
        assert await c.call("deleteParam", "/n", "/a") == [1, "parameter /a deleted", 0]
        assert await c.call("deleteParam", "/n", "/a") == [-1, "parameter [/a] is not set", 0]
        assert await c.call("deleteParam", "/n", "/") == [-1, "parameter [/] is not set", 0]
        tree = (await c.call("getParam", "/n", "/"))[2]
        assert tree["d"] == {"w": 2} and "a" not in tree
        # big values round-trip; ints beyond 32 bits come back as a fault like rosmaster
        await c.call("setParam", "/n", "/f", 1.5e300)
        assert (await c.call("getParam", "/n", "/f"))[2] == 1.5e300
    with_master(t)


def test_search_param() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        await c.call("setParam", "/n", "/robot_description", {"arm": 1, "base": 2})
        await c.call("setParam", "/n", "/pr2/robot_description", {"base": 3})
        await c.call("setParam", "/n", "/pr2/foo/node/private", 4)
        assert await c.call("searchParam", "/pr2/foo", "robot_description") == [
            1, "Found [/pr2/robot_description]", "/pr2/robot_description"]
        assert await c.call("searchParam", "/pr2/foo", "robot_description/arm") == [
            1, "Found [/pr2/robot_description/arm]", "/pr2/robot_description/arm"]
        assert await c.call("searchParam", "/other/node", "robot_description") == [
            1, "Found [/robot_description]", "/robot_description"]
        # the caller's own (private) namespace is searched first
        assert await c.call("searchParam", "/pr2/foo/node", "private") == [
            1, "Found [/pr2/foo/node/private]", "/pr2/foo/node/private"]
        assert await c.call("searchParam", "/x", "/robot_description") == [
            1, "Found [/robot_description]", "/robot_description"]
        assert await c.call("searchParam", "/x", "missing") == [
            -1, "Cannot find parameter [missing] in an upwards search", ""]
    with_master(t)


def test_subscribe_unsubscribe_param() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("subscribeParam", "/n", A, "/p") == [1, "Subscribed to parameter [/p]", {}]
        await c.call("setParam", "/x", "/q", {"r": 1})
        assert await c.call("subscribeParam", "/n", A, "q") == [1, "Subscribed to parameter [/q]", {"r": 1}]
        assert await c.call("lookupNode", "/x", "/n") == [1, "node api", A]
        assert await c.call("unsubscribeParam", "/n", A, "/p") == [1, "Unsubscribe to parameter [/p]", 1]
        assert await c.call("unsubscribeParam", "/n", A, "/never") == [1, "Unsubscribe to parameter [/never]", 1]
        assert await c.call("unsubscribeParam", "/n", A, "/q") == [1, "Unsubscribe to parameter [/q]", 1]
        assert await c.call("lookupNode", "/x", "/n") == [-1, "unknown node [/n]", ""]
    with_master(t)


def test_node_replacement_drops_old_registrations() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        await c.call("registerPublisher", "/node", "/t1", "std_msgs/String", A)
        await c.call("registerSubscriber", "/node", "/t2", "std_msgs/String", A)
        await c.call("registerService", "/node", "/s", "rosrpc://h:1", A)
        await c.call("registerPublisher", "/node", "/t3", "std_msgs/String", B)
        assert (await c.call("getSystemState", "/x"))[2] == [[["/t3", ["/node"]]], [], []]
        assert await c.call("lookupNode", "/x", "/node") == [1, "node api", B]
        assert await c.call("lookupService", "/x", "/s") == [-1, "no provider", ""]
    with_master(t)


def test_shutdown_call_is_reported() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        assert await c.call("shutdown", "/x", "bye") == [1, "shutdown", 0]
        assert await asyncio.wait_for(m.wait_for_shutdown_request(), 2) == "bye"
    with_master(t)


def test_multicall_like_rospy() -> None:
    async def t(m: Master, c: XmlRpcClient) -> None:
        result = await c.call("system.multicall", [
            {"methodName": "getUri", "params": ["/x"]},
            {"methodName": "getParam", "params": ["/x", "/run_id"]},
        ])
        assert result == [[[1, "", m.uri]], [[1, "Parameter [/run_id]", "test-run-id"]]]
    with_master(t)


