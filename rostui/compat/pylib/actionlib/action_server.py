"""actionlib.action_server: ``ActionServer``, goals in from clients, status, feedback and results out.

Goals arrive on ``<ns>/goal`` and cancels on ``<ns>/cancel``; the server keeps the latched
``<ns>/status`` array (every goal it knows, sent on each change and at ``actionlib_status_frequency``,
5 Hz unless set), ``<ns>/feedback`` and ``<ns>/result``. A goal that ended stays in the status array for
``<ns>/status_list_timeout`` seconds (5). A cancel with an empty id and zero stamp cancels everything; one
with an id cancels that goal (remembered as RECALLING if the goal has not come yet); one with a stamp
cancels every goal stamped at or before it, and goals that arrive later with an older stamp.
"""

from __future__ import annotations

import threading
from typing import Any, Callable

import rospy

from rostui.core.msg import get_message_class

from .server_goal_handle import ServerGoalHandle, StatusTracker
from .spec import action_types, queue_size_param
from .states import GoalStatus

__all__ = ["ActionServer", "nop_cb"]

GoalIDType: Any = get_message_class("actionlib_msgs/GoalID")
GoalStatusArray: Any = get_message_class("actionlib_msgs/GoalStatusArray")

_DEFAULT_STATUS_HZ = 5.0
_DEFAULT_STATUS_LIST_TIMEOUT = 5.0
_CANCELED_BY_STAMP = ("This goal handle was canceled by the action server because its timestamp is before the "
                      "timestamp of the last cancel request")


def nop_cb(goal_handle: Any) -> None:
    """A callback that does nothing (the default cancel callback)."""


