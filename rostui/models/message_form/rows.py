"""A message type laid out as a form: one row per field, each an expression, and the message they make.

Nested messages are opened into their fields (``linear.x``), arrays are one row holding a list
(``[0.0, 0.0]``, or a list of dicts for an array of messages), and a Header's stamp starts as ``now``, the
time at which each message is sent. A numeric row whose expression is a plain number is also a slider: it has a
range (from the form file, else a default that holds its value, within the type's) and :meth:`FieldRow.nudge`
moves it by a hundredth of that range. A string row takes what its expression gives as text (``str()``, as
rqt_publisher converts), and an expression that does not compute as the text itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Iterator

from rostui.core.msg import Message, MessageError
from rostui.core.msg.convert import fill_message, message_to_dict
from rostui.core.msg.spec import HEADER_TYPE
from rostui.core.one_line import exception_line
from rostui.core.rostime import Duration, Time, TVal

from .expression import ExpressionError, evaluate, is_number_literal

__all__ = ["FormError", "FieldRow", "MessageForm", "INT_TYPES", "FLOAT_TYPES", "SLIDER_STEPS"]

#: Integer field types and their ranges.
INT_TYPES: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1), "byte": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1), "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1), "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1), "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
}

#: Floating-point field types.
FLOAT_TYPES = ("float32", "float64")

#: Steps from one end of a slider's range to the other.
SLIDER_STEPS = 100

#: Largest magnitude a slider shows; a value beyond it (or not finite) has no slider.
SLIDER_LIMIT = 1e300


class FormError(Exception):
    """What is wrong with a form, in one line naming the field."""


@dataclass
class FieldRow:
    """One field of the form: its dotted ``path``, its ROS ``type`` and the ``expression`` that gives its value;
    ``low``/``high`` is its slider's range (numeric fields only)."""

    path: str
    type: str
    expression: str
    low: float | None = None
    high: float | None = None

    @property
    def numeric(self) -> bool:
        """True for an integer or floating-point scalar: a row with a slider."""
        return self.type in INT_TYPES or self.type in FLOAT_TYPES

    @property
    def integer(self) -> bool:
        """True for an integer scalar."""
        return self.type in INT_TYPES

    def number(self) -> float | None:
        """The row's value when its expression is a plain, finite number no larger than :data:`SLIDER_LIMIT`
        (what a slider shows and moves), else None: ``sin(t)`` or ``random()`` is not replaced by a slider."""
        if not self.numeric or not is_number_literal(self.expression):
            return None
        try:
            value = evaluate(self.expression)
        except ExpressionError:
            return None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return None
        if not math.isfinite(value) or abs(value) > SLIDER_LIMIT:
            return None
        return value

    def slider_range(self) -> tuple[float, float]:
        """The slider's range: the one set, else ±1 for floats and 0..100 (or ±100) for integers, widened to
        hold the value and kept within the type's range."""
        if self.low is not None and self.high is not None and self.low < self.high:
            return self.low, self.high
        if self.integer:
            type_low, type_high = INT_TYPES[self.type]
            low, high = float(max(type_low, -100)), float(min(type_high, 100))
        else:
            low, high = -1.0, 1.0
        value = self.number()
        if value is not None and not low <= value <= high:
            reach = _round_up(abs(value))
            low, high = (min(low, -reach) if low < 0 else low), max(high, reach)
        if self.integer:
            low, high = max(low, float(INT_TYPES[self.type][0])), min(high, float(INT_TYPES[self.type][1]))
        return low, high

    def fraction(self) -> float | None:
        """Where the value sits in the slider's range, 0 to 1; None without a slider."""
        value = self.number()
        if value is None:
            return None
        low, high = self.slider_range()
        return min(max((float(value) - low) / (high - low), 0.0), 1.0)

    def nudge(self, steps: int) -> bool:
        """Move the slider ``steps`` hundredths of its range (clamped to it); False if the row has no slider."""
        value = self.number()
        if value is None:
            return False
        low, high = self.slider_range()
        step = (high - low) / SLIDER_STEPS
        if self.integer:
            step = max(1.0, round(step))
        moved = min(max(float(value) + steps * step, low), high)
        self.expression = str(int(round(moved))) if self.integer else _short(moved)
        return True


