"""Diagnostic tasks: a named function that fills a status, tasks made of tasks, and the list an updater runs."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from .status import DiagnosticStatusWrapper

__all__ = ["CompositeDiagnosticTask", "DiagnosticTask", "DiagnosticTaskVector", "FunctionDiagnosticTask"]

StatusFunction = Callable[[Any], Any]


class DiagnosticTask:
    """A named task: ``run(stat)`` fills the status and returns it (this one leaves it as it is)."""

    def __init__(self, name: str) -> None:
        self.name = name

    def getName(self) -> str:  # noqa: N802 (diagnostic_updater's name)
        """The task's name."""
        return self.name

    def run(self, stat: Any) -> Any:
        """Fill *stat* and return it."""
        return stat


class FunctionDiagnosticTask(DiagnosticTask):
    """A task that is a function ``fn(stat) -> stat``."""

    def __init__(self, name: str, fn: StatusFunction) -> None:
        super().__init__(name)
        self.fn = fn

    def run(self, stat: Any) -> Any:
        """Call the function."""
        return self.fn(stat)


class CompositeDiagnosticTask(DiagnosticTask):
    """Tasks run one after another on one status: each starts from the status's first summary, the key-values
    add up, and the summaries are merged (the worse level wins)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.tasks: list[DiagnosticTask] = []

    def run(self, stat: Any) -> Any:
        """Run every task, then give the status the merged summary."""
        combined = DiagnosticStatusWrapper()
        original = DiagnosticStatusWrapper()
        original.summary(stat)
        for task in self.tasks:
            stat.summary(original)
            stat = task.run(stat)
            combined.mergeSummary(stat)
        stat.summary(combined)
        return stat

    def addTask(self, t: DiagnosticTask) -> None:  # noqa: N802 (diagnostic_updater's name)
        """Add a task."""
        self.tasks.append(t)


class _NamedTask:
    """A task as the vector keeps it: a name and the function that fills a status (naming it first)."""

    def __init__(self, name: str, fn: StatusFunction) -> None:
        self.name = name
        self.fn = fn

    def run(self, stat: Any) -> Any:
        stat.name = self.name
        return self.fn(stat)


class DiagnosticTaskVector:
    """Named tasks in the order they were added."""

    DiagnosticTaskInternal = _NamedTask

    def __init__(self) -> None:
        self.tasks: list[_NamedTask] = []
        self.lock = threading.Lock()

    def addedTaskCallback(self, task: _NamedTask) -> None:  # noqa: N802 (diagnostic_updater's name)
        """Called with each task added."""

    def add(self, *args: Any) -> None:
        """``add(task)`` (a DiagnosticTask) or ``add(name, fn)``."""
        if len(args) == 1:
            task = _NamedTask(args[0].getName(), args[0].run)
        else:
            task = _NamedTask(args[0], args[1])
        with self.lock:
            self.tasks.append(task)
            self.addedTaskCallback(task)

    def removeByName(self, name: str) -> bool:  # noqa: N802 (diagnostic_updater's name)
        """Remove the first task named *name*; whether there was one."""
        with self.lock:
            for index, task in enumerate(self.tasks):
                if task.name == name:
                    del self.tasks[index]
                    return True
        return False
