"""The logic of ``rostui topic`` (what ``rostopic`` does), free of any CLI framework.

Master queries take a ``call(method, *args)`` callable that returns the
unwrapped value of a Master API call, so the command layer decides how a
missing master is reported.  The long-running tools (echo, hz, bw, pub) are
coroutines driving an :class:`~rostui.core.node.AsyncNode`; they write their
text through an ``out(text)`` callable.

Output follows real ``rostopic`` byte for byte; where rostopic prints a
multi-line error, the error here is one line.
"""

from __future__ import annotations

import math
import os
import sys
import time
from collections import deque
from typing import Any, Callable, Iterable, Iterator, Sequence

MasterCall = Callable[..., Any]
Out = Callable[[str], None]

#: rostopic's node name for master calls.
CALLER_ID = "/rostopic"
#: How long ``pub -1`` stays up after publishing (rostopic's _ONCE_DELAY).
ONCE_DELAY = 3.0
#: How long file/stdin publishing waits for a first subscriber.
SUBSCRIBER_TIMEOUT = 5.0
#: ``hz`` keeps at most this many messages when no window is given.
HZ_DEFAULT_WINDOW = 50000
#: ``bw``'s default window.
BW_DEFAULT_WINDOW = 100


class TopicToolError(Exception):
    """A failure to report as one ``ERROR: ...`` line (exit 1)."""


class UsageError(TopicToolError):
    """Bad command-line input (reported like a parser error, exit 1)."""


def one_line(text: str) -> str:
    """Fold a multi-line message into one line."""
    parts = [p.strip() for p in str(text).splitlines() if p.strip()]
    if not parts:
        return ""
    head, rest = parts[0], [p.lstrip("* ").strip() for p in parts[1:]]
    if not rest:
        return head
    return head + (" " if head.endswith(":") else ": ") + ", ".join(rest)


# ----------------------------------------------------------------------------- names
def resolve_topic(name: str) -> str:
    """Resolve a command-line topic name as rostopic does (ROS_NAMESPACE, ``~`` under /rostopic)."""
    from rostui.core import names

    ns = os.environ.get("ROS_NAMESPACE", "/") or "/"
    if not ns.startswith("/"):
        ns = "/" + ns
    return names.resolve_name(name, ns, CALLER_ID)


# ----------------------------------------------------------------------------- master views
def topic_types(call: MasterCall) -> list[tuple[str, str]]:
    """``[(topic, type), ...]`` from getTopicTypes."""
    return [(t, ty) for t, ty in call("getTopicTypes")]


def system_state(call: MasterCall) -> tuple[list, list, list]:
    """``(publishers, subscribers, services)`` from getSystemState."""
    pubs, subs, srvs = call("getSystemState")
    return pubs, subs, srvs


def topic_list(call: MasterCall) -> tuple[list[tuple[str, str, list[str]]], list[tuple[str, str, list[str]]]]:
    """Published and subscribed topics as ``(topic, type, nodes)``, in the master's order."""
    pubs, subs, _ = system_state(call)
    types = dict(reversed(topic_types(call)))

    def typed(entries: list) -> list[tuple[str, str, list[str]]]:
        return [(t, types.get(t, "unknown type"), list(nodes)) for t, nodes in entries]

    return typed(pubs), typed(subs)


def _in_namespace(topic: str, ns: str | None) -> bool:
    if not ns:
        return True
    prefix = ns if ns.endswith("/") else ns + "/"
    return topic == ns or topic.startswith(prefix)


def format_list(pubs: Sequence[tuple[str, str, list[str]]], subs: Sequence[tuple[str, str, list[str]]], *,
                verbose: bool = False, publishers_only: bool = False, subscribers_only: bool = False,
                namespace: str | None = None) -> str:
    """The text ``rostopic list [-v] [-p|-s] [/ns]`` prints (with its final newline)."""
    pubs = [p for p in pubs if _in_namespace(p[0], namespace)]
    subs = [s for s in subs if _in_namespace(s[0], namespace)]
    lines: list[str] = []
    if verbose:
        if not subscribers_only:
            lines.append("")
            lines.append("Published topics:")
            for t, ty, nodes in pubs:
                n = len(nodes)
                lines.append(f" * {t} [{ty}] {n} publishers" if n > 1 else f" * {t} [{ty}] 1 publisher")
        if not publishers_only:
            lines.append("")
            lines.append("Subscribed topics:")
            for t, ty, nodes in subs:
                n = len(nodes)
                lines.append(f" * {t} [{ty}] {n} subscribers" if n > 1 else f" * {t} [{ty}] 1 subscriber")
        lines.append("")
        return "\n".join(lines) + "\n"
    if publishers_only:
        topics = [t for t, _, _ in pubs]
    elif subscribers_only:
        topics = [t for t, _, _ in subs]
    else:
        topics = list({t for t, _, _ in pubs} | {t for t, _, _ in subs})
    topics.sort()
    return "\n".join(topics) + "\n"


