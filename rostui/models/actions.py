"""What the action app knows without a screen: the action servers on the master, and the one goal it is running.

One unannounced node asks the master for its topics every ``period`` seconds (getSystemState and getTopicTypes)
and finds the servers by actionlib's five topics. A goal goes out through a
:class:`~rostui.tools.action.GoalSession` for the chosen action, kept while that action stays chosen and closed
when another is chosen, so the app is listed on the master as a client of the action it talks to, as actionlib's
clients are.
"""

from __future__ import annotations

import asyncio
from typing import Any, Callable

from rostui.core.master_errors import MasterError, MasterUnreachableError
from rostui.models.calling_node import CallingNode
from rostui.models.monitor.publish import PublishError, message_from_text, message_template
from rostui.tools.action import ActionError, ActionInfo, GoalOutcome, GoalSession, find_actions

__all__ = ["ActionsSource", "GoalFailed", "SERVER_TIMEOUT", "goal_template"]

#: Seconds the app waits for an action's server before a goal is sent.
SERVER_TIMEOUT = 5.0


class GoalFailed(Exception):
    """A goal that could not be sent; the message is one line."""


def goal_template(action_type: str) -> str:
    """The YAML of a default goal of ``action_type`` (``pkg/Name``); :class:`GoalFailed` for an unknown type."""
    try:
        return message_template(f"{action_type}Goal")[1]
    except PublishError as exc:
        raise GoalFailed(str(exc)) from None


class ActionsSource(CallingNode):
    """The action servers on the master at ``master_uri``; :meth:`refresh` asks again, :meth:`send` runs a goal."""

    def __init__(self, master_uri: str, *, timeout: float = 3.0) -> None:
        super().__init__("rostui_actions", master_uri, "rostui action done", quiet=True)
        self.timeout = timeout
        self.actions: list[ActionInfo] = []
        self.read = False
        """Whether the master has answered once."""
        self.session: GoalSession | None = None

    async def close(self) -> None:
        """Close the session and shut the node down."""
        await self._drop_session()
        await super().close()

    async def refresh(self) -> list[ActionInfo]:
        """The action servers now; :class:`~rostui.core.master_errors.MasterUnreachableError` without a master."""
        try:
            publishers, subscribers, _services = await asyncio.wait_for(self.node.master_call("getSystemState"),
                                                                        self.timeout)
            types = await asyncio.wait_for(self.node.master_call("getTopicTypes"), self.timeout)
        except (asyncio.TimeoutError, OSError) as exc:
            raise MasterUnreachableError(self.master_uri, str(exc) or "no answer") from None
        except MasterError as exc:
            raise MasterUnreachableError(self.master_uri, str(exc)) from None
        own = self.node.name
        self.actions = [action for action in find_actions(publishers, subscribers, dict(types))
                        if own not in action.servers]
        self.read = True
        return self.actions

    def action(self, name: str) -> ActionInfo | None:
        """The action server ``name``, if listed."""
        return next((action for action in self.actions if action.name == name), None)

    async def send(self, action: ActionInfo, goal_text: str, *, on_feedback: Callable[[Any], None],
                   on_status: Callable[[int, str], None]) -> GoalOutcome:
        """Send the goal ``goal_text`` (YAML) to ``action`` and wait for its result.

        :class:`GoalFailed` when the type is unknown, the YAML does not fit it or no server answers."""
        if action.type is None:
            raise GoalFailed(f"the master names no type for {action.name}")
        session = self.session
        if session is None or session.ns != action.name.rstrip("/") or session.action_type != action.type:
            await self._drop_session()
            try:
                session = GoalSession(self.node, action.name, action.type)
                await session.connect(SERVER_TIMEOUT)
            except ActionError as exc:
                raise GoalFailed(str(exc)) from None
            self.session = session
        try:
            goal = message_from_text(session.goal_class, goal_text)
        except PublishError as exc:
            raise GoalFailed(str(exc)) from None
        session.on_feedback, session.on_status = on_feedback, on_status
        return await session.send(goal)

    def cancel(self) -> bool:
        """Ask the server to stop the goal running now; False when none is."""
        session = self.session
        if session is None or not session.goal_id or session.finished:
            return False
        session.cancel()
        return True

    async def _drop_session(self) -> None:
        session, self.session = self.session, None
        if session is not None:
            try:
                await session.close()
            except MasterError:  # the master is gone; the node's own sockets close with it
                pass
