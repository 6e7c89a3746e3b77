"""Master -> node notifications: publisherUpdate, paramUpdate and shutdown, received by real servers."""

from __future__ import annotations

import asyncio
import time
from typing import Any, Awaitable, Callable

from rostui.core.master import Master
from rostui.core.master.handler import SETTLE_SECONDS
from rostui.core.xmlrpc import XmlRpcClient, XmlRpcServer


class FakeNode:
    """A slave-API stand-in that records what the master tells it."""

    def __init__(self, gate: asyncio.Event | None = None, param_reply: int = 1) -> None:
        self.events: list[tuple[str, tuple[Any, ...]]] = []
        self.gate = gate
        self.arrived = 0
        self.param_reply = param_reply
        self.changed = asyncio.Event()

    def _record(self, name: str, args: tuple[Any, ...]) -> None:
        self.events.append((name, args))
        self.changed.set()

    async def publisherUpdate(self, caller_id: str, topic: str, pubs: list[str]) -> list[Any]:
        self.arrived += 1
        self.changed.set()
        if self.gate is not None:
            await self.gate.wait()  # a node that answers only when the test lets it
        self._record("publisherUpdate", (caller_id, topic, pubs))
        return [1, "", 0]

    def paramUpdate(self, caller_id: str, key: str, value: Any) -> list[Any]:
        self._record("paramUpdate", (caller_id, key, value))
        return [self.param_reply, "", 0]

    def shutdown(self, caller_id: str, msg: str) -> list[Any]:
        self._record("shutdown", (caller_id, msg))
        return [1, "", 0]

    async def wait_for(self, count: int, timeout: float = 5.0) -> list[tuple[str, tuple[Any, ...]]]:
        deadline = time.monotonic() + timeout
        while len(self.events) < count:
            self.changed.clear()
            remaining = deadline - time.monotonic()
            assert remaining > 0, f"only got {self.events}"
            try:
                await asyncio.wait_for(self.changed.wait(), remaining)
            except asyncio.TimeoutError:
                pass
        return self.events


Test = Callable[[Master, XmlRpcClient, list[tuple[FakeNode, str]]], Awaitable[None]]


def scenario(test: Test, nodes: list[FakeNode]) -> None:
    """Start a master and one XmlRpcServer per fake node, then run ``test``."""
    async def main() -> None:
        master = Master("127.0.0.1", 0, run_id="r")
        await master.start()
        servers = [XmlRpcServer(n, "127.0.0.1") for n in nodes]
        for s in servers:
            await s.start()
        client = XmlRpcClient(master.uri)
        try:
            await test(master, client, [(n, s.uri) for n, s in zip(nodes, servers)])
        finally:
            await client.close()
            await master.stop()
            for s in servers:
                await s.close()
    asyncio.run(main())


def test_publisher_update_on_register_and_unregister() -> None:
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (sub, sub_uri), (pub, pub_uri) = nodes
        await c.call("registerSubscriber", "/sub", "/chatter", "std_msgs/String", sub_uri)
        assert (await c.call("registerPublisher", "/pub", "/chatter", "std_msgs/String", pub_uri))[2] == [sub_uri]
        events = await sub.wait_for(1)
        assert events[0] == ("publisherUpdate", ("/master", "/chatter", [pub_uri]))
        await c.call("unregisterPublisher", "/pub", "/chatter", pub_uri)
        events = await sub.wait_for(2)
        assert events[1] == ("publisherUpdate", ("/master", "/chatter", []))
        assert pub.events == []
    scenario(t, [FakeNode(), FakeNode()])


def test_register_does_not_wait_for_slow_subscriber_and_keeps_order() -> None:
    gate = asyncio.Event()

    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (slow, slow_uri), = nodes
        await c.call("registerSubscriber", "/slow", "/a", "std_msgs/String", slow_uri)
        await c.call("registerSubscriber", "/slow", "/b", "std_msgs/String", slow_uri)
        for caller, topic, uri in (("/p1", "/a", "http://127.0.0.1:1/"), ("/p2", "/b", "http://127.0.0.1:1/"),
                                   ("/p3", "/a", "http://127.0.0.1:2/")):
            # The subscriber has not answered anything yet: a master waiting for it would hang here.
            await asyncio.wait_for(c.call("registerPublisher", caller, topic, "std_msgs/String", uri), 10)
        assert slow.events == []
        while slow.arrived < 1:  # the first update (for /a) is in flight, the later ones queued
            slow.changed.clear()
            await asyncio.wait_for(slow.changed.wait(), 10)
        gate.set()
        await slow.wait_for(3, timeout=10)
        # the pending /a update, queued behind /b, carries the newest list (a repeat may follow: see below)
        assert slow.events[:3] == [
            ("publisherUpdate", ("/master", "/a", ["http://127.0.0.1:1/"])),
            ("publisherUpdate", ("/master", "/b", ["http://127.0.0.1:1/"])),
            ("publisherUpdate", ("/master", "/a", ["http://127.0.0.1:1/", "http://127.0.0.1:2/"])),
        ]
    scenario(t, [FakeNode(gate=gate)])


