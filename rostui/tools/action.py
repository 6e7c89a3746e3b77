"""Action servers on the master, found by actionlib's five topics, and one goal sent to one of them (axclient).

An actionlib server in namespace NS subscribes to ``NS/goal`` and ``NS/cancel`` and publishes ``NS/status``,
``NS/feedback`` and ``NS/result``; the action's type is its goal topic's type without ``ActionGoal``. A goal is
sent as actionlib's clients send it: an ``ActionGoal`` with a fresh ``GoalID``, once the server's status has come
and it has subscribed to the goal topic; feedback and status are followed for that goal alone, and cancelling
publishes its id on ``NS/cancel``.
"""

from __future__ import annotations

import asyncio
import time
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Sequence

from rostui.core.msg import Time, get_message_class
from rostui.core.node.node import AsyncNode

__all__ = ["ActionInfo", "ActionError", "GoalOutcome", "STATUS_NAMES", "TOPICS", "find_actions", "action_type_of",
           "GoalSession"]

TOPICS = ("goal", "cancel", "status", "feedback", "result")

#: actionlib_msgs/GoalStatus's states by number.
STATUS_NAMES = {0: "PENDING", 1: "ACTIVE", 2: "PREEMPTED", 3: "SUCCEEDED", 4: "ABORTED", 5: "REJECTED",
                6: "PREEMPTING", 7: "RECALLING", 8: "RECALLED", 9: "LOST"}
#: The states a goal ends in.
TERMINAL = frozenset({2, 3, 4, 5, 8, 9})


class ActionError(Exception):
    """An action that cannot be used as asked; the message is one line."""


@dataclass(frozen=True)
class ActionInfo:
    """One action namespace: its type (``pkg/Name``, None when the master does not say), the nodes serving it and
    the nodes that send it goals."""

    name: str
    type: str | None
    servers: tuple[str, ...]
    clients: tuple[str, ...]


def action_type_of(topic_type: str | None) -> str | None:
    """``pkg/Name`` of an action from one of its envelope types (``pkg/NameActionGoal``...), else None."""
    for suffix in ("ActionGoal", "ActionResult", "ActionFeedback"):
        if topic_type and topic_type.endswith(suffix) and len(topic_type) > len(suffix):
            return topic_type[:-len(suffix)]
    return None


def find_actions(publishers: Iterable[Sequence[Any]], subscribers: Iterable[Sequence[Any]],
                 types: dict[str, str]) -> list[ActionInfo]:
    """The action servers in a master's ``getSystemState`` lists (and ``getTopicTypes`` as ``types``), by name.

    A server is a node that publishes ``NS/status``, ``NS/feedback`` and ``NS/result`` and subscribes to
    ``NS/goal`` and ``NS/cancel``."""
    pubs = {str(topic): set(nodes) for topic, nodes in publishers}
    subs = {str(topic): set(nodes) for topic, nodes in subscribers}
    found = []
    for status in sorted(topic for topic in pubs if topic.endswith("/status")):
        ns = status[:-len("/status")]
        servers = set(pubs[status])
        for topic, table in (("feedback", pubs), ("result", pubs), ("goal", subs), ("cancel", subs)):
            servers &= table.get(f"{ns}/{topic}", set())
        if not servers:
            continue
        kind = next((found_type for found_type in (action_type_of(types.get(f"{ns}/{topic}"))
                                                   for topic in ("goal", "result", "feedback")) if found_type), None)
        found.append(ActionInfo(ns or "/", kind, tuple(sorted(servers)), tuple(sorted(pubs.get(f"{ns}/goal", ())))))
    return found


@dataclass(frozen=True)
class GoalOutcome:
    """How a goal ended: its final state's number and name, the server's text, and the result message."""

    status: int
    text: str
    result: Any

    @property
    def status_name(self) -> str:
        """``SUCCEEDED``, ``ABORTED``..."""
        return STATUS_NAMES.get(self.status, f"status {self.status}")


