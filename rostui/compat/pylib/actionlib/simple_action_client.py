"""actionlib.simple_action_client: ``SimpleActionClient``, one goal at a time with done, active and feedback calls."""

from __future__ import annotations

import threading
from typing import Any, Callable

import rospy

from .action_client import ActionClient, ClientGoalHandle
from .states import CommState, GoalStatus, SimpleGoalState

__all__ = ["SimpleActionClient"]


class SimpleActionClient:
    """``SimpleActionClient(ns, XAction)``: send a goal, wait for its result, cancel it.

    Sending a goal stops following the previous one. ``get_state()`` reports RECALLING as PENDING and
    PREEMPTING as ACTIVE, and LOST before any goal was sent.
    """

    def __init__(self, ns: str, ActionSpec: Any) -> None:  # noqa: N803 (actionlib's name)
        self.action_client = ActionClient(ns, ActionSpec)
        self.simple_state = SimpleGoalState.DONE
        self.gh: ClientGoalHandle | None = None
        self.done_condition = threading.Condition()
        self.done_cb: Callable[..., Any] | None = None
        self.active_cb: Callable[..., Any] | None = None
        self.feedback_cb: Callable[..., Any] | None = None

    def wait_for_server(self, timeout: Any = None) -> bool:
        """Wait until the server is connected (zero or no timeout: for ever); whether it is."""
        return self.action_client.wait_for_server(rospy.Duration() if timeout is None else timeout)

    def send_goal(self, goal: Any, done_cb: Callable[..., Any] | None = None,
                  active_cb: Callable[..., Any] | None = None, feedback_cb: Callable[..., Any] | None = None) -> None:
        """Send ``goal``: ``done_cb(status, result)`` at the end, ``active_cb()`` once active, ``feedback_cb(fb)``."""
        self.stop_tracking_goal()
        self.done_cb, self.active_cb, self.feedback_cb = done_cb, active_cb, feedback_cb
        self.simple_state = SimpleGoalState.PENDING
        self.gh = self.action_client.send_goal(goal, self._handle_transition, self._handle_feedback)

    def send_goal_and_wait(self, goal: Any, execute_timeout: Any = None, preempt_timeout: Any = None) -> int:
        """Send ``goal`` and wait for it; past ``execute_timeout`` cancel it and wait ``preempt_timeout``; its state."""
        execute_timeout = rospy.Duration() if execute_timeout is None else execute_timeout
        preempt_timeout = rospy.Duration() if preempt_timeout is None else preempt_timeout
        self.send_goal(goal)
        if not self.wait_for_result(execute_timeout):
            rospy.logdebug("Canceling goal")
            self.cancel_goal()
            if self.wait_for_result(preempt_timeout):
                rospy.logdebug("Preempt finished within specified preempt_timeout [%.2f]", preempt_timeout.to_sec())
            else:
                rospy.logdebug("Preempt didn't finish specified preempt_timeout [%.2f]", preempt_timeout.to_sec())
        return self.get_state()

    def wait_for_result(self, timeout: Any = None) -> bool:
        """Wait until the goal is done (zero or no timeout: for ever); whether it is."""
        if not self.gh:
            rospy.logerr("Called wait_for_result when no goal exists")
            return False
        timeout = rospy.Duration() if timeout is None else timeout
        deadline = rospy.get_rostime() + timeout
        step = rospy.Duration(0.1)
        with self.done_condition:
            while not rospy.is_shutdown():
                left = deadline - rospy.get_rostime()
                if timeout > rospy.Duration(0.0) and left <= rospy.Duration(0.0):
                    break
                if self.simple_state == SimpleGoalState.DONE:
                    break
                if left > step or timeout == rospy.Duration():
                    left = step
                self.done_condition.wait(left.to_sec())
        return self.simple_state == SimpleGoalState.DONE

    def get_result(self) -> Any:
        """The result of the goal, or None before it came."""
        if not self.gh:
            rospy.logerr("Called get_result when no goal is running")
            return None
        return self.gh.get_result()

    def get_state(self) -> int:
        """The goal's GoalStatus value, as a simple client sees it."""
        if not self.gh:
            rospy.logerr("Called get_state when no goal is running")
            return GoalStatus.LOST
        status = self.gh.get_goal_status()
        if status == GoalStatus.RECALLING:
            return GoalStatus.PENDING
        if status == GoalStatus.PREEMPTING:
            return GoalStatus.ACTIVE
        return status

    def get_goal_status_text(self) -> str:
        """The server's text with the goal's latest status."""
        if not self.gh:
            rospy.logerr("Called get_goal_status_text when no goal is running")
            return "ERROR: Called get_goal_status_text when no goal is running"
        return self.gh.get_goal_status_text()

    def cancel_all_goals(self) -> None:
        """Ask the server to cancel every goal."""
        self.action_client.cancel_all_goals()

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        """Ask the server to cancel the goals stamped at or before ``time``."""
        self.action_client.cancel_goals_at_and_before_time(time)

    def cancel_goal(self) -> None:
        """Ask the server to cancel this client's goal."""
        if self.gh:
            self.gh.cancel()

    def stop_tracking_goal(self) -> None:
        """Forget the current goal (its callbacks stop)."""
        self.gh = None

    def _set_simple_state(self, state: int) -> None:
        self.simple_state = state

    def _handle_transition(self, gh: ClientGoalHandle) -> None:
        comm_state = gh.get_comm_state()
        error = ("Received comm state %s when in simple state %s with SimpleActionClient in NS %s"
                 % (CommState.to_string(comm_state), SimpleGoalState.to_string(self.simple_state),
                    rospy.resolve_name(self.action_client.ns)))
        if comm_state in (CommState.ACTIVE, CommState.PREEMPTING):
            if self.simple_state == SimpleGoalState.PENDING:
                self._set_simple_state(SimpleGoalState.ACTIVE)
                if self.active_cb:
                    self.active_cb()
            elif self.simple_state == SimpleGoalState.DONE:
                rospy.logerr(error)
        elif comm_state == CommState.RECALLING:
            if self.simple_state != SimpleGoalState.PENDING:
                rospy.logerr(error)
        elif comm_state == CommState.DONE:
            if self.simple_state in (SimpleGoalState.PENDING, SimpleGoalState.ACTIVE):
                self._set_simple_state(SimpleGoalState.DONE)
                if self.done_cb:
                    self.done_cb(gh.get_goal_status(), gh.get_result())
                with self.done_condition:
                    self.done_condition.notify_all()
            elif self.simple_state == SimpleGoalState.DONE:
                rospy.logerr("SimpleActionClient received DONE twice")

    def _handle_feedback(self, gh: ClientGoalHandle, feedback: Any) -> None:
        if not self.gh:
            return  # feedback of a goal no longer followed, in the moment before a new one is sent
        if gh != self.gh:
            rospy.logerr("Got a feedback callback on a goal handle that we're not tracking. %s vs %s"
                         % (self.gh.comm_state_machine.action_goal.goal_id.id,  # type: ignore[union-attr]
                            gh.comm_state_machine.action_goal.goal_id.id))  # type: ignore[union-attr]
            return
        if self.feedback_cb:
            self.feedback_cb(feedback)
