"""Views of messages as dicts and YAML text, and filling messages from dicts / ``rostopic pub`` args.

:func:`message_to_yaml` prints exactly what ``rostopic echo`` prints for a
message (without the ``---`` line); :func:`message_from_yaml_args` follows
``rostopic pub``'s argument rules; :func:`default_yaml_template` gives the text
``rostopic pub`` tab completion offers (``rosmsg-proto``).
"""

from __future__ import annotations

from typing import Any, Callable, Iterable, Mapping

import yaml

from ..rostime import Duration, Time, TVal
from .errors import MessageValueError, UnknownMessageTypeError
from .message import Message
from .registry import get_message_class
from .spec import HEADER_TYPE

__all__ = [
    "field_class",
    "format_value",
    "message_to_dict",
    "fill_message",
    "message_to_yaml",
    "message_from_yaml_args",
    "fill_message_args",
    "default_yaml_template",
]

_INT_RANGES: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1), "byte": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1), "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1), "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
}


def _split_type(t: str) -> tuple[str, bool, int | None]:
    """``float64[9]`` -> ``("float64", True, 9)``."""
    if t.endswith("]"):
        base, _, rest = t.partition("[")
        n = rest[:-1]
        return base, True, (int(n) if n else None)
    return t, False, None


def field_class(msg: Message | type[Message], base: str) -> type[Message]:
    """The class of a nested field type, from the definition that built *msg*'s class (a peer's may differ)."""
    cls = getattr(msg, "_field_classes", {}).get(base)
    return cls if isinstance(cls, type) and issubclass(cls, Message) else get_message_class(base)


# ----------------------------------------------------------------------------- dict view
def message_to_dict(msg: Message) -> dict[str, Any]:
    """A plain dict of *msg* (nested messages as dicts, time as ``{secs, nsecs}``, uint8[] as list of ints)."""
    return {f: _to_plain(getattr(msg, f), t) for f, t in zip(msg.__slots__, msg._slot_types)}


def _to_plain(v: Any, t: str) -> Any:
    if isinstance(v, Message):
        return message_to_dict(v)
    if isinstance(v, TVal):
        return {"secs": v.secs, "nsecs": v.nsecs}
    if isinstance(v, (bytes, bytearray)):
        return list(v)
    if isinstance(v, (list, tuple)):
        base = _split_type(t)[0]
        return [_to_plain(x, base) for x in v]
    return v


# ----------------------------------------------------------------------------- filling
def fill_message(
    msg_or_cls: Message | type[Message],
    values: Mapping[str, Any] | list[Any],
    *,
    keys: Mapping[str, Any] | None = None,
) -> Message:
    """Set fields of a message (or a new instance of a class) from a dict or a positional list.

    Values are type-checked (ints range-checked, floats accept ints, time
    accepts ``{secs, nsecs}``, integer nanoseconds or float seconds).  *keys*
    maps strings such as ``now``/``auto`` to substitute Time/Header values.
    Raises :class:`MessageValueError` naming the offending field.
    """
    msg = msg_or_cls() if isinstance(msg_or_cls, type) else msg_or_cls
    _fill(msg, values, dict(keys or {}), "")
    return msg


def _fill(msg: Message, values: Any, keys: dict[str, Any], prefix: str) -> None:
    slots = msg.__slots__
    types = msg._slot_types
    if isinstance(values, Mapping):
        for f, v in values.items():
            if f not in slots:
                raise MessageValueError(f"No field name [{prefix}{f}] in {msg._type}")
            i = slots.index(f)
            if v is None:  # `field:` with nothing after it: the field's default
                setattr(msg, f, msg._defaults[f]())
            else:
                setattr(msg, f, _convert(msg, types[i], v, keys, prefix + str(f)))
    elif isinstance(values, (list, tuple)):
        if len(values) > len(slots):
            raise MessageValueError(
                f"Too many arguments for {prefix or msg._type}:\n * Given: {list(values)}\n * Expected: {list(slots)}"
            )
        if len(values) < len(slots):
            raise MessageValueError(
                f"Not enough arguments for {prefix or msg._type}:\n * Given: {list(values)}\n * Expected: {list(slots)}"
            )
        for f, t, v in zip(slots, types, values):
            setattr(msg, f, msg._defaults[f]() if v is None else _convert(msg, t, v, keys, prefix + f))
    else:
        raise MessageValueError(f"[{prefix or msg._type}] needs a dict or list of field values, got {type(values).__name__}: {values!r}")


