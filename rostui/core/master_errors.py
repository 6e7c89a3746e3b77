"""What a node's calls to its master raise."""

from __future__ import annotations

__all__ = ["MasterError", "MasterRefusedError", "MasterUnreachableError", "unreachable_text"]


def unreachable_text(master_uri: str, cause: str = "") -> str:
    """The one sentence every rostui tool and API says when the master does not answer (rostopic's words),
    then ``: cause`` when one is given."""
    return f"Unable to communicate with master at {master_uri}" + (f": {cause}" if cause else "")


class MasterError(Exception):
    """The master could not be reached or refused a call."""


class MasterUnreachableError(MasterError):
    """The master did not answer at all (down, wrong URI, network, too slow): the one error for it, in every layer.

    Its text is :func:`unreachable_text`.
    """

    def __init__(self, master_uri: str, cause: str = "") -> None:
        self.master_uri = master_uri
        self.cause = cause
        super().__init__(unreachable_text(master_uri, cause))


class MasterRefusedError(MasterError):
    """The master answered with a failure code (e.g. no such parameter or service)."""
