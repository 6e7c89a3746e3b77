"""``bag filter``: copy the messages of a bag for which a Python expression over ``topic``, ``m`` and ``t`` holds.

As ``rosbag filter``: ``topic`` is the topic name, ``m`` the deserialised message (attributes as genpy's:
``m.data``, ``m.header.stamp.secs``) and ``t`` the message's time in the bag (a ``Time`` with ``secs``,
``nsecs``, ``to_sec()``, ``to_nsec()`` and comparisons). Messages are read in time order; every connection with
a kept message is written, headers unchanged.
"""

from __future__ import annotations

import builtins
import os
from collections.abc import Callable
from types import CodeType, SimpleNamespace
from typing import Any

from rostui.core.bag.decode import Decoder
from rostui.core.bag.files import ConnectionMap, merged_messages, open_reader
from rostui.core.bag.model import BagError
from rostui.core.bag.progress import Progress, counted
from rostui.tools.bag.rewrite import new_file
from rostui.core.rostime import Duration, Time

_TIME_NAMES = SimpleNamespace(Time=Time, Duration=Duration)
#: Names an expression sees besides the builtins, ``topic``, ``m`` and ``t``.
EXPRESSION_GLOBALS: dict[str, Any] = {"__builtins__": builtins, "Time": Time, "Duration": Duration,
                                      "rospy": _TIME_NAMES, "genpy": _TIME_NAMES}


class BagTime(Time):
    """``t``: a message's time in the bag, shown as rosbag shows it (``rospy.Time[...]``)."""

    def __repr__(self) -> str:
        return f"rospy.Time[{self.to_nsec()}]"


def compile_expression(expr: str, what: str = "expression") -> CodeType:
    """Compile one Python expression; BagError with a one-line reason when it is not one."""
    try:
        return compile(expr, f"<{what}>", "eval")
    except SyntaxError as exc:
        where = f" at column {exc.offset}" if exc.offset else ""
        raise BagError(f"invalid {what} '{expr}': {exc.msg}{where}") from None
    except ValueError as exc:  # e.g. a NUL byte
        raise BagError(f"invalid {what} '{expr}': {exc}") from None


def evaluate(code: CodeType, topic: str, m: Any, t: Time) -> Any:
    """The value of a compiled expression for one message."""
    return eval(code, EXPRESSION_GLOBALS, {"topic": topic, "m": m, "t": t})


def _describe_failure(what: str, exc: Exception, topic: str, t: Time) -> BagError:
    return BagError(f"the {what} failed on {topic} at {t.secs}.{t.nsecs:09d}: {type(exc).__name__}: {exc}")


def filter_bag(src: str, dst: str, expr: str, *, print_expr: str | None = None,
               printer: Callable[[str], None] | None = None, progress: Progress | None = None) -> tuple[int, int]:
    """Write the messages of ``src`` for which ``expr`` is true to ``dst`` (format by its name, uncompressed).

    With ``print_expr``, ``printer`` gets ``MATCH value`` or ``NO MATCH value`` for every message, as
    ``rosbag filter --print`` prints. Returns (kept, read). On any error ``dst`` is not touched.
    """
    if os.path.exists(dst) and os.path.exists(src) and os.path.samefile(src, dst):
        raise BagError(f"cannot use the same file as input and output: {src}")
    keep = compile_expression(expr)
    show = compile_expression(print_expr, "print expression") if print_expr is not None else None
    reader = open_reader(src)
    try:
        total = reader.summary().message_count if progress is not None else 0
        decode = Decoder()
        kept = read = 0
        with new_file(dst) as writer:
            conns = ConnectionMap(writer)
            for conn, time_ns, data, source in counted(merged_messages([reader]), total, progress):
                read += 1
                m = decode(conn, data)
                t = BagTime.from_nsec(time_ns)
                try:
                    match = bool(evaluate(keep, conn.topic, m, t))
                except Exception as exc:
                    raise _describe_failure("expression", exc, conn.topic, t) from None
                if show is not None and printer is not None:
                    try:
                        value = evaluate(show, conn.topic, m, t)
                    except Exception as exc:
                        raise _describe_failure("print expression", exc, conn.topic, t) from None
                    printer(f"{'MATCH' if match else 'NO MATCH'} {value}")
                if match:
                    conns.write(conn, time_ns, data, source)
                    kept += 1
        return kept, read
    finally:
        reader.close()
