"""actionlib's states: the client's communication states, terminal and simple states, and GoalStatus names.

``CommState`` follows one goal on the client side; :data:`TRANSITIONS` says, for each communication
state and each status the server reports, which states the client passes through (in order), or that
nothing changes (:data:`NO_TRANSITION`), or that the report makes no sense there (:data:`INVALID_TRANSITION`).
"""

from __future__ import annotations

from typing import Any

from rostui.core.msg import get_message_class

__all__ = ["CommState", "GoalStatus", "INVALID_TRANSITION", "NO_TRANSITION", "SimpleGoalState", "TerminalState",
           "TRANSITIONS", "get_name_of_constant"]

GoalStatus: Any = get_message_class("actionlib_msgs/GoalStatus")

NO_TRANSITION = -1
"""The status changes nothing in this state."""
INVALID_TRANSITION = -2
"""The server reported a status that cannot follow this state (logged as an error, ignored)."""


def get_name_of_constant(C: Any, n: int) -> str:
    """The name of the integer constant ``n`` of class ``C`` (``NO_SUCH_STATE_<n>`` when there is none)."""
    for name, value in vars(C).items():
        if type(value) is int and value == n:
            return name
    return "NO_SUCH_STATE_%d" % n


class CommState:
    """Where a goal is in the client's exchange with the server."""

    WAITING_FOR_GOAL_ACK = 0
    PENDING = 1
    ACTIVE = 2
    WAITING_FOR_RESULT = 3
    WAITING_FOR_CANCEL_ACK = 4
    RECALLING = 5
    PREEMPTING = 6
    DONE = 7
    LOST = 8
    to_string = classmethod(get_name_of_constant)


class TerminalState:
    """How a goal ended (GoalStatus's terminal values, and LOST)."""

    RECALLED = GoalStatus.RECALLED
    REJECTED = GoalStatus.REJECTED
    PREEMPTED = GoalStatus.PREEMPTED
    ABORTED = GoalStatus.ABORTED
    SUCCEEDED = GoalStatus.SUCCEEDED
    LOST = GoalStatus.LOST
    to_string = classmethod(get_name_of_constant)


class SimpleGoalState:
    """The simple client's view: pending, active or done."""

    PENDING = 0
    ACTIVE = 1
    DONE = 2
    to_string = classmethod(get_name_of_constant)


GoalStatus.to_string = classmethod(get_name_of_constant)


def _table() -> dict[int, dict[int, Any]]:
    """The transitions, one row per communication state, one column per reported status.

    A cell lists the states passed through, first letters joined by ``>``; ``-`` is no transition, ``x``
    an invalid one. Columns: PENDING ACTIVE REJECTED RECALLING RECALLED PREEMPTED SUCCEEDED ABORTED
    PREEMPTING.
    """
    letters = {"P": CommState.PENDING, "A": CommState.ACTIVE, "W": CommState.WAITING_FOR_RESULT,
               "R": CommState.RECALLING, "E": CommState.PREEMPTING}
    columns = [GoalStatus.PENDING, GoalStatus.ACTIVE, GoalStatus.REJECTED, GoalStatus.RECALLING,
               GoalStatus.RECALLED, GoalStatus.PREEMPTED, GoalStatus.SUCCEEDED, GoalStatus.ABORTED,
               GoalStatus.PREEMPTING]
    rows = {
        CommState.WAITING_FOR_GOAL_ACK: "P    A    P>W  P>R  P>W  A>E>W A>W  A>W  A>E",
        CommState.PENDING:              "-    A    W    R    R>W  A>E>W A>W  A>W  A>E",
        CommState.ACTIVE:               "x    -    x    x    x    E>W   W    W    E",
        CommState.WAITING_FOR_RESULT:   "x    -    -    x    -    -     -    -    x",
        CommState.WAITING_FOR_CANCEL_ACK: "-  -    W    R    R>W  E>W   E>W  E>W  E",
        CommState.RECALLING:            "x    x    W    -    W    E>W   E>W  E>W  E",
        CommState.PREEMPTING:           "x    x    x    x    x    W     W    W    -",
        CommState.DONE:                 "x    x    -    x    -    -     -    -    x",
    }
    table: dict[int, dict[int, Any]] = {}
    for state, cells in rows.items():
        row: dict[int, Any] = {}
        for status, cell in zip(columns, cells.split()):
            row[status] = (NO_TRANSITION if cell == "-" else INVALID_TRANSITION if cell == "x"
                           else tuple(letters[c] for c in cell.split(">")))
        table[state] = row
    return table


TRANSITIONS: dict[int, dict[int, Any]] = _table()
"""``TRANSITIONS[comm_state][goal_status]``: the states to pass through, or a NO/INVALID marker."""
