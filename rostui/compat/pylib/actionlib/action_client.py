"""actionlib.action_client: ``ActionClient`` and the goal handles it gives, following each goal's state.

The client publishes goals on ``<ns>/goal`` and cancels on ``<ns>/cancel``, and follows the server's
``<ns>/status``, ``<ns>/result`` and ``<ns>/feedback``. Each goal's state moves through
:data:`~actionlib.states.TRANSITIONS` as statuses arrive; a goal stops being followed once no handle of
it is left, as in actionlib.
"""

from __future__ import annotations

import threading
import time
import weakref
from typing import Any, Callable

import rospy

from rostui.core.msg import get_message_class

from .spec import GoalID, action_types, queue_size_param
from .states import INVALID_TRANSITION, NO_TRANSITION, TRANSITIONS, CommState, GoalStatus

__all__ = ["ActionClient", "ClientGoalHandle", "CommStateMachine", "GoalManager"]

GoalStatusArray: Any = get_message_class("actionlib_msgs/GoalStatusArray")
Header: Any = get_message_class("std_msgs/Header")

_TERMINAL = (GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.REJECTED,
             GoalStatus.RECALLED, GoalStatus.LOST)
_DELIVERS_RESULT = (CommState.WAITING_FOR_GOAL_ACK, CommState.WAITING_FOR_CANCEL_ACK, CommState.PENDING,
                    CommState.ACTIVE, CommState.WAITING_FOR_RESULT, CommState.RECALLING, CommState.PREEMPTING)
_goal_count = 0
_goal_count_lock = threading.Lock()


class CommStateMachine:
    """One goal as the client follows it: its state, the server's latest status and its result."""

    def __init__(self, action_goal: Any, transition_cb: Callable[..., Any] | None,
                 feedback_cb: Callable[..., Any] | None, send_goal_fn: Callable[[Any], Any],
                 send_cancel_fn: Callable[[Any], Any]) -> None:
        self.action_goal = action_goal
        self.transition_cb, self.feedback_cb = transition_cb, feedback_cb
        self.send_goal_fn, self.send_cancel_fn = send_goal_fn, send_cancel_fn
        self.state = CommState.WAITING_FOR_GOAL_ACK
        self.mutex = threading.RLock()
        self.latest_goal_status = GoalStatus(status=GoalStatus.PENDING)
        self.latest_result: Any = None

    def __eq__(self, other: object) -> bool:
        return isinstance(other, CommStateMachine) and self.action_goal.goal_id.id == other.action_goal.goal_id.id

    def __hash__(self) -> int:
        return hash(self.action_goal.goal_id.id)

    def set_state(self, state: int) -> None:
        """Move to ``state`` without telling anyone."""
        self.state = state

    def transition_to(self, state: int) -> None:
        """Move to ``state`` and tell the transition callback."""
        rospy.logdebug("Transitioning to %s (from %s, goal: %s)", CommState.to_string(state),
                       CommState.to_string(self.state), self.action_goal.goal_id.id)
        self.state = state
        if self.transition_cb:
            self.transition_cb(ClientGoalHandle(self))

    def update_status(self, status_array: Any) -> None:
        """Follow a status array from the server."""
        with self.mutex:
            if self.state == CommState.DONE:
                return
            status = next((s for s in status_array.status_list if s.goal_id.id == self.action_goal.goal_id.id), None)
            if status is None:
                if self.state not in (CommState.WAITING_FOR_GOAL_ACK, CommState.WAITING_FOR_RESULT, CommState.DONE):
                    self.latest_goal_status.status = GoalStatus.LOST  # the server forgot a goal it had
                    self.transition_to(CommState.DONE)
                return
            self.latest_goal_status = status
            if status.status not in TRANSITIONS[self.state]:
                rospy.logerr("Got an unknown status from the ActionServer: %i" % status.status)
                return
            step = TRANSITIONS[self.state][status.status]
            if step == INVALID_TRANSITION:
                rospy.logerr("Invalid goal status transition from %s to %s"
                             % (CommState.to_string(self.state), GoalStatus.to_string(status.status)))
            elif step != NO_TRANSITION:
                for state in step:
                    self.transition_to(state)

    def update_result(self, action_result: Any) -> None:
        """Take the server's result for this goal: its final status, then DONE."""
        if self.action_goal.goal_id.id != action_result.status.goal_id.id:
            return
        with self.mutex:
            self.latest_goal_status = action_result.status
            self.latest_result = action_result
            if self.state in _DELIVERS_RESULT:
                self.update_status(GoalStatusArray(status_list=[action_result.status]))
                self.transition_to(CommState.DONE)
            elif self.state == CommState.DONE:
                rospy.logerr("Got a result when we were already in the DONE state")
            else:
                rospy.logerr("In a funny state: %i" % self.state)

    def update_feedback(self, action_feedback: Any) -> None:
        """Hand feedback for this goal to the feedback callback (until the goal is done)."""
        if self.action_goal.goal_id.id != action_feedback.status.goal_id.id:
            return
        if self.feedback_cb and self.state != CommState.DONE:
            self.feedback_cb(ClientGoalHandle(self), action_feedback.feedback)