def list_json(pubs: Sequence[tuple[str, str, list[str]]], subs: Sequence[tuple[str, str, list[str]]], *,
              namespace: str | None = None) -> list[dict[str, Any]]:
    """Every topic with its type, publishers and subscribers (``--json``)."""
    out: dict[str, dict[str, Any]] = {}
    for t, ty, nodes in pubs:
        if _in_namespace(t, namespace):
            out.setdefault(t, {"topic": t, "type": ty, "publishers": [], "subscribers": []})["publishers"] += nodes
    for t, ty, nodes in subs:
        if _in_namespace(t, namespace):
            out.setdefault(t, {"topic": t, "type": ty, "publishers": [], "subscribers": []})["subscribers"] += nodes
    return [out[t] for t in sorted(out)]


def topic_info(call: MasterCall, topic: str) -> dict[str, Any]:
    """Type, publishers and subscribers (with their XML-RPC URIs) of one topic."""
    pubs, subs = topic_list(call)
    pubs = [p for p in pubs if p[0] == topic]
    subs = [s for s in subs if s[0] == topic]
    if not pubs and not subs:
        raise TopicToolError(f"Unknown topic {topic}")
    types = dict(reversed(topic_types(call)))
    cache: dict[str, str] = {}

    def api(node: str) -> str:
        if node not in cache:
            from rostui.core.xmlrpc import RosApiError

            try:
                cache[node] = call("lookupNode", node)
            except RosApiError:
                cache[node] = f"unknown address {node}"
        return cache[node]

    return {
        "topic": topic,
        "type": types.get(topic, "unknown type"),
        "publishers": [{"node": n, "uri": api(n)} for _, _, nodes in pubs for n in nodes],
        "subscribers": [{"node": n, "uri": api(n)} for _, _, nodes in subs for n in nodes],
    }


def format_info(info: dict[str, Any]) -> str:
    """The text ``rostopic info`` prints (``print`` adds one more newline)."""
    out = [f"Type: {info['type']}\n\n"]
    for key, title in (("publishers", "Publishers"), ("subscribers", "Subscribers")):
        entries = info[key]
        if entries:
            out.append(f"{title}: \n")
            out.extend(f" * {e['node']} ({e['uri']})\n" for e in entries)
        else:
            out.append(f"{title}: None\n")
        out.append("\n")
    return "".join(out)


def find_topic_type(call: MasterCall, topic: str) -> tuple[str | None, str | None, str]:
    """``(type, real_topic, field_path)`` for a topic or a field of one (``/rosout/msg``).

    The exact topic wins; otherwise the longest published topic that is a
    prefix, skipping types that lack the field.  ``(None, None, "")`` when
    nothing matches.
    """
    val = topic_types(call)
    matches = [(t, ty) for t, ty in val if t == topic]
    if not matches:
        matches = sorted(((t, ty) for t, ty in val if topic.startswith(t + "/")), key=lambda m: m[0], reverse=True)
        while matches:
            t, ty = matches[0]
            attrs = topic[len(t) + 1:].rstrip("/").split("[")[0]
            if not attrs:
                break
            cls = _local_class(ty)
            if cls is None:
                break
            try:
                _nested_attribute(cls(), attrs)
            except AttributeError:
                matches.pop(0)
                continue
            matches = [(t, ty)]
            break
    if not matches:
        return None, None, ""
    t, ty = matches[0]
    if ty == "*":
        return None, None, ""
    return ty, t, topic[len(t):]


def _local_class(type_name: str) -> Any:
    from rostui.core.msg import MessageError, get_message_class

    try:
        return get_message_class(type_name)
    except (MessageError, ValueError, OSError):
        return None


def _nested_attribute(msg: Any, path: str) -> Any:
    for attr in path.split("/"):
        if attr not in getattr(msg, "__slots__", ()):
            raise AttributeError(attr)
        msg = getattr(msg, attr)
    return msg