def _convert(owner: Message, t: str, v: Any, keys: dict[str, Any], where: str) -> Any:
    base, is_array, n = _split_type(t)
    if v is None:
        raise MessageValueError(f"Field [{where}] has no value")
    if is_array:
        if base in ("uint8", "char") and isinstance(v, (bytes, bytearray)):
            out: Any = bytes(v)
        elif isinstance(v, (list, tuple)):
            out = [_convert_scalar(owner, base, x, keys, f"{where}[{i}]") for i, x in enumerate(v)]
            if base in ("uint8", "char"):
                out = bytes(out)
        else:
            raise MessageValueError(f"Field [{where}] must be a list or tuple instead of: {type(v).__name__}")
        if n is not None and len(out) != n:
            raise MessageValueError(f"Field [{where}] has incorrect number of elements: {len(out)} != {n}")
        return out
    return _convert_scalar(owner, base, v, keys, where)


def _convert_scalar(owner: Message, t: str, v: Any, keys: dict[str, Any], where: str) -> Any:
    if t in _INT_RANGES:
        if isinstance(v, bool) or not isinstance(v, int):
            if isinstance(v, float) and v.is_integer():
                v = int(v)
            else:
                raise MessageValueError(f"Field [{where}] must be an integer ({t}), got {type(v).__name__}: {v!r}")
        lo, hi = _INT_RANGES[t]
        if not lo <= v <= hi:
            raise MessageValueError(f"Field [{where}] value {v} out of range for {t}")
        return v
    if t in ("float32", "float64"):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise MessageValueError(f"Field [{where}] must be a number ({t}), got {type(v).__name__}: {v!r}")
        return float(v)
    if t == "bool":
        if isinstance(v, bool):
            return v
        if isinstance(v, int) and v in (0, 1):
            return bool(v)
        raise MessageValueError(f"Field [{where}] must be a bool, got {type(v).__name__}: {v!r}")
    if t == "string":
        if isinstance(v, str):
            return v
        if isinstance(v, bytes):
            return v.decode("utf-8", "replace")
        raise MessageValueError(f"Field [{where}] must be a string, got {type(v).__name__}: {v!r}")
    if t in ("time", "duration"):
        cls: type[TVal] = Time if t == "time" else Duration
        if isinstance(v, str):
            if v in keys and isinstance(keys[v], cls):
                return cls(keys[v].secs, keys[v].nsecs)
            raise MessageValueError(f"No key named [{v}] for field [{where}]")
        if isinstance(v, cls):
            return cls(v.secs, v.nsecs)
        if isinstance(v, bool):
            raise MessageValueError(f"Field [{where}] must be a {t}, got bool")
        if isinstance(v, int):
            secs, nsecs = divmod(v, 1_000_000_000)
            return _make_tval(cls, secs, nsecs, where)
        if isinstance(v, float):
            return _make_tval(cls, v, 0, where)
        if isinstance(v, Mapping):
            unknown = set(v) - {"secs", "nsecs"}
            if unknown:
                raise MessageValueError(f"No field name [{where}.{sorted(unknown)[0]}] in {t}")
            return _make_tval(cls, v.get("secs", 0) or 0, v.get("nsecs", 0) or 0, where)
        if isinstance(v, (list, tuple)) and len(v) == 2:
            return _make_tval(cls, v[0], v[1], where)
        raise MessageValueError(f"Field [{where}] must be a {t} ({{secs, nsecs}} or nanoseconds), got {v!r}")
    # nested message
    sub_cls = field_class(owner, t)
    if isinstance(v, Message):
        if v._type != t:
            raise MessageValueError(f"Field [{where}] must be a {t}, got {v._type}")
        return v
    if isinstance(v, str):
        if v in keys and isinstance(keys[v], Message) and keys[v]._type == t:
            sub = sub_cls()
            for f in sub.__slots__:
                setattr(sub, f, getattr(keys[v], f))
            return sub
        raise MessageValueError(f"No key named [{v}] for field [{where}] ({t})")
    sub = sub_cls()
    _fill(sub, v, keys, where + ".")
    return sub


def _make_tval(cls: type[TVal], secs: Any, nsecs: Any, where: str) -> TVal:
    try:
        if not isinstance(nsecs, int) or isinstance(nsecs, bool):
            raise TypeError("nsecs must be an integer")
        return cls(secs, nsecs)
    except (TypeError, ValueError) as e:
        raise MessageValueError(f"Field [{where}]: {e}") from None


