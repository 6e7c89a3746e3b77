"""actionlib.simple_action_server: ``SimpleActionServer``, one goal at a time, run by an execute callback.

With ``execute_cb`` a thread of the server's own takes the next goal (checking every 0.1 s) and calls
``execute_cb(goal)``; the callback ends the goal with ``set_succeeded``, ``set_aborted`` or
``set_preempted`` (a callback that returns without doing so gets its goal aborted, one that raises is
logged and aborted). A newer goal preempts the current one and replaces a pending one. Without
``execute_cb`` the user's goal and preempt callbacks call ``accept_new_goal`` themselves.
"""

from __future__ import annotations

import threading
import traceback
from typing import Any, Callable

import rospy

from .action_server import ActionServer
from .server_goal_handle import ServerGoalHandle
from .states import GoalStatus

__all__ = ["SimpleActionServer"]

_REPLACED = "This goal was canceled because another goal was received by the simple action server"
_LOOP_SECONDS = 0.1


class SimpleActionServer:
    """``SimpleActionServer(name, XAction, execute_cb=None, auto_start=True)``."""

    def __init__(self, name: str, ActionSpec: Any, execute_cb: Callable[[Any], Any] | None = None,  # noqa: N803
                 auto_start: bool = True) -> None:
        self.new_goal = False
        self.preempt_request = False
        self.new_goal_preempt_request = False
        self.execute_callback = execute_cb
        self.goal_callback: Callable[[], Any] | None = None
        self.preempt_callback: Callable[[], Any] | None = None
        self.need_to_terminate = False
        self.terminate_mutex = threading.RLock()
        # the action server calls in holding its own lock: take ours only after it, never the other way round
        self.lock = threading.RLock()
        self.execute_condition = threading.Condition(self.lock)
        self.current_goal = ServerGoalHandle()
        self.next_goal = ServerGoalHandle()
        self.execute_thread: threading.Thread | None = None
        if self.execute_callback:
            self.execute_thread = threading.Thread(target=self.executeLoop, daemon=True,
                                                   name=f"SimpleActionServer {name}")
            self.execute_thread.start()
        self.action_server = ActionServer(name, ActionSpec, self.internal_goal_callback,
                                          self.internal_preempt_callback, auto_start)

    def __del__(self) -> None:
        if hasattr(self, "execute_callback") and self.execute_callback:
            with self.terminate_mutex:
                self.need_to_terminate = True

    def accept_new_goal(self) -> Any:
        """Take the next goal (the current one, if active, is canceled); returns the goal message."""
        with self.action_server.lock, self.lock:
            if not self.new_goal or not self.next_goal.get_goal():
                rospy.logerr("Attempting to accept the next goal when a new goal is not available")
                return None
            if self.is_active() and self.current_goal.get_goal() and self.current_goal != self.next_goal:
                self.current_goal.set_canceled(None, _REPLACED)
            rospy.logdebug("Accepting a new goal")
            self.current_goal = self.next_goal
            self.new_goal = False
            self.preempt_request = self.new_goal_preempt_request
            self.new_goal_preempt_request = False
            self.current_goal.set_accepted("This goal has been accepted by the simple action server")
            return self.current_goal.get_goal()

    def is_new_goal_available(self) -> bool:
        """Whether a goal waits to be accepted."""
        return self.new_goal

    def is_preempt_requested(self) -> bool:
        """Whether the current goal was asked to stop (canceled, or a newer goal came)."""
        return self.preempt_request

    def is_active(self) -> bool:
        """Whether a goal is being worked on (ACTIVE or PREEMPTING)."""
        if not self.current_goal.get_goal():
            return False
        status = self.current_goal.get_goal_status().status
        return status in (GoalStatus.ACTIVE, GoalStatus.PREEMPTING)

    def get_default_result(self) -> Any:
        """A default-constructed result."""
        return self.action_server.ActionResultType().result

    def _result(self, result: Any) -> Any:
        return result if result else self.get_default_result()  # actionlib takes any falsy result for none

    def set_succeeded(self, result: Any = None, text: str = "") -> None:
        """End the current goal as SUCCEEDED."""
        with self.action_server.lock, self.lock:
            self.current_goal.set_succeeded(self._result(result), text)

    def set_aborted(self, result: Any = None, text: str = "") -> None:
        """End the current goal as ABORTED."""
        with self.action_server.lock, self.lock:
            self.current_goal.set_aborted(self._result(result), text)

    def set_preempted(self, result: Any = None, text: str = "") -> None:
        """End the current goal as PREEMPTED (canceled)."""
        with self.action_server.lock, self.lock:
            rospy.logdebug("Setting the current goal as canceled")
            self.current_goal.set_canceled(self._result(result), text)

    def publish_feedback(self, feedback: Any) -> None:
        """Send feedback for the current goal."""
        self.current_goal.publish_feedback(feedback)

    def register_goal_callback(self, cb: Callable[[], Any]) -> None:
        """Call ``cb()`` when a goal comes (not with an execute callback)."""
        if self.execute_callback:
            rospy.logwarn("Cannot call SimpleActionServer.register_goal_callback() because an executeCallback "
                          "exists. Not going to register it.")
        else:
            self.goal_callback = cb

    def register_preempt_callback(self, cb: Callable[[], Any]) -> None:
        """Call ``cb()`` when the current goal is asked to stop."""
        self.preempt_callback = cb

    def start(self) -> None:
        """Start serving."""
        self.action_server.start()

    def internal_goal_callback(self, goal: ServerGoalHandle) -> None:
        """A goal came: it becomes the next one if it is newer than the current and the next."""
        with self.execute_condition:
            try:
                rospy.logdebug("A new goal %shas been recieved by the single goal action server",
                               goal.get_goal_id().id)
                newer_than_current = (not self.current_goal.get_goal()
                                      or goal.get_goal_id().stamp >= self.current_goal.get_goal_id().stamp)
                newer_than_next = (not self.next_goal.get_goal()
                                   or goal.get_goal_id().stamp >= self.next_goal.get_goal_id().stamp)
                if not (newer_than_current and newer_than_next):
                    goal.set_canceled(None, _REPLACED)
                    return
                if self.next_goal.get_goal() and (not self.current_goal.get_goal()
                                                  or self.next_goal != self.current_goal):
                    self.next_goal.set_canceled(None, _REPLACED)
                self.next_goal = goal
                self.new_goal = True
                self.new_goal_preempt_request = False
                if self.is_active():
                    self.preempt_request = True
                    if self.preempt_callback:
                        self.preempt_callback()
                if self.goal_callback:
                    self.goal_callback()
                self.execute_condition.notify()
            except Exception as exc:  # noqa: BLE001 (actionlib logs a failing user callback and goes on)
                rospy.logerr("SimpleActionServer.internal_goal_callback - exception %s", str(exc))

    def internal_preempt_callback(self, preempt: ServerGoalHandle) -> None:
        """A client asked to cancel: flag the current goal, or the next one."""
        with self.lock:
            rospy.logdebug("A preempt has been received by the SimpleActionServer")
            if preempt == self.current_goal:
                rospy.logdebug("Setting preempt_request bit for the current goal to TRUE and invoking callback")
                self.preempt_request = True
                if self.preempt_callback:
                    self.preempt_callback()
            elif preempt == self.next_goal:
                rospy.logdebug("Setting preempt request bit for the next goal to TRUE")
                self.new_goal_preempt_request = True

    def executeLoop(self) -> None:  # noqa: N802 (actionlib's name)
        """The execute thread: take each new goal and run the execute callback on it."""
        while not rospy.is_shutdown():
            with self.terminate_mutex:
                if self.need_to_terminate:
                    break
            if self.is_active():
                rospy.logerr("Should never reach this code with an active goal")
                return
            if self.is_new_goal_available():
                goal = self.accept_new_goal()
                if not self.execute_callback:
                    rospy.logerr("execute_callback_ must exist. This is a bug in SimpleActionServer")
                    return
                try:
                    self.execute_callback(goal)
                    if self.is_active():
                        rospy.logwarn("Your executeCallback did not set the goal to a terminal status.  "
                                      "This is a bug in your ActionServer implementation. Fix your code!  "
                                      "For now, the ActionServer will set this goal to aborted")
                        self.set_aborted(None, "No terminal state was set.")
                except Exception as exc:  # noqa: BLE001 (a failing callback aborts its goal, as in actionlib)
                    rospy.logerr("Exception in your execute callback: %s\n%s", str(exc), traceback.format_exc())
                    self.set_aborted(None, "Exception in execute callback: %s" % str(exc))
            with self.execute_condition:
                self.execute_condition.wait(_LOOP_SECONDS)