def type_text(call: MasterCall, topic: str) -> str:
    """What ``rostopic type TOPIC`` prints: the type, or ``TYPE field fieldtype`` for a field."""
    ty, real, _ = find_topic_type(call, topic)
    if ty is None or real is None:
        raise TopicToolError(f"unknown topic type [{topic}]")
    if topic == real:
        return ty
    field = topic[len(real) + 1:]
    field_type = ty
    for part in field.split("/"):
        cls = _local_class(field_type.split("[")[0])
        if cls is None or part not in cls.__slots__:
            raise TopicToolError(f"unknown field [{field}] in {ty}")
        field_type = cls._slot_types[cls.__slots__.index(part)]
    return f"{ty} {field} {field_type}"


def find_by_type(call: MasterCall, type_name: str) -> list[str]:
    """Topics whose type is *type_name* (``rostopic find``)."""
    return [t for t, ty in topic_types(call) if ty == type_name]


# ----------------------------------------------------------------------------- echo
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


def field_type_of(cls: Any, path: str) -> str | None:
    """The declared type of the field at *path* (``header/stamp``) of *cls*, or None."""
    from rostui.core.msg.convert import _field_class

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
                owner = _field_class(owner, base)
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


def _is_message(val: Any) -> bool:
    return hasattr(val, "_slot_types") and hasattr(val, "__slots__")


def _plot_fields(val: Any, f: str, keep: Callable[[Any], Iterable[str]] | None) -> str | None:
    from rostui.core.rostime import TVal

    tp = type(val)
    if tp in (bool, int, float) or isinstance(val, TVal) or isinstance(val, str):
        return f
    if _is_message(val):
        fields = list(keep(val)) if keep is not None else val.__slots__
        sub = [_plot_fields(_plot_attr(val, a, t), f + "." + a, keep)
               for a, t in zip(val.__slots__, val._slot_types) if a in fields]
        sub = [s for s in sub if s is not None]
        return ",".join(sub) if sub else None
    if tp in (list, tuple):
        if not val:
            return None
        v0 = val[0]
        if type(v0) in (bool, int, float, str) or isinstance(v0, TVal):
            return ",".join(f"{f}{x}" for x in range(len(val)))
        if _is_message(v0):
            sub = [_plot_fields(v, f"{f}{x}", keep) for x, v in enumerate(val)]
            sub = [s for s in sub if s]
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
    if _is_message(val):
        fields = list(keep(val)) if keep is not None else val.__slots__
        sub = [_plot_values(_plot_attr(val, a, t), offset, keep)
               for a, t in zip(val.__slots__, val._slot_types) if a in fields]
        sub = [s for s in sub if s is not None]
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
        if _is_message(v0):
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
                 clear: bool = False) -> None:
        self.evaluate = field_evaluator(field)
        self.field = field
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
        if self.plot:
            keep = self._keep()
            head = ""
            if self.first:
                fields = _plot_fields(data, "field", keep)
                head = "%" + ("time," + fields if fields is not None else "time,") + "\n"
                self.first = False
            body = _plot_values(data, offset, keep) or ""
            off = offset.to_nsec() if offset is not None else 0
            if getattr(data, "_has_header", False):
                stamp = data.header.stamp.to_nsec()
            else:
                stamp = now_nsec if now_nsec is not None else time.time_ns()
            return f"{head}{stamp - off},{body}\n"
        return self.prefix + self._yaml(msg, data, offset) + "\n---\n"

    def _yaml(self, msg: Any, data: Any, offset: Any) -> str:
        from rostui.core.msg.convert import _strify, message_to_yaml

        if _is_message(data):
            return message_to_yaml(data, noarr=self.noarr, nostr=self.nostr,
                                   fixed_numeric_width=self.fixed_width, time_offset=offset)
        t = self._type_information(msg)
        if isinstance(data, (bytes, bytearray)):
            data = list(data)
        if t is not None and (self.noarr or self.nostr):
            data = _transform_value(data, t, self.nostr, self.noarr)
            if isinstance(data, str) and data.startswith("<"):
                t = "string"
        return _strify(data, t or "", "", self.fixed_width, offset, None)

    def _type_information(self, msg: Any) -> str | None:
        cls = type(msg)
        if self._field_type_for is not cls:
            self._field_type_for = cls
            self._field_type = field_type_of(cls, self.field)
        return self._field_type