class ClientGoalHandle:
    """A client's handle on one goal it sent."""

    def __init__(self, comm_state_machine: CommStateMachine | None = None) -> None:
        self.comm_state_machine = comm_state_machine

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ClientGoalHandle) or not self.comm_state_machine or not other.comm_state_machine:
            return False
        return self.comm_state_machine == other.comm_state_machine

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.comm_state_machine)

    def _machine(self, what: str) -> CommStateMachine | None:
        if self.comm_state_machine is None:
            rospy.logerr(f"Trying to {what} on an inactive ClientGoalHandle.")
        return self.comm_state_machine

    def cancel(self) -> None:
        """Ask the server to cancel this goal."""
        csm = self.comm_state_machine
        if csm is None:
            return
        with csm.mutex:
            csm.send_cancel_fn(GoalID(stamp=rospy.Time(0), id=csm.action_goal.goal_id.id))
            csm.transition_to(CommState.WAITING_FOR_CANCEL_ACK)

    def get_comm_state(self) -> int:
        """The goal's :class:`~actionlib.states.CommState` (-1 for an empty handle)."""
        csm = self._machine("get_comm_state")
        return -1 if csm is None else csm.state

    def get_goal_status(self) -> int:
        """The latest GoalStatus value the server reported."""
        csm = self._machine("get_goal_status")
        return GoalStatus.PENDING if csm is None else int(csm.latest_goal_status.status)

    def get_goal_status_text(self) -> str:
        """The server's text with its latest status."""
        csm = self._machine("get_goal_status_text")
        return "ERROR: Trying to get_goal_status_text on an inactive ClientGoalHandle." if csm is None \
            else str(csm.latest_goal_status.text)

    def get_result(self) -> Any:
        """The result message, or None until the server sent it."""
        csm = self._machine("get_result")
        if csm is None or not csm.latest_result:
            return None
        return csm.latest_result.result

    def get_terminal_state(self) -> int:
        """How the goal ended (a GoalStatus value); LOST, with an error, if its status is not terminal."""
        csm = self._machine("get_terminal_state")
        if csm is None:
            return GoalStatus.LOST
        with csm.mutex:
            if csm.state != CommState.DONE:
                rospy.logwarn("Asking for the terminal state when we're in [%s]", CommState.to_string(csm.state))
            status = int(csm.latest_goal_status.status)
            if status in _TERMINAL:
                return status
            rospy.logerr("Asking for a terminal state, but the goal status is %d", status)
            return GoalStatus.LOST


class GoalManager:
    """The goals a client follows (as weak references: a goal whose handles are all gone is dropped)."""

    def __init__(self, ActionSpec: Any) -> None:  # noqa: N803 (actionlib's name)
        self.types = action_types(ActionSpec)
        self.list_mutex = threading.RLock()
        self.statuses: weakref.WeakSet[CommStateMachine] = weakref.WeakSet()
        self.send_goal_fn: Callable[[Any], Any] = lambda _: None
        self.cancel_fn: Callable[[Any], Any] = lambda _: None

    def register_send_goal_fn(self, fn: Callable[[Any], Any]) -> None:
        """How goals are sent."""
        self.send_goal_fn = fn

    def register_cancel_fn(self, fn: Callable[[Any], Any]) -> None:
        """How cancels are sent."""
        self.cancel_fn = fn

    @staticmethod
    def _generate_id() -> Any:
        global _goal_count
        with _goal_count_lock:
            _goal_count += 1
            count = _goal_count
        now = rospy.Time.now()
        return GoalID(id="%s-%i-%.3f" % (rospy.get_caller_id(), count, now.to_sec()), stamp=now)

    def init_goal(self, goal: Any, transition_cb: Callable[..., Any] | None = None,
                  feedback_cb: Callable[..., Any] | None = None) -> ClientGoalHandle:
        """Send ``goal`` under a new id and follow it; returns its handle."""
        action_goal = self.types.action_goal(header=Header(), goal_id=self._generate_id(), goal=goal)
        action_goal.header.stamp = rospy.get_rostime()
        csm = CommStateMachine(action_goal, transition_cb, feedback_cb, self.send_goal_fn, self.cancel_fn)
        with self.list_mutex:
            self.statuses.add(csm)
        self.send_goal_fn(action_goal)
        return ClientGoalHandle(csm)

    def _each(self) -> list[CommStateMachine]:
        with self.list_mutex:
            return list(self.statuses)

    def update_statuses(self, status_array: Any) -> None:
        """Give a status array to every goal."""
        for csm in self._each():
            csm.update_status(status_array)

    def update_results(self, action_result: Any) -> None:
        """Give a result to every goal (the one it is for takes it)."""
        for csm in self._each():
            csm.update_result(action_result)

    def update_feedbacks(self, action_feedback: Any) -> None:
        """Give feedback to every goal (the one it is for takes it)."""
        for csm in self._each():
            csm.update_feedback(action_feedback)