@dataclass
class MessageForm:
    """The rows of a message class ``cls``; :meth:`build` makes a message of them."""

    cls: type[Message]
    rows: list[FieldRow] = field(default_factory=list)

    @classmethod
    def of(cls, msg_class: type[Message]) -> "MessageForm":
        """The form of ``msg_class`` with every field at its default (Header stamps ``now``)."""
        return cls(msg_class, list(_rows(msg_class(), "", stamped=False)))

    @property
    def type_name(self) -> str:
        """The message type, ``pkg/Name``."""
        return self.cls._type

    def row(self, path: str) -> FieldRow | None:
        """The row of ``path``, or None."""
        return next((row for row in self.rows if row.path == path), None)

    def build(self, *, i: int = 1, t: float = 0.0, now: Time | None = None) -> Message:
        """The message the rows give as the ``i``-th sent (1 for the first), ``t`` seconds after the first, at
        ``now``; :class:`FormError` naming the first field that cannot be filled."""
        stamp = now if now is not None else Time.now()
        variables = {"i": i, "t": t, "now": stamp}
        document: dict[str, Any] = {}
        for row in self.rows:
            _place(document, row.path.split("."), _row_value(row, variables))
        try:
            return fill_message(self.cls, document, keys={"now": stamp})
        except (MessageError, ValueError, TypeError, OverflowError) as exc:
            raise FormError(exception_line(exc, None)) from None


def _rows(msg: Message, prefix: str, *, stamped: bool) -> Iterator[FieldRow]:
    for name, slot_type in zip(msg.__slots__, msg._slot_types):
        value = getattr(msg, name)
        path = prefix + name
        if isinstance(value, Message):
            yield from _rows(value, path + ".", stamped=value._type == HEADER_TYPE)
        elif stamped and name == "stamp" and isinstance(value, Time):
            yield FieldRow(path, slot_type, "now")
        else:
            yield FieldRow(path, slot_type, _literal(value))


def _literal(value: Any) -> str:
    """The expression that gives ``value``."""
    if isinstance(value, TVal):
        return "0" if not value.secs and not value.nsecs else f"{value.to_sec()!r}"
    if isinstance(value, (bytes, bytearray)):
        return repr(list(value))
    if isinstance(value, Message):
        return repr(message_to_dict(value))
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_literal(item) for item in value) + "]"
    return repr(value)


def _row_value(row: FieldRow, variables: dict[str, Any]) -> Any:
    try:
        value = evaluate(row.expression, variables)
    except ExpressionError as exc:
        if row.type == "string":  # rqt_publisher's rule: a string field takes what does not compute as text
            return row.expression
        raise FormError(f"{row.path}: {exc}") from None
    if row.type == "string" and not isinstance(value, str):
        return str(value)
    if isinstance(value, TVal) and row.type in ("time", "duration"):
        kind = Time if row.type == "time" else Duration
        return kind(value.secs, value.nsecs)
    return value


def _place(document: dict[str, Any], parts: list[str], value: Any) -> None:
    for part in parts[:-1]:
        document = document.setdefault(part, {})
    document[parts[-1]] = value


def _round_up(value: float) -> float:
    """The next 1, 2 or 5 times a power of ten at or above ``value`` (finite, at most :data:`SLIDER_LIMIT`)."""
    scale = 1.0
    while scale * 10 <= value:
        scale *= 10
    for factor in (1, 2, 5, 10):
        if value <= factor * scale:
            return factor * scale
    return 10 * scale


def _short(value: float) -> str:
    text = f"{value:.12g}"
    return text if any(c in text for c in ".en") else text + ".0"