# ----------------------------------------------------------------------------- hz / bw
class HzStats:
    """Arrival times of one topic's messages; rostopic hz's statistics over a window.

    Adding a message is one clock read and one deque append; the statistics
    are computed when printed (once a second).
    """

    __slots__ = ("times", "last_printed", "window")

    def __init__(self, window: int = -1) -> None:
        self.window = window if window is not None and window >= 0 else HZ_DEFAULT_WINDOW
        self.times: deque[float] = deque(maxlen=max(self.window, 1))
        self.last_printed = 0.0

    def add(self, t: float) -> None:
        """Record an arrival at wall time *t* (seconds); a clock jump back restarts the window."""
        times = self.times
        if times and times[0] > t:
            times.clear()
        times.append(t)

    def rate(self) -> float | None:
        """The rate :meth:`stats` reports (messages per second over the window), without the other figures."""
        times = self.times
        if len(times) < 2:
            return None
        mean = (times[-1] - times[0]) / (len(times) - 1)
        return 1.0 / mean if mean > 0.0 else 0

    def stats(self) -> tuple[float, float, float, float, int] | None:
        """``(rate, min_delta, max_delta, std_dev, window)`` or None when there is nothing new."""
        times = list(self.times)
        if len(times) < 2 or times[-1] == self.last_printed:
            return None
        deltas = [b - a for a, b in zip(times, times[1:])]
        n = len(deltas)
        mean = (times[-1] - times[0]) / n
        rate = 1.0 / mean if mean > 0.0 else 0
        std_dev = math.sqrt(sum((x - mean) ** 2 for x in deltas) / n)
        self.last_printed = times[-1]
        return rate, min(deltas), max(deltas), std_dev, n + 1


def format_hz(stats: tuple[float, float, float, float, int] | None) -> str:
    """One topic's report (``average rate: ...`` and its second line, or ``no new messages``)."""
    if stats is None:
        return "no new messages\n"
    rate, lo, hi, sd, window = stats
    return "average rate: %.3f\n\tmin: %.3fs max: %.3fs std dev: %.5fs window: %s\n" % (rate, lo, hi, sd, window)


def format_hz_table(rows: Sequence[tuple[str, tuple[float, float, float, float, int] | None]]) -> str:
    """Several topics' report as rostopic's ASCII table (its window column included, quirks and all)."""
    header = ["topic", "rate", "min_delta", "max_delta", "std_dev", "window"]
    cols: dict[str, list[str]] = {h: [] for h in header}
    for topic, st in rows:
        if st is None:
            continue
        rate, lo, hi, sd, window = st
        # rostopic appends the window twice per topic; rows then take the first entries.
        cols["window"].append(str(window))
        cols["topic"].append(topic)
        cols["rate"].append("{:.4}".format(rate))
        cols["min_delta"].append("{:.4}".format(lo))
        cols["max_delta"].append("{:.4}".format(hi))
        cols["std_dev"].append("{:.4}".format(sd))
        cols["window"].append(str(window))
    if not cols["topic"]:
        return "no new messages\n"
    widths = []
    heads = []
    for h in header:
        w = max(len(h), max(len(x) for x in cols[h]))
        widths.append(w)
        heads.append(h.center(w))
        cols[h] = [x.ljust(w) for x in cols[h]]
    hline = "=" * (sum(widths) + 3 * (len(header) - 1))
    body = "\n".join("   ".join(cols[h][i] for h in header) for i in range(len(cols["topic"])))
    return "   ".join(heads) + "\n" + hline + "\n" + body + "\n\n"


def bandwidth_unit(bps: float) -> tuple[float, str]:
    """rostopic bw's unit for a byte rate, as (divisor, suffix): bytes below 1000, then KB, then MB."""
    if bps < 1000:
        return 1.0, "B"
    if bps < 1_000_000:
        return 1000.0, "KB"
    return 1_000_000.0, "MB"


