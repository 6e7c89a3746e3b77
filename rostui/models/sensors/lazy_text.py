"""A message read lazily (:mod:`rostui.models.sensors.lazy_msg`) as text of a bounded size, however large it is.

The text is laid out as ``rostopic echo`` prints a message (``name: value``,
nested messages indented, arrays of messages as ``-`` items), but an array
shows only its first :data:`ARRAY_SHOWN` items followed by its length
(``[2.0, 2.0, …, … (10000000 items)]``) and a string its first
:data:`~rostui.models.monitor.tree.STRING_SHOWN` characters, as the
monitor's tree does: a LaserScan of ten million ranges is a few lines,
read from its bytes without building the ranges.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import yaml

from rostui.core.msg import Duration, Time, get_message_spec
from rostui.models.monitor.tree import ARRAY_SHOWN, STRING_SHOWN
from rostui.models.sensors.lazy_msg import LazyMessage

__all__ = ["lazy_text"]


def _scalar(value: Any) -> str:
    if isinstance(value, str):
        if not value:
            return "''"
        shown = value if len(value) <= STRING_SHOWN else value[:STRING_SHOWN] + "…"
        return str(yaml.dump(shown, default_style='"', width=float("inf"), allow_unicode=True)).rstrip("\n")
    if isinstance(value, (bool, np.bool_)):
        return "True" if value else "False"
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return str(value)


def _more(count: int) -> str:
    return f"… ({count} items)"


def _lines(msg: LazyMessage, indent: str) -> list[str]:
    lines: list[str] = []
    for f in get_message_spec(msg._type).fields:
        value = getattr(msg, f.name)
        head = f"{indent}{f.name}:"
        if isinstance(value, (Time, Duration)):
            lines += [head + " ", f"{indent}  secs: {value.secs}", f"{indent}  nsecs: {value.nsecs:9d}"]
        elif isinstance(value, LazyMessage):
            lines.append(head + " ")
            lines += _lines(value, indent + "  ")
        elif f.is_array:
            lines += _array(head, value, indent)
        else:
            lines.append(f"{head} {_scalar(value)}")
    return lines


def _array(head: str, value: Any, indent: str) -> list[str]:
    """An array field: its first items, then its length when it has more."""
    count = len(value)
    first = value[:ARRAY_SHOWN]
    if count and isinstance(first[0], LazyMessage):
        lines = [head + " "]
        for item in first:
            lines.append(f"{indent}  - ")
            lines += _lines(item, indent + "    ")
        if count > ARRAY_SHOWN:
            lines.append(f"{indent}  - {_more(count)}")
        return lines
    if count and isinstance(first[0], (Time, Duration)):
        items = [f"{{secs: {v.secs}, nsecs: {v.nsecs}}}" for v in first]
    else:
        items = [_scalar(v) for v in first]
    if count > ARRAY_SHOWN:
        items.append(_more(count))
    return [f"{head} [{', '.join(items)}]"]


def lazy_text(msg: LazyMessage) -> str:
    """``msg`` as ``rostopic echo`` lays it out, each array cut to its first items and its length."""
    return "\n".join(_lines(msg, ""))