def fill_message_args(msg: Message, args: list[Any], *, now: Time | None = None) -> Message:
    """Fill *msg* from already YAML-parsed ``rostopic pub`` arguments.

    One dict argument sets fields by name; otherwise the arguments are the
    field values in order (all of them).  ``now`` stands for the current time
    in time fields, ``auto`` for a Header stamped now.
    """
    stamp = now if now is not None else Time.now()
    keys: dict[str, Any] = {"now": stamp}
    try:
        keys["auto"] = get_message_class(HEADER_TYPE)(stamp=Time(stamp.secs, stamp.nsecs))
    except UnknownMessageTypeError:  # pragma: no cover - std_msgs is built in
        pass
    if len(args) == 1 and isinstance(args[0], dict):
        _fill(msg, args[0], keys, "")
    else:
        _fill(msg, list(args), keys, "")
    return msg


def message_from_yaml_args(cls: type[Message], args: list[str], *, now: Time | None = None) -> Message:
    """Build a *cls* message from ``rostopic pub`` command-line arguments (each a YAML value)."""
    parsed: list[Any] = []
    for i, a in enumerate(args):
        try:
            parsed.append(yaml.safe_load(a))
        except yaml.YAMLError as e:
            raise MessageValueError(f"argument {i + 1} is not valid YAML: {e}") from None
    return fill_message_args(cls(), parsed, now=now)


# ----------------------------------------------------------------------------- YAML (rostopic echo)
def _yaml_str(s: str) -> str:
    if not s:
        return "''"
    return yaml.dump(s, default_style='"').rstrip("\n")


def format_value(
    val: Any,
    t: str,
    indent: str,
    width: int | None,
    time_offset: Time | None,
    filt: Callable[[Message], Iterable[str]] | None,
) -> str:
    """``val`` (of field type ``t``) as rostopic echo prints it below ``indent``: numbers ``width`` wide when given,
    times relative to ``time_offset``, a message's fields chosen by ``filt``."""
    tp = type(val)
    if tp in (int, float) and width is not None:
        if tp is float:
            s: str = ("%." + str(width) + "f") % val
            return s[: max(s.find("."), width)]
        digits: str = ("%" + str(width) + "d") % val
        return digits
    if tp in (int, float, bool):
        return str(val)
    if isinstance(val, str):
        return _yaml_str(val)
    if isinstance(val, TVal):
        tv: TVal = val - time_offset if time_offset is not None and isinstance(val, Time) else val
        if width is not None:
            fmt = "%" + str(width) + "d"
            return f"\n{indent}secs: " + (fmt % tv.secs) + f"\n{indent}nsecs: " + (fmt % tv.nsecs)
        return "\n%ssecs: %s\n%snsecs: %9d" % (indent, tv.secs, indent, tv.nsecs)
    if tp in (list, tuple):
        if not val:
            return "[]"
        v0 = val[0]
        if type(v0) in (int, float) and width is not None:
            return "[" + ", ".join(format_value(v, "", indent, width, time_offset, filt) for v in val) + "]"
        if isinstance(v0, str):
            text = yaml.dump(list(val)).rstrip("\n")
            if text[0] == "[":
                return text
            return "\n" + "\n".join(indent + line for line in text.splitlines())
        if type(v0) in (int, float, bool):
            return str(list(val))
        base = _split_type(t)[0]
        pref = indent + "- "
        sub_indent = indent + "  "
        return "\n" + "\n".join(pref + format_value(v, base, sub_indent, width, time_offset, filt) for v in val)
    if isinstance(val, Message):
        fields = list(filt(val)) if filt is not None else val.__slots__
        ni = "  " + indent
        lines = []
        for f, ft in zip(val.__slots__, val._slot_types):
            if f not in fields:
                continue
            v = getattr(val, f)
            if isinstance(v, (bytes, bytearray)) and "uint8[" in ft:
                v = list(v)
            lines.append(f"{indent}{f}: " + format_value(v, ft, ni, width, time_offset, filt))
        body = "\n".join(lines)
        return "\n" + body if indent else body
    return str(val)


def _transform(msg: Message, nostr: bool, noarr: bool) -> Any:
    """Mirror rostopic echo's value transform: summarise arrays/strings, recurse into nested messages."""
    names = list(msg.__slots__)
    types = list(msg._slot_types)
    values: list[Any] = []
    for i, (f, t) in enumerate(zip(names, types)):
        v = getattr(msg, f)
        if noarr and "[" in t:
            values.append("<array type: %s, length: %s>" % (t.rstrip("[]"), len(v)))
            types[i] = "string"
        elif nostr and t == "string":
            values.append("<string length: %s>" % len(v))
            types[i] = "string"
        elif nostr and t == "string[]":
            values.append("<array type: string, length: %s>" % len(v))
            types[i] = "string"
        elif isinstance(v, Message) and "[" not in t:
            values.append(_transform(v, nostr, noarr))
        else:
            values.append(v)
    return _Shadow(msg._type, names, types, values)


