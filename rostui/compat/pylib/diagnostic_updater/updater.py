"""``Updater``: runs a node's diagnostic tasks and publishes their statuses on ``/diagnostics``."""

from __future__ import annotations

from typing import Any

import rospy

from .status import DiagnosticArray, DiagnosticStatusWrapper
from .tasks import DiagnosticTaskVector, _NamedTask

__all__ = ["Updater"]

ERROR = 2
PERIOD_PARAM = "~diagnostic_period"
PERIOD_CHECK = 0.25
"""Seconds between two reads of ``~diagnostic_period``."""
NO_HWID_WARNING = (
    "diagnostic_updater: No HW_ID was set. This is probably a bug. Please report it. For devices that do not have a "
    "HW_ID, set this value to 'none'. This warning only occurs once all diagnostics are OK so it is okay to wait "
    "until the device is open before calling setHardwareID.")


class Updater(DiagnosticTaskVector):
    """Publishes every task's status on ``/diagnostics``: ``update()`` at most once per period, ``force_update()``
    at once; each status is named ``<node>: <task>``."""

    def __init__(self) -> None:
        super().__init__()
        self.publisher = rospy.Publisher("/diagnostics", DiagnosticArray, queue_size=10)
        self.last_time = rospy.Time.now()
        self.last_time_period_checked = self.last_time
        self.period: float = 1
        self.verbose = False
        self.hwid = ""
        self.warn_nohwid_done = False

    def update(self) -> None:
        """Publish the statuses if a period has passed since the last time."""
        self._check_diagnostic_period()
        if rospy.Time.now() >= self.last_time + rospy.Duration(self.period):
            self.force_update()

    def force_update(self) -> None:
        """Run every task now and publish their statuses (a task that sets nothing says ERROR "No message was set")."""
        self.last_time = rospy.Time.now()
        warn_nohwid = not self.hwid
        statuses = []
        with self.lock:
            for task in self.tasks:
                status = DiagnosticStatusWrapper()
                status.name = task.name
                status.level = ERROR
                status.message = "No message was set"
                status.hardware_id = self.hwid
                task.run(status)
                statuses.append(status)
                if status.level:
                    warn_nohwid = False
                if self.verbose and status.level:
                    rospy.logwarn("Non-zero diagnostic status. Name: '%s', status %i: '%s'"
                                  % (status.name, status.level, status.message))
        if warn_nohwid and not self.warn_nohwid_done:
            rospy.logwarn(NO_HWID_WARNING)
            self.warn_nohwid_done = True
        self.publish(statuses)

    def broadcast(self, lvl: int, msg: str) -> None:
        """Publish one status per task, each with this level and message."""
        statuses = []
        for task in self.tasks:
            status = DiagnosticStatusWrapper()
            status.name = task.name
            status.summary(lvl, msg)
            statuses.append(status)
        self.publish(statuses)

    def setHardwareID(self, hwid: str) -> None:  # noqa: N802 (diagnostic_updater's name)
        """The hardware id every status carries."""
        self.hwid = hwid

    def _check_diagnostic_period(self) -> None:
        now = rospy.Time.now()
        if now >= self.last_time_period_checked + rospy.Duration(PERIOD_CHECK):
            self.period = rospy.get_param_cached(PERIOD_PARAM, 1)
            self.last_time_period_checked = now

    def publish(self, msg: Any) -> None:
        """Publish one status or a list of them as a DiagnosticArray stamped now, their names prefixed with the
        node's."""
        statuses = msg if type(msg) is list else [msg]
        for stat in statuses:
            stat.name = rospy.get_name()[1:] + ": " + stat.name
        array = DiagnosticArray()
        array.status = statuses
        array.header.stamp = rospy.Time.now()
        self.publisher.publish(array)

    def addedTaskCallback(self, task: _NamedTask) -> None:  # noqa: N802 (diagnostic_updater's name)
        """Say at once that the new task is starting up (level OK)."""
        stat = DiagnosticStatusWrapper()
        stat.name = task.name
        stat.summary(0, "Node starting up")
        self.publish(stat)
