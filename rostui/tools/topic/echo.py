"""``rostui topic echo``'s formatting: field selection, ``-p`` plot lines and rostopic's YAML-shaped text; decoding any type."""

from __future__ import annotations

import sys
import time
from typing import Any, Callable, Iterable, Iterator

from rostui.tools.topic.common import UsageError


def _slice_of(spec: str) -> int | slice:
    if spec == "":
        raise ValueError("empty array index")
    parts = spec.split(":")
    if len(parts) == 1:
        try:
            return int(parts[0])
        except ValueError:
            raise ValueError(f"non-integer array index step '{parts[0]}'") from None
    if len(parts) > 3:
        raise ValueError("too many slice arguments")
    args: list[int | None] = [None, None, None]
    for i, (what, p) in enumerate(zip(("start", "stop", "step"), parts)):
        if p != "":
            try:
                args[i] = int(p)
            except ValueError:
                raise ValueError(f"non-integer slice {what} '{p}'") from None
    return slice(*args)


def field_evaluator(pattern: str) -> Callable[[Any], Any] | None:
    """A function selecting ``/field[/sub][i|a:b]...`` of a message (None for the whole message).

    Raises :class:`UsageError` for a malformed index.
    """
    evals: list[tuple[str, int | slice | None]] = []
    for f in (p for p in pattern.split("/") if p):
        if "[" in f:
            name, rest = f.split("[", 1)
            if not rest.endswith("]"):
                raise UsageError(f"missing closing ']' in slice spec '{f}'")
            try:
                evals.append((name, _slice_of(rest[:-1])))
            except ValueError as e:
                raise UsageError(f"field '{name}' has invalid slice argument '{rest[:-1]}': {e}") from None
        else:
            evals.append((f, None))
    if not evals:
        return None

    def run(msg: Any, steps: list[tuple[str, int | slice | None]]) -> Any:
        for i, (name, sl) in enumerate(steps):
            if name not in getattr(msg, "__slots__", ()):
                print(f"no field named {name} in {pattern}", file=sys.stderr)
                return None
            msg = getattr(msg, name)
            if sl is not None:
                if isinstance(msg, (bytes, bytearray)):
                    msg = list(msg)
                try:
                    msg = msg[sl]
                except IndexError as e:
                    print(f"{e}: {pattern}", file=sys.stderr)
                    return None
                if isinstance(msg, list):
                    rest = steps[i + 1:]
                    return [run(m, rest) for m in msg]
        return msg

    return lambda msg: run(msg, evals)


def echo_usage_problem(*, topic: str | None, bag: bool, all_topics: bool, offset: bool, plot: bool, clear: bool,
                       width: int | None, as_json: bool) -> str | None:
    """What is wrong with ``topic echo``'s options taken together, in rostopic's words; None when they fit.

    A malformed field index in ``topic`` (``/a/b[x]``) is one too, reported before any master is asked.
    """
    from rostui.tools.topic.common import UsageError

    if width is not None and width < 2:
        return "Fixed width for numeric values must be at least 2"
    if as_json and (plot or clear or width is not None):
        return "--json cannot be combined with -p, -c or -w"
    if all_topics and not bag:
        return "Display all option is only valid when echoing from bag files"
    if offset and bag:
        return "offset time option is not valid with bag files"
    if topic is None and not all_topics:
        return "topic must be specified"
    try:
        field_evaluator("" if all_topics or topic is None else topic)
    except UsageError as exc:
        return str(exc)
    return None


def field_type_of(cls: Any, path: str) -> str | None:
    """The declared type of the field at *path* (``header/stamp``) of *cls*, or None."""
    from rostui.core.msg.convert import field_class

    parts = [p for p in path.strip("/").split("/") if p]
    if not parts:
        return None
    t: str | None = None
    owner = cls
    for i, part in enumerate(parts):
        name = part.split("[")[0]
        if owner is None or name not in owner.__slots__:
            return None
        t = owner._slot_types[owner.__slots__.index(name)]
        if i + 1 < len(parts):
            base = t.split("[", 1)[0]
            try:
                owner = field_class(owner, base)
            except Exception:
                owner = None
    return t