class BwStats:
    """Sizes and arrival times of the last ``window`` messages (rostopic bw)."""

    def __init__(self, window: int | None = None) -> None:
        self.window = window or BW_DEFAULT_WINDOW
        self.times: deque[float] = deque(maxlen=self.window)
        self.sizes: deque[int] = deque(maxlen=self.window)

    def add(self, t: float, size: int) -> None:
        """Record one message of *size* bytes arriving at *t*."""
        self.times.append(t)
        self.sizes.append(size)

    def bytes_per_second(self, now: float) -> float | None:
        """The window's bytes divided by the time since its first message (None with fewer than two)."""
        if len(self.times) < 2 or now <= self.times[0]:
            return None
        return sum(self.sizes) / (now - self.times[0])

    def report(self, now: float) -> str | None:
        """The two report lines, or None with fewer than two messages."""
        if len(self.times) < 2:
            return None
        n = len(self.times)
        total = sum(self.sizes)
        bps = total / (now - self.times[0])
        mean = total / n
        divisor, unit = bandwidth_unit(bps)
        bw, mean_s, lo, hi = ["%.2f%s" % (v / divisor, unit) for v in (bps, mean, min(self.sizes), max(self.sizes))]
        return "average: %s/s\n\tmean: %s min: %s max: %s window: %s\n" % (bw, mean_s, lo, hi, n)


# ----------------------------------------------------------------------------- pub input
def yaml_error(e: Exception, where: str = "") -> str:
    """One line for a YAML error: what was wrong and where (``file:line:column``)."""
    problem = getattr(e, "problem", None) or getattr(e, "context", None) or one_line(str(e))
    mark = getattr(e, "problem_mark", None) or getattr(e, "context_mark", None)
    if mark is None:
        return f"{where}: {problem}" if where else str(problem)
    pos = f"{mark.line + 1}:{mark.column + 1}"
    return f"{where}:{pos}: {problem}" if where else f"{problem} (line {mark.line + 1}, column {mark.column + 1})"


def parse_yaml_args(args: Sequence[str]) -> list[Any]:
    """Each ``rostopic pub`` argument as YAML; :class:`UsageError` for malformed YAML."""
    import yaml

    out = []
    for a in args:
        try:
            out.append(yaml.safe_load(a))
        except yaml.YAMLError as e:
            raise UsageError(f"Argument error: argument {len(out) + 1} ({a!r}) is not valid YAML: {yaml_error(e)}") from None
    return out


def printable_args(msg: Any, prefix: str = "") -> str:
    """The field names a positional ``pub`` needs, as genpy lists them (``x y z``)."""
    names = []
    for f in msg.__slots__:
        v = getattr(msg, f)
        if _is_message(v):
            names.append(printable_args(v, prefix + f + "."))
        else:
            names.append(prefix + f)
    return " ".join(names)


def build_message(cls: Any, pub_args: list[Any], now: Any = None) -> Any:
    """A *cls* message filled from parsed ``pub`` arguments (``now``/``auto`` substituted).

    Raises :class:`TopicToolError` with one line naming the problem.
    """
    from rostui.core.msg import MessageError
    from rostui.core.msg.convert import fill_message_args

    msg = cls()
    try:
        return fill_message_args(msg, list(pub_args), now=now)
    except (MessageError, ValueError, TypeError) as e:
        raise TopicToolError(f"{one_line(str(e))} (args are: [{printable_args(cls())}])") from None


def message_class(type_name: str) -> Any:
    """The class of a message type for ``pub``; one-line error for an unknown type."""
    from rostui.core.msg import MessageError, get_message_class

    try:
        return get_message_class(type_name)
    except (MessageError, ValueError, OSError):
        pkg = type_name.split("/", 1)[0] if "/" in type_name else type_name
        raise TopicToolError(f"invalid message type: {type_name}. If this is a valid message type, "
                             f"check that package '{pkg}' is on ROS_PACKAGE_PATH") from None


def yaml_documents_from_file(path: str) -> list[Any]:
    """Every YAML document of an echo-formatted file (``---`` separated)."""
    import yaml

    if not os.path.isfile(path):
        raise TopicToolError(f"file does not exist: {path}")
    try:
        with open(path, encoding="utf-8") as f:
            return list(yaml.safe_load_all(f))
    except yaml.YAMLError as e:
        raise TopicToolError(f"invalid YAML in file: {yaml_error(e, path)}") from None


