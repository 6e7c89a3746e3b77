"""A launch's command-line options, shared by the supervisor and the remote launches it owns."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["SupervisorOptions"]


@dataclass
class SupervisorOptions:
    """Command-line options of a launch."""

    screen: bool = False
    verbose: bool = False
    wait: bool = False
    port: int | None = None
    sigint_timeout: float = 15.0
    sigterm_timeout: float = 2.0
    capture: bool = False
    """Nodes' stdout and stderr into their output rings (the monitor owns the terminal)."""
    handle_signals: bool = True
    """Ctrl-C, SIGTERM and SIGHUP stop the launch (off when the monitor handles them)."""
    stay_when_all_ended: bool = False
    """Keep the launch (and the master) up when every node has ended, so nodes can be started again."""