def _transform_value(val: Any, t: str, nostr: bool, noarr: bool) -> Any:
    if noarr and "[" in t:
        return "<array type: %s, length: %s>" % (t.rstrip("[]"), len(val))
    if nostr and t == "string":
        return "<string length: %s>" % len(val)
    if nostr and t == "string[]":
        return "<array type: string, length: %s>" % len(val)
    return val


def is_message(val: Any) -> bool:
    return hasattr(val, "_slot_types") and hasattr(val, "__slots__")


def _plot_fields(val: Any, f: str, keep: Callable[[Any], Iterable[str]] | None) -> str | None:
    from rostui.core.rostime import TVal

    tp = type(val)
    if tp in (bool, int, float) or isinstance(val, TVal) or isinstance(val, str):
        return f
    if is_message(val):
        fields = list(keep(val)) if keep is not None else val.__slots__
        found = [_plot_fields(_plot_attr(val, a, t), f + "." + a, keep)
                 for a, t in zip(val.__slots__, val._slot_types) if a in fields]
        sub = [s for s in found if s is not None]
        return ",".join(sub) if sub else None
    if tp in (list, tuple):
        if not val:
            return None
        v0 = val[0]
        if type(v0) in (bool, int, float, str) or isinstance(v0, TVal):
            return ",".join(f"{f}{x}" for x in range(len(val)))
        if is_message(v0):
            found = [_plot_fields(v, f"{f}{x}", keep) for x, v in enumerate(val)]
            sub = [s for s in found if s]
            return ",".join(sub) if sub else None
    return None


def _plot_attr(val: Any, f: str, t: str) -> Any:
    attr = getattr(val, f)
    if isinstance(attr, (bytes, bytearray)) and "uint8[" in t:
        return list(attr)
    return attr


def _plot_values(val: Any, offset: Any, keep: Callable[[Any], Iterable[str]] | None) -> str | None:
    from rostui.core.rostime import Time, TVal

    tp = type(val)
    if tp is bool:
        return "1" if val else "0"
    if tp in (int, float) or isinstance(val, TVal):
        if offset is not None and isinstance(val, Time):
            return str(val - offset)
        return str(val)
    if is_message(val):
        fields = list(keep(val)) if keep is not None else val.__slots__
        found = [_plot_values(_plot_attr(val, a, t), offset, keep)
                 for a, t in zip(val.__slots__, val._slot_types) if a in fields]
        sub = [s for s in found if s is not None]
        return ",".join(sub) if sub else None
    if isinstance(val, str):
        return val
    if tp in (list, tuple):
        if not val:
            return None
        v0 = val[0]
        if type(v0) is bool:
            return ",".join("1" if v else "0" for v in val)
        if type(v0) in (int, float) or isinstance(v0, TVal):
            return ",".join(str(v) for v in val)
        if isinstance(v0, str):
            return ",".join(val)
        if is_message(v0):
            sub = [s for s in (_plot_values(v, offset, keep) for v in val) if s is not None]
            return ",".join(sub) if sub else None
    return None


