"""A received message as a tree of fields for the monitor's expanded view.

Nested messages become branches, arrays show their first
:data:`ARRAY_SHOWN` items and a count of the rest, integer fields are
followed by the name of the constant their type defines for that value
(rosgraph_msgs/Log ``level: 2 (INFO)``), and every numeric leaf carries the
path :func:`value_at` reads to plot it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rostui.core.rostime import TVal

__all__ = ["FieldItem", "message_tree", "constant_names", "value_at", "PathError", "ARRAY_SHOWN"]

#: Array items shown in a tree; the rest are counted.
ARRAY_SHOWN = 8
#: Characters of a string field shown.
STRING_SHOWN = 120
_INT_TYPES = {"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "byte", "char"}


class PathError(ValueError):
    """A field path that does not name a field of the message."""


@dataclass(frozen=True)
class FieldItem:
    """One field (or array item) of a message: its label, value text, children and path from the message."""

    label: str
    text: str
    path: str
    children: tuple["FieldItem", ...] = ()
    numeric: bool = False

    @property
    def line(self) -> str:
        """``label: text`` as the tree shows it (only the label for a branch without text)."""
        return f"{self.label}: {self.text}" if self.text else self.label


def constant_names(cls: Any, field_type: str, value: Any) -> list[str]:
    """Names of the constants ``cls`` defines with ``value``: those of ``field_type`` first, else any integer one."""
    spec = getattr(cls, "_spec", None)
    if spec is None or isinstance(value, bool) or not isinstance(value, int):
        return []
    constants = [c for c in spec.constants if not isinstance(c.value, (bool, str)) and c.value == value]
    same = [c.name for c in constants if c.type == field_type]
    if same:
        return same
    if field_type in _INT_TYPES:
        return [c.name for c in constants if c.type in _INT_TYPES]
    return []


def _join(path: str, name: str) -> str:
    return f"{path}/{name}" if path else name


def _scalar_text(value: Any) -> str:
    if isinstance(value, str):
        shown = value if len(value) <= STRING_SHOWN else value[:STRING_SHOWN] + "…"
        return repr(shown)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _is_message(value: Any) -> bool:
    return hasattr(value, "__slots__") and hasattr(value, "_slot_types")


def _is_numeric(value: Any) -> bool:
    return isinstance(value, (int, float, TVal))


def _item(label: str, value: Any, field_type: str, path: str, owner: Any) -> FieldItem:
    if _is_message(value):
        return FieldItem(label, "", path, _children(value, path))
    if isinstance(value, TVal):
        return FieldItem(label, f"{value.secs}.{value.nsecs:09d}", path, numeric=True)
    if isinstance(value, (bytes, bytearray, list, tuple)):
        count = len(value)  # an image's megabyte of uint8 is only counted, never copied
        base = field_type.split("[", 1)[0]
        shown = [_item(f"[{i}]", v, base, f"{path}[{i}]", owner) for i, v in enumerate(value[:ARRAY_SHOWN])]
        if count > ARRAY_SHOWN:
            shown.append(FieldItem(f"… {count - ARRAY_SHOWN} more", "", f"{path}[…]"))
        return FieldItem(f"{label}", f"{base}[{count}]", path, tuple(shown))
    text = _scalar_text(value)
    names = constant_names(type(owner), field_type, value) if owner is not None else []
    if names:
        text += f" ({'|'.join(names)})"
    return FieldItem(label, text, path, numeric=_is_numeric(value))


def _children(msg: Any, path: str) -> tuple[FieldItem, ...]:
    return tuple(_item(name, getattr(msg, name), ftype, _join(path, name), msg)
                 for name, ftype in zip(msg.__slots__, msg._slot_types))


def message_tree(msg: Any) -> tuple[FieldItem, ...]:
    """The top-level fields of ``msg`` as :class:`FieldItem` trees."""
    return _children(msg, "")


def _steps(path: str) -> list[tuple[str, list[int]]]:
    steps = []
    for part in (p for p in path.split("/") if p):
        name, _, rest = part.partition("[")
        indexes = []
        while rest:
            number, _, rest = rest.partition("]")
            try:
                indexes.append(int(number))
            except ValueError:
                raise PathError(f"bad array index [{number}] in {path}") from None
            rest = rest.removeprefix("[")
        steps.append((name, indexes))
    return steps


def value_at(msg: Any, path: str) -> float:
    """The numeric value at ``path`` (``pose/position/x``, ``ranges[3]``) as a float (times in seconds).

    Raises :class:`PathError` when the path names no numeric field of ``msg``.
    """
    value = msg
    for name, indexes in _steps(path):
        if not _is_message(value) or name not in value.__slots__:
            raise PathError(f"no field {name} in {path}")
        value = getattr(value, name)
        for index in indexes:
            try:
                value = value[index]
            except (IndexError, TypeError):
                raise PathError(f"no item [{index}] in {path}") from None
    if isinstance(value, TVal):
        return value.to_sec()
    if isinstance(value, bool):
        return 1.0 if value else 0.0
    if isinstance(value, (int, float)):
        return float(value)
    raise PathError(f"{path} is not a number")
