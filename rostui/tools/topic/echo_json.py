"""``rostui topic echo --json``: each message as one JSON object on one line (JSON Lines).

Made for ``| jq``: fields in message order, nested messages as objects, time
and duration as ``{"secs": .., "nsecs": ..}``, ``uint8[]``/``char[]`` data as a
list of ints (what ``jq 'add'`` or ``jq '.data[0]'`` can work with; base64
would need decoding first), and non-finite floats as the strings ``"nan"``,
``"inf"`` and ``"-inf"`` (JSON has no literal for them, and most parsers,
jq's among them, reject Python's ``NaN``).
"""

from __future__ import annotations

import json
import math
from typing import Any

from rostui.core.rostime import Time, TVal


def _is_message(value: Any) -> bool:
    return hasattr(value, "__slots__") and hasattr(value, "_slot_types")


def json_value(value: Any, *, time_offset: Time | None = None, noarr: bool = False,
               nostr: bool = False) -> Any:
    """A plain JSON value for a message, a field or a list of them.

    ``time_offset`` (``--offset``): Time fields become their offset from it;
    ``noarr``/``nostr`` leave array and string fields out of messages.
    """
    if _is_message(value):
        out: dict[str, Any] = {}
        for name, type_name in zip(value.__slots__, value._slot_types):
            if noarr and "[" in type_name:
                continue
            if nostr and type_name.split("[")[0] == "string":
                continue
            out[name] = json_value(getattr(value, name), time_offset=time_offset, noarr=noarr, nostr=nostr)
        return out
    if isinstance(value, TVal):
        if time_offset is not None and isinstance(value, Time):
            value = value - time_offset
        return {"secs": value.secs, "nsecs": value.nsecs}
    if isinstance(value, (bytes, bytearray)):
        return list(value)
    if isinstance(value, (list, tuple)):
        return [json_value(v, time_offset=time_offset, noarr=noarr, nostr=nostr) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if hasattr(value, "tolist"):  # numpy arrays and scalars from generated deserialisers
        return json_value(value.tolist(), time_offset=time_offset, noarr=noarr, nostr=nostr)
    return value


def json_line(value: Any, *, time_offset: Time | None = None, noarr: bool = False, nostr: bool = False) -> str:
    """One JSON Lines record (no newline inside, ``\\n`` at the end) for ``value``."""
    plain = json_value(value, time_offset=time_offset, noarr=noarr, nostr=nostr)
    return json.dumps(plain, ensure_ascii=False, separators=(",", ":"), allow_nan=False) + "\n"