class GoalSession:
    """One goal sent to the action server in ``ns`` (of type ``action_type``) from ``node``.

    Run :meth:`connect`, then :meth:`send` with the goal message (of :attr:`goal_class`); ``on_feedback(msg)`` gets
    each feedback of this goal, ``on_status(state, text)`` each change of its state. :meth:`cancel` asks the server
    to stop it.
    """

    def __init__(self, node: AsyncNode, ns: str, action_type: str, *,
                 on_feedback: Callable[[Any], None] = lambda _msg: None,
                 on_status: Callable[[int, str], None] = lambda _state, _text: None) -> None:
        self.node, self.ns, self.action_type = node, ns.rstrip("/") or "", action_type
        try:
            self.action_goal_class = get_message_class(f"{action_type}ActionGoal")
            self.goal_class = get_message_class(f"{action_type}Goal")
            self.result_class = get_message_class(f"{action_type}ActionResult")
            self.feedback_class = get_message_class(f"{action_type}ActionFeedback")
        except Exception as exc:  # unknown package or a broken .action: the user's type is wrong
            raise ActionError(f"cannot load action type {action_type}: {exc}") from None
        self.on_feedback, self.on_status = on_feedback, on_status
        self.goal_id = ""
        self.state: int | None = None
        self.server_seen = asyncio.Event()
        self._outcome: asyncio.Future[GoalOutcome] | None = None
        self._goal_pub: Any = None
        self._cancel_pub: Any = None
        self._handles: list[Any] = []

    @property
    def finished(self) -> bool:
        """Whether the last goal sent has its result (or was given up)."""
        return self._outcome is not None and self._outcome.done()

    def topic(self, name: str) -> str:
        """``NS/name``."""
        return f"{self.ns}/{name}"

    async def connect(self, timeout: float) -> None:
        """Advertise goal and cancel, follow status, feedback and result, and wait until the server is there.

        ActionError when no server answered within ``timeout`` seconds."""
        status_class = get_message_class("actionlib_msgs/GoalStatusArray")
        self._goal_pub = await self.node.advertise(self.topic("goal"), self.action_goal_class, queue_size=10)
        self._cancel_pub = await self.node.advertise(self.topic("cancel"), get_message_class("actionlib_msgs/GoalID"),
                                                     queue_size=10)
        self._handles = [self._goal_pub, self._cancel_pub,
                         await self.node.subscribe(self.topic("status"), status_class, self._on_status_array),
                         await self.node.subscribe(self.topic("feedback"), self.feedback_class, self._on_feedback),
                         await self.node.subscribe(self.topic("result"), self.result_class, self._on_result)]
        deadline = time.monotonic() + timeout
        # as actionlib's wait_for_server: the server's status heard, and all five topics connected both ways (a
        # feedback or result published before its subscription is connected would be lost)
        while not (self.server_seen.is_set() and all(handle.get_num_connections() for handle in self._handles)):
            if time.monotonic() > deadline:
                raise ActionError(f"no action server answered on {self.ns or '/'} within {timeout:g} s")
            await asyncio.sleep(0.02)

    def send_goal(self, goal: Any) -> str:
        """Send ``goal`` now; its id (await :meth:`result` for how it ends)."""
        now = Time.now()
        self.goal_id = f"{self.node.name}-1-{now.secs}.{now.nsecs:09d}"
        self.state = None
        self._outcome = asyncio.get_running_loop().create_future()
        goal_id = get_message_class("actionlib_msgs/GoalID")(stamp=now, id=self.goal_id)
        header = get_message_class("std_msgs/Header")(stamp=now)
        self._goal_pub.publish(self.action_goal_class(header=header, goal_id=goal_id, goal=goal))
        return self.goal_id

    async def result(self) -> GoalOutcome:
        """How the goal sent last ends."""
        assert self._outcome is not None, "no goal sent"
        return await self._outcome

    async def send(self, goal: Any) -> GoalOutcome:
        """Send ``goal`` and wait for its result."""
        self.send_goal(goal)
        return await self.result()

    async def close(self) -> None:
        """Stop publishing and listening on the action's topics (a goal still running goes on at the server)."""
        handles, self._handles = self._handles, []
        for handle in handles:
            await handle.unregister()
        if self._outcome is not None and not self._outcome.done():
            self._outcome.cancel()

    def cancel(self) -> None:
        """Ask the server to stop this goal (its result still comes, PREEMPTED or RECALLED)."""
        if self._cancel_pub is not None and self.goal_id:
            self._cancel_pub.publish(get_message_class("actionlib_msgs/GoalID")(stamp=Time(0, 0), id=self.goal_id))

    def _on_status_array(self, msg: Any) -> None:
        self.server_seen.set()
        for status in msg.status_list:
            if status.goal_id.id == self.goal_id and self.goal_id:
                self._set_state(int(status.status), status.text)

    def _set_state(self, state: int, text: str) -> None:
        if state != self.state:
            self.state = state
            self.on_status(state, text)

    def _on_feedback(self, msg: Any) -> None:
        if self.goal_id and msg.status.goal_id.id == self.goal_id:
            self._set_state(int(msg.status.status), msg.status.text)
            self.on_feedback(msg.feedback)

    def _on_result(self, msg: Any) -> None:
        if self.goal_id and msg.status.goal_id.id == self.goal_id and self._outcome is not None \
                and not self._outcome.done():
            self._set_state(int(msg.status.status), msg.status.text)
            self._outcome.set_result(GoalOutcome(int(msg.status.status), msg.status.text, msg.result))