class EchoFormatter:
    """Turns received messages into the text ``rostopic echo`` prints for them.

    ``field`` is the part of the topic argument after the real topic
    (``/x`` for ``/turtle1/pose/x``); ``count`` stops after N messages.
    """

    def __init__(self, field: str = "", *, plot: bool = False, noarr: bool = False, nostr: bool = False,
                 offset: bool = False, count: int | None = None, fixed_width: int | None = None,
                 clear: bool = False, from_bag: bool = False, as_json: bool = False) -> None:
        self.evaluate = field_evaluator(field)
        self.as_json = as_json
        """One JSON object a line (``--json``, see echo_json.py) instead of rostopic's YAML."""
        self.field = field
        self.from_bag = from_bag
        """As ``rostopic echo -b``: ``-p``'s time is the bag's, and a selected field is printed without its
        declared type (raw ``bytes`` stay bytes, ``--noarr``/``--nostr`` leave it whole)."""
        self.plot = plot
        self.noarr = noarr
        self.nostr = nostr
        self.offset = offset
        self.max_count = count
        self.fixed_width = fixed_width
        self.prefix = "\033[2J\033[;H" if clear and not plot else ""
        self.count = 0
        self.first = True
        self._field_type: str | None = None
        self._field_type_for: Any = None

    def select(self, field: str) -> None:
        """Print ``field`` (``/x``, ``/a[0]``; '' for the whole message) of the messages from now on."""
        if field != self.field:
            self.field = field
            self.evaluate = field_evaluator(field)

    @property
    def done(self) -> bool:
        """True once ``count`` messages were printed."""
        return self.max_count is not None and self.count >= self.max_count

    def _keep(self) -> Callable[[Any], Iterable[str]] | None:
        if not self.plot or not (self.noarr or self.nostr):
            return None
        noarr, nostr = self.noarr, self.nostr

        def keep(val: Any) -> Iterator[str]:
            for f, t in zip(val.__slots__, val._slot_types):
                if noarr and "[" in t:
                    continue
                if nostr and "string" in t:
                    continue
                yield f
        return keep

    def format(self, msg: Any, now_nsec: int | None = None) -> str | None:
        """The text for one message (None when nothing is printed for it)."""
        if self.done:
            return None
        from rostui.core.rostime import Time

        data = self.evaluate(msg) if self.evaluate is not None else msg
        if data is None:
            return None
        self.count += 1
        offset = Time.now() if self.offset else None
        if self.as_json:
            from rostui.tools.topic.echo_json import json_line

            return json_line(data, time_offset=offset, noarr=self.noarr, nostr=self.nostr)
        if self.plot:
            keep = self._keep()
            head = ""
            if self.first:
                fields = _plot_fields(data, "field", keep)
                head = "%" + ("time," + fields if fields is not None else "time,") + "\n"
                self.first = False
            body = _plot_values(data, offset, keep) or ""
            off = offset.to_nsec() if offset is not None else 0
            if self.from_bag and now_nsec is not None:
                stamp = now_nsec
            elif getattr(data, "_has_header", False):
                stamp = data.header.stamp.to_nsec()
            else:
                stamp = now_nsec if now_nsec is not None else time.time_ns()
            return f"{head}{stamp - off},{body}\n"
        return self.prefix + self._yaml(msg, data, offset) + "\n---\n"

    def _yaml(self, msg: Any, data: Any, offset: Any) -> str:
        from rostui.core.msg.convert import format_value, message_to_yaml

        if is_message(data):
            return message_to_yaml(data, noarr=self.noarr, nostr=self.nostr,
                                   fixed_numeric_width=self.fixed_width, time_offset=offset)
        if self.from_bag:
            return format_value(data, "", "", self.fixed_width, offset, None)
        t = self._type_information(msg)
        if isinstance(data, (bytes, bytearray)):
            data = list(data)
        if t is not None and (self.noarr or self.nostr):
            data = _transform_value(data, t, self.nostr, self.noarr)
            if isinstance(data, str) and data.startswith("<"):
                t = "string"
        return format_value(data, t or "", "", self.fixed_width, offset, None)

    def _type_information(self, msg: Any) -> str | None:
        cls = type(msg)
        if self._field_type_for is not cls:
            self._field_type_for = cls
            self._field_type = field_type_of(cls, self.field)
        return self._field_type



def decode(raw: Any) -> Any:
    """Deserialize an AnyMsg with the class its publisher's header describes, once checked
    (:func:`rostui.core.msg.connection_class`: rostui's own type wins; a definition must hash to its md5sum)."""
    from rostui.core.msg import connection_class

    header = raw._connection_header or {}
    cls = connection_class(header.get("type", ""), header.get("md5sum", ""), header.get("message_definition", ""),
                           sender=f"publisher [{header.get('callerid') or '?'}]")
    return cls.deserialize(raw._buff)