class ActionClient:
    """Sends goals to the action server at ``ns`` and follows them: ``ActionClient(ns, XAction)``."""

    def __init__(self, ns: str, ActionSpec: Any) -> None:  # noqa: N803 (actionlib's name)
        self.ns = ns
        self.last_status_msg: Any = None
        types = action_types(ActionSpec)
        self.ActionSpec = ActionSpec
        self.ActionGoal, self.ActionResult, self.ActionFeedback = types.action_goal, types.action_result, \
            types.action_feedback
        self.Goal, self.Result, self.Feedback = types.goal, types.result, types.feedback
        pub_queue = queue_size_param("actionlib_client_pub_queue_size", 10)
        sub_queue = queue_size_param("actionlib_client_sub_queue_size", None)
        base = rospy.remap_name(ns)
        self.pub_goal = rospy.Publisher(base + "/goal", self.ActionGoal, queue_size=pub_queue)
        self.pub_cancel = rospy.Publisher(base + "/cancel", GoalID, queue_size=pub_queue)
        self.manager = GoalManager(ActionSpec)
        self.manager.register_send_goal_fn(self.pub_goal.publish)
        self.manager.register_cancel_fn(self.pub_cancel.publish)
        self.status_sub = rospy.Subscriber(base + "/status", GoalStatusArray, self._status_cb, queue_size=sub_queue)
        self.result_sub = rospy.Subscriber(base + "/result", self.ActionResult, self._result_cb, queue_size=sub_queue)
        self.feedback_sub = rospy.Subscriber(base + "/feedback", self.ActionFeedback, self._feedback_cb,
                                             queue_size=sub_queue)

    def stop(self) -> None:
        """Stop talking to the server."""
        for topic in (self.status_sub, self.result_sub, self.feedback_sub, self.pub_goal, self.pub_cancel):
            topic.unregister()

    def send_goal(self, goal: Any, transition_cb: Callable[..., Any] | None = None,
                  feedback_cb: Callable[..., Any] | None = None) -> ClientGoalHandle:
        """Send ``goal``; ``transition_cb(handle)`` on each change of state, ``feedback_cb(handle, feedback)``."""
        return self.manager.init_goal(goal, transition_cb, feedback_cb)

    def cancel_all_goals(self) -> None:
        """Ask the server to cancel every goal it has, from any client."""
        self.pub_cancel.publish(GoalID(stamp=rospy.Time.from_sec(0.0), id=""))

    def cancel_goals_at_and_before_time(self, time: Any) -> None:
        """Ask the server to cancel every goal stamped at or before ``time``."""
        self.pub_cancel.publish(GoalID(stamp=time, id=""))

    def wait_for_server(self, timeout: Any = None) -> bool:
        """Wait until a server is connected both ways (zero timeout: for ever); whether it is."""
        timeout = rospy.Duration() if timeout is None else timeout
        deadline = rospy.get_rostime() + timeout
        while not rospy.is_shutdown():
            if self._server_connected():
                return True
            if timeout != rospy.Duration(0.0) and rospy.get_rostime() >= deadline:
                return False
            time.sleep(0.01)
        return False

    wait_for_action_server_to_start = wait_for_server

    def _server_connected(self) -> bool:
        """Whether the node that sent the last status hears our goals and cancels and we hear all it sends."""
        if self.last_status_msg is None:
            return False
        server = self.last_status_msg._connection_header["callerid"]
        if not (self.pub_goal.impl.has_connection(server) and self.pub_cancel.impl.has_connection(server)):
            return False
        return all(any(c.callerid_pub == server for c in sub.impl.connections)
                   for sub in (self.status_sub, self.result_sub, self.feedback_sub))

    def _status_cb(self, msg: Any) -> None:
        self.last_status_msg = msg
        self.manager.update_statuses(msg)

    def _result_cb(self, msg: Any) -> None:
        self.manager.update_results(msg)

    def _feedback_cb(self, msg: Any) -> None:
        self.manager.update_feedbacks(msg)
