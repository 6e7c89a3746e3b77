"""What a live view knows of its link to the master, and how its status line says it."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["SourceState"]


@dataclass(frozen=True)
class SourceState:
    """``waiting`` (no master yet), ``connected`` or ``lost``, with the master's URI and a one-line detail."""

    status: str
    master_uri: str
    detail: str = ""

    def text(self, marks: bool = False) -> str:
        """One line for a status bar; with ``marks`` a leading ●, ✖ or … and, once connected, no URI."""
        if self.status == "connected":
            return "● master" if marks else f"master {self.master_uri}"
        if self.status == "lost":
            return ("✖ " if marks else "") + f"master {self.master_uri} gone: waiting for it to come back"
        return (("… " if marks else "") + f"waiting for master {self.master_uri}"
                + (f" ({self.detail})" if self.detail else ""))
