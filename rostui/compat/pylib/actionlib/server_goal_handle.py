"""actionlib.server_goal_handle: ``ServerGoalHandle``, how a server moves one goal through its states.

Each setter checks the goal's current status; a transition actionlib does not allow is logged as an error
and ignored. Reaching a terminal status publishes the result (then the status array) and starts the
time after which the goal leaves the status list.
"""

from __future__ import annotations

from typing import Any

import rospy

from .spec import GoalID, GoalIDGenerator
from .states import GoalStatus

__all__ = ["ServerGoalHandle", "StatusTracker"]


class StatusTracker:
    """A goal the server knows of: its status (id, state, text), the goal itself, when to forget it."""

    def __init__(self, goal_id: Any = None, status: int | None = None, goal: Any = None) -> None:
        self.goal: Any = None
        self.status = GoalStatus()
        self.handle_destruction_time = rospy.Time()
        if goal_id is not None:
            self.status.goal_id = goal_id
            self.status.status = status
            return
        self.goal = goal
        self.status.goal_id = goal.goal_id
        self.status.status = GoalStatus.PENDING
        if self.status.goal_id.id == "":
            self.status.goal_id = GoalIDGenerator().generate_ID()
        if self.status.goal_id.stamp == rospy.Time():
            self.status.goal_id.stamp = rospy.Time.now()


_NOT_SET = "Attempt to set status on an uninitialized ServerGoalHandle"


class ServerGoalHandle:
    """The server's handle on one goal."""

    def __init__(self, status_tracker: StatusTracker | None = None, action_server: Any = None,
                 handle_tracker: Any = None) -> None:
        self.status_tracker = status_tracker
        self.action_server = action_server
        self.handle_tracker = handle_tracker
        self.goal: Any = status_tracker.goal if status_tracker is not None else None

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ServerGoalHandle) or not self.goal or not other.goal:
            return False
        assert self.status_tracker is not None and other.status_tracker is not None
        return bool(self.status_tracker.status.goal_id.id == other.status_tracker.status.goal_id.id)

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.status_tracker.status.goal_id.id) if self.status_tracker is not None else 0

    def get_default_result(self) -> Any:
        """A default-constructed result of this action."""
        return self.action_server.ActionResultType().result

    def _move(self, allowed: dict[int, int], text: str | None, publish_result: Any, wrong: str | None) -> bool:
        """Move the goal by ``allowed`` (from-status: to-status); publish the status, or the result if it ended.

        A status not in ``allowed`` is logged with ``wrong`` (quietly when None) and nothing changes.
        """
        if not self.goal:
            rospy.logerr(_NOT_SET)
            return False
        assert self.status_tracker is not None
        with self.action_server.lock:
            status = self.status_tracker.status.status
            if status not in allowed:
                if wrong is not None:
                    rospy.logerr(wrong + ", it is currently in state: %d", status)
                return False
            self.status_tracker.status.status = allowed[status]
            if text is not None:
                self.status_tracker.status.text = text
            if publish_result is _NO_RESULT:
                self.action_server.publish_status()
            else:
                self.status_tracker.handle_destruction_time = rospy.Time.now()
                self.action_server.publish_result(self.status_tracker.status, publish_result)
            return True

    def set_accepted(self, text: str = "") -> None:
        """PENDING becomes ACTIVE (RECALLING becomes PREEMPTING)."""
        self._move({GoalStatus.PENDING: GoalStatus.ACTIVE, GoalStatus.RECALLING: GoalStatus.PREEMPTING}, text,
                   _NO_RESULT, "To transition to an active state, the goal must be in a pending or recalling state")

    def set_canceled(self, result: Any = None, text: str = "") -> None:
        """PENDING or RECALLING become RECALLED, ACTIVE or PREEMPTING become PREEMPTED; the result is sent."""
        self._move({GoalStatus.PENDING: GoalStatus.RECALLED, GoalStatus.RECALLING: GoalStatus.RECALLED,
                    GoalStatus.ACTIVE: GoalStatus.PREEMPTED, GoalStatus.PREEMPTING: GoalStatus.PREEMPTED}, text,
                   result, "To transition to a cancelled state, the goal must be in a pending, recalling, active, "
                   "or preempting state")

    def set_rejected(self, result: Any = None, text: str = "") -> None:
        """PENDING or RECALLING become REJECTED; the result is sent."""
        self._move({GoalStatus.PENDING: GoalStatus.REJECTED, GoalStatus.RECALLING: GoalStatus.REJECTED}, text, result,
                   "To transition to a rejected state, the goal must be in a pending or recalling state")

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        """ACTIVE or PREEMPTING become ABORTED; the result is sent."""
        self._move({GoalStatus.ACTIVE: GoalStatus.ABORTED, GoalStatus.PREEMPTING: GoalStatus.ABORTED}, text, result,
                   "To transition to an aborted state, the goal must be in a preempting or active state")

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        """ACTIVE or PREEMPTING become SUCCEEDED; the result is sent."""
        self._move({GoalStatus.ACTIVE: GoalStatus.SUCCEEDED, GoalStatus.PREEMPTING: GoalStatus.SUCCEEDED}, text,
                   result, "To transition to a succeeded state, the goal must be in a preempting or active state")

    def set_cancel_requested(self) -> bool:
        """A client asked to cancel: PENDING becomes RECALLING, ACTIVE becomes PREEMPTING; whether it moved."""
        return self._move({GoalStatus.PENDING: GoalStatus.RECALLING, GoalStatus.ACTIVE: GoalStatus.PREEMPTING}, None,
                          _NO_RESULT, None)

    def publish_feedback(self, feedback: Any) -> None:
        """Send feedback for this goal."""
        if not self.goal:
            rospy.logerr("Attempt to publish feedback on an uninitialized ServerGoalHandle")
            return
        assert self.status_tracker is not None
        with self.action_server.lock:
            self.action_server.publish_feedback(self.status_tracker.status, feedback)

    def get_goal(self) -> Any:
        """The goal message (the user's part), or None for an empty handle (quietly: servers ask often)."""
        return self.goal.goal if self.goal else None

    def get_goal_id(self) -> Any:
        """The goal's ``actionlib_msgs/GoalID``."""
        status = self._status("get a goal id")
        return GoalID() if status is None else status.goal_id

    def get_goal_status(self) -> Any:
        """The goal's ``actionlib_msgs/GoalStatus``."""
        status = self._status("get goal status")
        return GoalStatus() if status is None else status

    def _status(self, what: str) -> Any:
        """The goal's status (None, logged as actionlib does, for an empty handle)."""
        if not self.goal or self.status_tracker is None:
            rospy.logerr(f"Attempt to {what} on an uninitialized ServerGoalHandle")
            return None
        with self.action_server.lock:
            return self.status_tracker.status


_NO_RESULT = object()