class _Shadow:
    """A lightweight message-like record used only for printing transformed messages."""

    __slots__ = ("_t", "_n", "_ts", "_v")

    def __init__(self, type_name: str, names: list[str], types: list[str], values: list[Any]) -> None:
        """Hold *values* for *names* with *types*."""
        self._t, self._n, self._ts, self._v = type_name, names, types, values


def _strify_shadow(s: _Shadow, indent: str, width: int | None, time_offset: Time | None) -> str:
    ni = "  " + indent
    lines = []
    for f, ft, v in zip(s._n, s._ts, s._v):
        if isinstance(v, _Shadow):
            text = _strify_shadow(v, ni, width, time_offset)
        else:
            if isinstance(v, (bytes, bytearray)) and "uint8[" in ft:
                v = list(v)
            text = format_value(v, ft, ni, width, time_offset, None)
        lines.append(f"{indent}{f}: {text}")
    body = "\n".join(lines)
    return "\n" + body if indent else body


def message_to_yaml(
    msg: Message,
    *,
    noarr: bool = False,
    nostr: bool = False,
    fixed_numeric_width: int | None = None,
    time_offset: Time | None = None,
) -> str:
    """The text ``rostopic echo`` prints for *msg* (``--noarr``, ``--nostr``, ``-w``, ``--offset``), without ``---``."""
    if noarr or nostr:
        return _strify_shadow(_transform(msg, nostr, noarr), "", fixed_numeric_width, time_offset)
    return format_value(msg, msg._type, "", fixed_numeric_width, time_offset, None)


# ----------------------------------------------------------------------------- rosmsg-proto template
_MAX_BLOCK_ITEMS = 4


class _ProtoMsg:
    """A message (or time value) to be dumped as an ordered mapping."""

    __slots__ = ("items",)

    def __init__(self, items: list[tuple[str, Any]]) -> None:
        """Hold the (field, value) pairs."""
        self.items = items


class _ProtoDumper(yaml.SafeDumper):
    """SafeDumper that mimics rosmsg-proto's flow-style heuristics."""


def _represent_proto(dumper: _ProtoDumper, obj: _ProtoMsg) -> yaml.Node:
    long_list = any(isinstance(v, list) and len(v) > _MAX_BLOCK_ITEMS for _, v in obj.items)
    if long_list or len(obj.items) > _MAX_BLOCK_ITEMS:
        # types-PyYAML types the attribute as bool, but PyYAML's None (flow style for leaf collections) is meant
        dumper.default_flow_style = None  # type: ignore[assignment]
    return dumper.represent_mapping("tag:yaml.org,2002:map", obj.items)


_ProtoDumper.add_representer(_ProtoMsg, _represent_proto)


def _array_instance(base: str, owner: Message) -> Any:
    if base in ("float32", "float64") or base in _INT_RANGES:
        return 0
    if base == "string":
        return ""
    if base == "bool":
        return False
    if base in ("time", "duration"):
        return _ProtoMsg([("data", _ProtoMsg([("secs", 0), ("nsecs", 0)]))])
    try:
        return _proto(field_class(owner, base)())
    except UnknownMessageTypeError:
        return None


def _proto(msg: Any) -> Any:
    if isinstance(msg, TVal):
        return _ProtoMsg([("secs", msg.secs), ("nsecs", msg.nsecs)])
    items: list[tuple[str, Any]] = []
    for f, t in zip(msg.__slots__, msg._slot_types):
        v = getattr(msg, f)
        if isinstance(v, list) and not v:
            inst = _array_instance(_split_type(t)[0], msg)
            v = [] if inst is None else [inst]
        elif isinstance(v, list):
            v = [_proto(x) if isinstance(x, (Message, TVal)) else x for x in v]
        elif isinstance(v, (Message, TVal)):
            v = _proto(v)
        items.append((f, v))
    return _ProtoMsg(items)


def default_yaml_template(cls: type[Message]) -> str:
    """The YAML of a default *cls* instance as ``rosmsg-proto msg`` prints it (what ``rostopic pub`` completes)."""
    text = yaml.dump(_proto(cls()), Dumper=_ProtoDumper, default_flow_style=False, default_style="", sort_keys=False)
    return text.rstrip("\n")
