"""diagnostic_updater for unmodified ROS 1 scripts: a node's health on ``/diagnostics``, on rostui's rospy.

``Updater`` runs named tasks (functions or ``DiagnosticTask`` objects) and publishes their
``DiagnosticStatus`` as one ``DiagnosticArray``, at most once per ``~diagnostic_period`` seconds
(1 by default); ``FrequencyStatus``, ``TimeStampStatus`` and ``Heartbeat`` are the ready-made tasks,
``HeaderlessTopicDiagnostic``, ``TopicDiagnostic`` and ``DiagnosedPublisher`` watch a topic's rate
and stamps. The names and their behaviour are diagnostic_updater's.
"""

from __future__ import annotations

from .publisher import DiagnosedPublisher, HeaderlessTopicDiagnostic, TopicDiagnostic
from .status import DiagnosticStatusWrapper
from .tasks import CompositeDiagnosticTask, DiagnosticTask, DiagnosticTaskVector, FunctionDiagnosticTask
from .update_functions import FrequencyStatus, FrequencyStatusParam, Heartbeat, TimeStampStatus, \
    TimeStampStatusParam
from .updater import Updater

__all__ = [
    "CompositeDiagnosticTask", "DiagnosedPublisher", "DiagnosticStatusWrapper", "DiagnosticTask",
    "DiagnosticTaskVector", "FrequencyStatus", "FrequencyStatusParam", "FunctionDiagnosticTask",
    "HeaderlessTopicDiagnostic", "Heartbeat", "TimeStampStatus", "TimeStampStatusParam", "TopicDiagnostic",
    "Updater",
]
