"""Topic watchers: a topic's rate (``HeaderlessTopicDiagnostic``), with its stamps (``TopicDiagnostic``), and a
publisher that ticks both as it publishes (``DiagnosedPublisher``)."""

from __future__ import annotations

from typing import Any

from .tasks import CompositeDiagnosticTask, DiagnosticTaskVector
from .update_functions import FrequencyStatus, FrequencyStatusParam, TimeStampStatus, TimeStampStatusParam

__all__ = ["DiagnosedPublisher", "HeaderlessTopicDiagnostic", "TopicDiagnostic"]


class HeaderlessTopicDiagnostic(CompositeDiagnosticTask):
    """"<name> topic status": the rate of ``tick()`` against *freq*, added to the updater *diag* at once."""

    def __init__(self, name: str, diag: DiagnosticTaskVector, freq: FrequencyStatusParam) -> None:
        super().__init__(name + " topic status")
        self.diag = diag
        self.freq = FrequencyStatus(freq)
        self.addTask(self.freq)
        self.diag.add(self)

    def tick(self) -> None:
        """Count one message."""
        self.freq.tick()

    def clear_window(self) -> None:
        """Start measuring the rate again."""
        self.freq.clear()


class TopicDiagnostic(HeaderlessTopicDiagnostic):
    """A topic's rate and its messages' stamps."""

    def __init__(self, name: str, diag: DiagnosticTaskVector, freq: FrequencyStatusParam,
                 stamp: TimeStampStatusParam) -> None:
        super().__init__(name, diag, freq)
        self.stamp = TimeStampStatus(stamp)
        self.addTask(self.stamp)

    def tick(self, stamp: Any) -> None:  # type: ignore[override]  # diagnostic_updater's signature
        """Count one message with this stamp."""
        self.stamp.tick(stamp)
        super().tick()


class DiagnosedPublisher(TopicDiagnostic):
    """A rospy Publisher whose ``publish`` counts each message and its ``header.stamp``."""

    def __init__(self, pub: Any, diag: DiagnosticTaskVector, freq: FrequencyStatusParam,
                 stamp: TimeStampStatusParam) -> None:
        super().__init__(pub.name, diag, freq, stamp)
        self.publisher = pub

    def publish(self, message: Any) -> None:
        """Tick with the message's stamp, then publish it."""
        self.tick(message.header.stamp)
        self.publisher.publish(message)