# ----------------------------------------------------------------------------- running nodes
class _Run:
    """A tool node and its stop signal (SIGINT/SIGTERM or the tool finishing)."""

    def __init__(self) -> None:
        import asyncio

        self.node: Any = None
        self.stop = asyncio.Event()

    async def __aenter__(self) -> "_Run":
        import asyncio
        import signal

        from rostui.core.node import AsyncNode

        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            try:
                loop.add_signal_handler(sig, self.stop.set)
            except (NotImplementedError, RuntimeError):  # pragma: no cover - non-Unix
                pass
        self.node = await AsyncNode("rostopic", anonymous=True, argv=[]).start(announce=False)
        return self

    async def __aexit__(self, *exc: object) -> None:
        import asyncio

        if self.node is not None:
            try:
                await asyncio.wait_for(self.node.shutdown(), 3.0)
            except (asyncio.TimeoutError, Exception):
                pass

    async def sleep(self, seconds: float) -> bool:
        """Sleep, or return True at once when asked to stop."""
        import asyncio

        if self.stop.is_set():
            return True
        try:
            await asyncio.wait_for(self.stop.wait(), seconds)
            return True
        except asyncio.TimeoutError:
            return False


async def _master(node: Any, method: str, *args: Any) -> Any:
    from rostui.core.node import MasterUnreachableError

    try:
        return await node.master_call(method, *args)
    except MasterUnreachableError:
        raise TopicToolError(f"Unable to communicate with master at {node.master_uri}") from None


async def _wait_for_topic(run: _Run, topic: str) -> tuple[str, str, str] | None:
    """Block until *topic* (or the topic holding that field) is published; None when stopped."""
    warned = False
    while True:
        types = await _master(run.node, "getTopicTypes")
        found = find_topic_type(lambda _m: types, topic)
        if found[0] is not None:
            return found  # type: ignore[return-value]
        if not warned:
            sys.stderr.write(f"WARNING: topic [{topic}] does not appear to be published yet\n")
            sys.stderr.flush()
            warned = True
        if await run.sleep(0.1):
            return None


def decode(raw: Any) -> Any:
    """Deserialize an AnyMsg with the class its publisher described (any type, even unknown locally)."""
    from rostui.core.msg import get_message_class, register_types_from_definition

    header = raw._connection_header or {}
    definition = header.get("message_definition")
    if definition:
        cls = register_types_from_definition(header["type"], definition)
    else:
        cls = get_message_class(header["type"])
    return cls.deserialize(raw._buff)


async def run_echo(topic: str, out: Out, *, plot: bool = False, noarr: bool = False, nostr: bool = False,
                   offset: bool = False, count: int | None = None, fixed_width: int | None = None,
                   clear: bool = False) -> int:
    """``rostopic echo``: print messages of *topic* (or a field of it) until stopped or *count* reached.

    Waits, like rostopic, while the topic is not published; decodes any type
    from its publisher's message_definition.
    """
    from rostui.core.node import AnyMsg

    async with _Run() as run:
        found = await _wait_for_topic(run, topic)
        if found is None:
            return 0
        _, real, field = found
        fmt = EchoFormatter(field, plot=plot, noarr=noarr, nostr=nostr, offset=offset, count=count,
                            fixed_width=fixed_width, clear=clear)
        failed: list[str] = []

        def on_msg(raw: Any) -> None:
            if fmt.done or run.stop.is_set():
                return
            try:
                text = fmt.format(decode(raw))
            except Exception as e:  # undecodable: say so and stop
                failed.append(f"cannot decode message on {real}: {one_line(str(e))}")
                run.stop.set()
                return
            if text is not None:
                try:
                    out(text)
                except BrokenPipeError:
                    run.stop.set()
                    return
            if fmt.done:
                run.stop.set()

        await run.node.subscribe(real, AnyMsg, on_msg)
        await run.stop.wait()
        if failed:
            raise TopicToolError(failed[0])
    return 0


async def run_hz(topics: Sequence[str], window: int, out: Out, *, clock: Callable[[], float] = time.time) -> int:
    """``rostopic hz``: report each topic's rate every second from arrival times (no decoding)."""
    from rostui.core.node import AnyMsg

    async with _Run() as run:
        stats: dict[str, HzStats] = {}
        for topic in topics:
            found = await _wait_for_topic(run, topic)
            if found is None:
                return 0
            st = stats.setdefault(topic, HzStats(window))
            add = st.add

            def on_msg(_raw: Any, add: Callable[[float], None] = add) -> None:
                add(clock())

            await run.node.subscribe(found[1], AnyMsg, on_msg)
            out(f"subscribed to [{found[1]}]\n")
        while not await run.sleep(1.0):
            if len(topics) == 1:
                out(format_hz(stats[topics[0]].stats()))
            else:
                out(format_hz_table([(t, stats[t].stats()) for t in topics]))
    return 0


