"""What a node's calls to its master raise."""

from __future__ import annotations

__all__ = ["MasterError", "MasterRefusedError", "MasterUnreachableError"]


class MasterError(Exception):
    """The master could not be reached or refused a call."""


class MasterUnreachableError(MasterError):
    """The master did not answer at all (down, wrong URI, network)."""


class MasterRefusedError(MasterError):
    """The master answered with a failure code (e.g. no such parameter or service)."""