def test_a_subscriber_that_handles_its_reply_last_still_learns_the_publisher() -> None:
    """rospy (and roscpp) apply a registerSubscriber reply and publisherUpdates in the order their threads get to
    them: an update sent right after the reply can be applied first, and the reply's older, empty list then
    wins. The master repeats a list that changed while the subscription settled, so the node ends knowing it."""
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (sub, sub_uri), (_, pub_uri) = nodes
        reply = await c.call("registerSubscriber", "/sub", "/chatter", "std_msgs/String", sub_uri)
        await c.call("registerPublisher", "/pub", "/chatter", "std_msgs/String", pub_uri)
        first = await sub.wait_for(1)
        applied = [first[0][1][2], reply[2]]  # the node handled the update, then its (older) reply
        assert applied[-1] == []
        events = await sub.wait_for(2, timeout=SETTLE_SECONDS + 10)
        applied.append(events[1][1][2])
        assert applied[-1] == [pub_uri]
    scenario(t, [FakeNode(), FakeNode()])


def test_dead_subscriber_does_not_block_others() -> None:
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (live, live_uri), = nodes
        await c.call("registerSubscriber", "/dead", "/t", "std_msgs/String", "http://127.0.0.1:1/")
        await c.call("registerSubscriber", "/live", "/t", "std_msgs/String", live_uri)
        await c.call("registerPublisher", "/p", "/t", "std_msgs/String", "http://127.0.0.1:9/")
        events = await live.wait_for(1)
        assert events[0][1] == ("/master", "/t", ["http://127.0.0.1:9/"])
        assert (await c.call("getUri", "/x"))[0] == 1
    scenario(t, [FakeNode()])


def test_same_name_node_replacement_shuts_down_old_node() -> None:
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (old, old_uri), (new, new_uri), (sub, sub_uri) = nodes
        await c.call("registerSubscriber", "/listener", "/chatter", "std_msgs/String", sub_uri)
        await c.call("registerPublisher", "/talker", "/chatter", "std_msgs/String", old_uri)
        await sub.wait_for(1)
        await c.call("registerPublisher", "/talker", "/other", "std_msgs/String", new_uri)
        events = await old.wait_for(1)
        assert events[0] == ("shutdown", ("/master", "[/talker] Reason: new node registered with same name"))
        # the old node's publication is gone and its subscribers are told
        sub_events = await sub.wait_for(2)
        assert sub_events[1] == ("publisherUpdate", ("/master", "/chatter", []))
        assert await c.call("lookupNode", "/x", "/talker") == [1, "node api", new_uri]
        assert new.events == []
    scenario(t, [FakeNode(), FakeNode(), FakeNode()])


def test_param_update_on_set_namespace_and_delete() -> None:
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (node, uri), = nodes
        await c.call("subscribeParam", "/n", uri, "/ns/a")
        await c.call("subscribeParam", "/n", uri, "/ns/gone")
        await c.call("setParam", "/other", "/ns/a", 1)
        events = await node.wait_for(1)
        assert events[0] == ("paramUpdate", ("/master", "/ns/a/", 1))
        # the subscriber's own set is not echoed back
        await c.call("setParam", "/n", "/ns/a", 2)
        await c.call("setParam", "/other", "/ns", {"a": 5, "b": 6})
        events = await node.wait_for(3)
        assert sorted(events[1:], key=repr) == [
            ("paramUpdate", ("/master", "/ns/a/", 5)),
            ("paramUpdate", ("/master", "/ns/gone/", {})),
        ]
        await c.call("deleteParam", "/other", "/ns")
        events = await node.wait_for(5)
        assert sorted(events[3:], key=repr) == [
            ("paramUpdate", ("/master", "/ns/a/", {})),
            ("paramUpdate", ("/master", "/ns/gone/", {})),
        ]
    scenario(t, [FakeNode()])


def test_param_subscriber_answering_minus_one_is_dropped() -> None:
    async def t(m: Master, c: XmlRpcClient, nodes: list[tuple[FakeNode, str]]) -> None:
        (node, uri), = nodes
        await c.call("subscribeParam", "/n", uri, "/p")
        await c.call("setParam", "/x", "/p", 1)
        await node.wait_for(1)
        await asyncio.sleep(0.1)
        assert await c.call("lookupNode", "/x", "/n") == [-1, "unknown node [/n]", ""]
    scenario(t, [FakeNode(param_reply=-1)])