async def run_bw(topic: str, window: int | None, out: Out) -> int:
    """``rostopic bw``: report the bandwidth of *topic* every second."""
    from rostui.core.node import AnyMsg

    async with _Run() as run:
        found = await _wait_for_topic(run, topic)
        if found is None:
            return 0
        st = BwStats(window)
        await run.node.subscribe(found[1], AnyMsg, lambda raw: st.add(time.time(), len(raw._buff)))
        out(f"subscribed to [{found[1]}]\n")
        while not await run.sleep(1.0):
            text = st.report(time.time())
            if text:
                out(text)
    return 0


async def _wait_for_subscriber(run: _Run, pub: Any, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        if await run.sleep(0.01):
            return


async def run_pub(topic: str, cls: Any, pub_args: list[Any], out: Out, *, rate: float | None, once: bool,
                  latch: bool, documents: Iterable[Any] | None = None, verbose: bool = False,
                  substitute: bool = False, single_document: bool = False) -> int:
    """``rostopic pub``: latch one message, repeat it at *rate*, or play *documents* (file/stdin)."""
    import asyncio

    from rostui.core.rostime import Time

    latched = rate is None or latch
    async with _Run() as run:
        try:
            pub = await run.node.advertise(topic, cls, queue_size=100, latch=latched)
        except Exception as e:
            raise TopicToolError(one_line(str(e))) from None

        def announce(msg: Any, once_: bool) -> None:
            from rostui.core.msg.convert import message_to_yaml

            s = f"publishing and latching [{message_to_yaml(msg)}]" if verbose else "publishing and latching message"
            out(s + (f" for {ONCE_DELAY} seconds\n" if once_ else ". Press ctrl-C to terminate\n"))

        async def at_rate(msg: Any, args: list[Any]) -> None:
            period = 1.0 / rate  # type: ignore[operator]
            loop = asyncio.get_running_loop()
            nxt = loop.time()
            while not run.stop.is_set():
                if substitute:
                    msg = build_message(cls, args, Time.now())
                if verbose:
                    from rostui.core.msg.convert import message_to_yaml
                    out(f"publishing {message_to_yaml(msg)}\n")
                pub.publish(msg)
                nxt += period
                delay = nxt - loop.time()
                if delay < -period:  # fell far behind: do not burst to catch up
                    nxt = loop.time()
                    delay = 0.0
                if await run.sleep(max(delay, 0.0)):
                    return

        if documents is None:
            msg = build_message(cls, pub_args, Time.now())
            if rate is None:
                announce(msg, once)
                pub.publish(msg)
                if once:
                    await run.sleep(ONCE_DELAY)
                else:
                    await run.stop.wait()
            else:
                await at_rate(msg, pub_args)
            return 0

        await _wait_for_subscriber(run, pub, SUBSCRIBER_TIMEOUT)
        docs = iter(documents)
        end = object()
        while not run.stop.is_set():
            doc = await asyncio.to_thread(next, docs, end)
            if doc is end:
                break
            if doc is None:
                continue
            args = doc if isinstance(doc, list) else [doc]
            msg = build_message(cls, args, Time.now())
            if single_document and rate is not None:
                out("Got one message and a rate, publishing repeatedly\n")
                await at_rate(msg, args)
            elif rate is None and not once:
                announce(msg, False)
                pub.publish(msg)
                await run.stop.wait()
            else:
                announce(msg, True)
                pub.publish(msg)
            if rate is not None:
                if await run.sleep(1.0 / rate):
                    break
            if once:
                break
        await asyncio.sleep(0.05)  # let the last frames leave before unregistering
    return 0


def stdin_documents() -> Iterator[Any]:
    """YAML documents read from stdin, each ended by a ``---`` line; a partial last one is dropped."""
    import yaml

    buff: list[str] = []
    for line in sys.stdin:
        if line.strip() == "---":
            try:
                loaded = yaml.safe_load("".join(buff).rstrip())
            except yaml.YAMLError as e:
                sys.stderr.write("Invalid YAML: %s\n" % yaml_error(e, "<stdin>"))
                loaded = None
            buff = []
            if loaded is not None:
                yield loaded
        else:
            buff.append(line)


# ----------------------------------------------------------------------------- completion