class ActionServer:
    """``ActionServer(ns, XAction, goal_cb, cancel_cb=nop_cb, auto_start=True)``: call ``start()`` to serve."""

    def __init__(self, ns: str, ActionSpec: Any, goal_cb: Callable[[Any], Any],  # noqa: N803 (actionlib's name)
                 cancel_cb: Callable[[Any], Any] = nop_cb, auto_start: bool = True) -> None:
        self.ns = ns
        types = action_types(ActionSpec)
        self.ActionSpec = ActionSpec
        self.ActionGoal, self.ActionResultType, self.ActionFeedback = types.action_goal, types.action_result, \
            types.action_feedback
        self.ActionResult = self.ActionResultType
        self.goal_callback, self.cancel_callback = goal_cb, cancel_cb
        self.lock = threading.RLock()
        self.status_list: list[StatusTracker] = []
        self.last_cancel = rospy.Time()
        self.status_list_timeout = rospy.Duration()
        self.started = False
        self.status_timer: Any = None
        if auto_start:
            rospy.logwarn("You've passed in true for auto_start to the python action server, you should always pass "
                          "in false to avoid race conditions.")
            self.start()

    def register_goal_callback(self, cb: Callable[[Any], Any]) -> None:
        """Call ``cb(goal_handle)`` for each new goal."""
        self.goal_callback = cb

    def register_cancel_callback(self, cancel_cb: Callable[[Any], Any]) -> None:
        """Call ``cancel_cb(goal_handle)`` for each goal a client asks to cancel."""
        self.cancel_callback = cancel_cb

    def start(self) -> None:
        """Advertise, subscribe and start publishing status."""
        with self.lock:
            self.initialize()
            self.started = True
            self.publish_status()

    def stop(self) -> None:
        """Stop the status timer."""
        if self.status_timer is not None:
            self.status_timer.shutdown()

    def initialize(self) -> None:
        """Make the publishers, subscribers and status timer (``start`` calls it)."""
        pub_queue = queue_size_param("actionlib_server_pub_queue_size", 50)
        sub_queue = queue_size_param("actionlib_server_sub_queue_size", None)
        base = rospy.remap_name(self.ns)
        self.status_pub = rospy.Publisher(base + "/status", GoalStatusArray, latch=True, queue_size=pub_queue)
        self.result_pub = rospy.Publisher(base + "/result", self.ActionResultType, queue_size=pub_queue)
        self.feedback_pub = rospy.Publisher(base + "/feedback", self.ActionFeedback, queue_size=pub_queue)
        self.goal_sub = rospy.Subscriber(base + "/goal", self.ActionGoal, self.internal_goal_callback,
                                         queue_size=sub_queue)
        self.cancel_sub = rospy.Subscriber(base + "/cancel", GoalIDType, self.internal_cancel_callback,
                                           queue_size=sub_queue)
        if rospy.has_param(base + "/status_frequency"):
            self.status_frequency = float(rospy.get_param(base + "/status_frequency", _DEFAULT_STATUS_HZ))
            rospy.logwarn("You're using the deprecated status_frequency parameter, please switch to "
                          "actionlib_status_frequency.")
        else:
            found = rospy.search_param("actionlib_status_frequency")
            self.status_frequency = _DEFAULT_STATUS_HZ if found is None else float(
                rospy.get_param(found, _DEFAULT_STATUS_HZ))
        self.status_list_timeout = rospy.Duration(
            float(rospy.get_param(base + "/status_list_timeout", _DEFAULT_STATUS_LIST_TIMEOUT)))
        self.status_timer = rospy.Timer(rospy.Duration(1.0 / self.status_frequency), self.publish_status_async)

    def publish_result(self, status: Any, result: Any) -> None:
        """Send a result (no result: the action's default one), then the status array."""
        with self.lock:
            message = self.ActionResultType()
            message.header.stamp = rospy.Time.now()
            message.status = status
            message.result = result if result is not None else self.ActionResultType().result
            if not rospy.is_shutdown():
                self.result_pub.publish(message)
            self.publish_status()

    def publish_feedback(self, status: Any, feedback: Any) -> None:
        """Send feedback for the goal whose status is ``status``."""
        with self.lock:
            message = self.ActionFeedback()
            message.header.stamp = rospy.Time.now()
            message.status = status
            message.feedback = feedback
            if not rospy.is_shutdown():
                self.feedback_pub.publish(message)

    def internal_cancel_callback(self, goal_id: Any) -> None:
        """A cancel request from a client."""
        with self.lock:
            if not self.started:
                return
            rospy.logdebug("The action server has received a new cancel request")
            found = False
            everything = goal_id.id == "" and goal_id.stamp == rospy.Time()
            for tracker in list(self.status_list):
                this_one = goal_id.id == tracker.status.goal_id.id
                older = goal_id.stamp != rospy.Time() and tracker.status.goal_id.stamp <= goal_id.stamp
                if everything or this_one or older:
                    found = found or this_one
                    handle = ServerGoalHandle(tracker, self)
                    if handle.set_cancel_requested():
                        self.cancel_callback(handle)
            if goal_id.id != "" and not found:
                tracker = StatusTracker(goal_id, GoalStatus.RECALLING)  # the goal may come after its cancel
                tracker.handle_destruction_time = rospy.Time.now()
                self.status_list.append(tracker)
            if goal_id.stamp > self.last_cancel:
                self.last_cancel = goal_id.stamp

    def internal_goal_callback(self, goal: Any) -> None:
        """A new goal from a client."""
        with self.lock:
            if not self.started:
                return
            rospy.logdebug("The action server has received a new goal request")
            for tracker in self.status_list:
                if goal.goal_id.id == tracker.status.goal_id.id:
                    rospy.logdebug("Goal %s was already in the status list with status %i"
                                   % (goal.goal_id.id, tracker.status.status))
                    if tracker.status.status == GoalStatus.RECALLING:
                        tracker.status.status = GoalStatus.RECALLED
                        self.publish_result(tracker.status, self.ActionResultType().result)
                    if tracker.goal is None:  # a cancel made it: it goes after the timeout from now
                        tracker.handle_destruction_time = rospy.Time.now()
                    return
            tracker = StatusTracker(None, None, goal)
            self.status_list.append(tracker)
            handle = ServerGoalHandle(tracker, self)
            if goal.goal_id.stamp != rospy.Time() and goal.goal_id.stamp <= self.last_cancel:
                handle.set_canceled(None, _CANCELED_BY_STAMP)
            else:
                self.goal_callback(handle)

    def publish_status_async(self, event: Any = None) -> None:
        """The status timer's tick."""
        with self.lock:
            if not rospy.is_shutdown():
                self.publish_status()

    def publish_status(self) -> None:
        """Send the status array: every goal known, less those that ended more than the timeout ago."""
        with self.lock:
            now = rospy.Time.now()
            self.status_list = [t for t in self.status_list if t.handle_destruction_time == rospy.Time()
                                or not t.handle_destruction_time + self.status_list_timeout < now]
            array = GoalStatusArray(status_list=[t.status for t in self.status_list])
            array.header.stamp = now
            if not rospy.is_shutdown():
                self.status_pub.publish(array)
