"""tf2_py for unmodified ROS 1 scripts: tf2's ``BufferCore`` and its exceptions, on rostui's tf buffer.

The buffer is :class:`rostui.tools.tf.buffer.TfBuffer` (the one the tf views use), told to refuse
data older than its cache as tf2 does. This module is the face tf2's Python binding shows: times go
in through ``to_sec()`` and come out as ``rospy.Time``, frame ids are checked with tf2's words, and
each failure raises the exception tf2 raises, with its text. Problems with an incoming transform
are printed on stderr, as tf2's C++ console prints them, and the transform is ignored.
"""

from __future__ import annotations

import math
import os
import sys
import threading
from typing import Any

from rostui.core.msg import get_message_class
from rostui.tools.tf.buffer import (
    LOOP_TEXT, NS, ConnectivityError, ExtrapolationError, FrameNotFoundError, LoopError, OldDataError, TfBuffer,
    TfError, seconds,
)
from rostui.tools.tf.transform import Transform, compose_as_matrices

__all__ = ["BufferCore", "ConnectivityException", "ExtrapolationException", "InvalidArgumentException",
           "LookupException", "TimeoutException", "TransformException"]


class TransformException(Exception):
    """The base of tf2's errors (``tf2.TransformException``)."""


class ConnectivityException(TransformException):
    """The two frames are in different trees."""


class LookupException(TransformException):
    """A frame no transform names, or a tree that loops."""


class ExtrapolationException(TransformException):
    """The time asked for is outside the data the buffer holds."""


class InvalidArgumentException(TransformException):
    """A frame id that is empty or starts with ``/``."""


class TimeoutException(TransformException):
    """A wait for a transform ran out of time."""


for _cls in (TransformException, ConnectivityException, LookupException, ExtrapolationException,
             InvalidArgumentException, TimeoutException):
    _cls.__module__ = "tf2"  # their printed name, as the binding's: tf2.LookupException

_DEFAULT_CACHE_SECONDS = 10.0


def time_ns(t: Any) -> int:
    """A ``rospy.Time``/``Duration`` as tf2's binding reads it: through ``to_sec()``, rounded to nanoseconds."""
    to_sec = getattr(t, "to_sec", None)
    if to_sec is None:
        raise TypeError("time must have a to_sec method, e.g. rospy.Time or rospy.Duration")
    value = float(to_sec())
    whole = math.floor(value)
    rest = value - whole
    nsec = int(math.floor(rest * 1e9 + 0.5))  # ROS's fromSec: round half away from zero, rest is never negative
    return whole * NS + nsec


def ros_time(ns: int) -> Any:
    """A ``rospy.Time`` of ``ns`` nanoseconds (the script's rospy, as tf2's binding makes them)."""
    import rospy  # the script's rospy: rostui's under `rostui python`

    return rospy.Time(ns // NS, ns % NS)


def _transform_stamped(target: str, source: str, stamp: int, transform: Transform) -> Any:
    msg: Any = get_message_class("geometry_msgs/TransformStamped")()
    msg.header.frame_id = target
    msg.header.stamp = ros_time(stamp)
    msg.child_frame_id = source
    t, q = msg.transform.translation, msg.transform.rotation
    t.x, t.y, t.z = (float(v) for v in transform.translation)
    q.x, q.y, q.z, q.w = (float(v) for v in transform.rotation)
    return msg


def _print_problem(level: str, text: str) -> None:
    """Say it on the process's stderr itself, as tf2's C++ console does (a test runner capturing
    ``sys.stderr`` does not catch it)."""
    line = f"{level}:   {text}\n" if level == "Error" else f"{level}: {text}\n"
    sys.stderr.flush()
    os.write(2, line.encode(errors="replace"))


def _invalid_frame_text(frame: str, where: str) -> str | None:
    if not frame:
        return f"Invalid argument passed to {where} in tf2 frame_ids cannot be empty"
    if frame.startswith("/"):
        return f"Invalid argument \"{frame}\" passed to {where} in tf2 frame_ids cannot start with a '/' like: "
    return None


class BufferCore:
    """tf2's transform buffer: transforms in, lookups and can-transform questions out."""

    def __init__(self, cache_time: Any = None) -> None:
        cache = _DEFAULT_CACHE_SECONDS if cache_time is None else time_ns(cache_time) / NS
        self._buffer = TfBuffer(cache, refuse_old_data=True)
        self._lock = threading.RLock()  # listeners write from the engine's thread while the script looks up

    # -- feeding ---------------------------------------------------------------------------
    def set_transform(self, transform: Any, authority: str) -> None:
        """Add a dynamic ``geometry_msgs/TransformStamped`` sent by ``authority``; a bad one is reported and ignored."""
        self._set(transform, authority, static=False)

    def set_transform_static(self, transform: Any, authority: str) -> None:
        """Add a static transform (valid at every time) sent by ``authority``."""
        self._set(transform, authority, static=True)

    def _set(self, ts: Any, authority: str, *, static: bool) -> None:
        child = str(ts.child_frame_id).lstrip("/")
        parent = str(ts.header.frame_id).lstrip("/")
        tr, rot = ts.transform.translation, ts.transform.rotation
        xyz = (float(tr.x), float(tr.y), float(tr.z))
        quat = (float(rot.x), float(rot.y), float(rot.z), float(rot.w))
        problems = []
        if child == parent:
            problems.append(f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with frame_id and '
                            f'child_frame_id  "{child}" because they are the same')
        if not child:
            problems.append(f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" because '
                            "child_frame_id not set ")
        if not parent:
            problems.append(f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from authority '
                            f'"{authority}" because frame_id not set')
        values = " ".join(f"{v:f}" for v in xyz), " ".join(f"{v:f}" for v in quat)
        if any(math.isnan(v) for v in xyz + quat):
            problems.append(f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority '
                            f'"{authority}" because of a nan value in the transform ({values[0]}) ({values[1]})')
        elif abs(sum(v * v for v in quat) - 1.0) > 0.01:
            problems.append(f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" from '
                            f'authority "{authority}" because of an invalid quaternion in the transform ({values[1]})')
        if problems:
            for text in problems:
                _print_problem("Error", text)
            return
        try:
            with self._lock:
                self._buffer.set_transform(parent, child, Transform.of(xyz, quat), time_ns(ts.header.stamp),
                                           static=static, broadcaster=authority, received=0.0)
        except OldDataError as exc:
            _print_problem("Warning", str(exc))
        except (TfError, ValueError) as exc:
            _print_problem("Error", str(exc))

    def clear(self) -> None:
        """Forget every transform."""
        with self._lock:
            self._buffer.clear()

    # -- checks ----------------------------------------------------------------------------
    def _validate(self, frame: str, where: str) -> None:
        problem = _invalid_frame_text(frame, where)
        if problem is not None:
            raise InvalidArgumentException(problem)
        if not self._buffer.has_exact_frame(frame):
            raise LookupException(f'"{frame}" passed to {where} does not exist. ')

    def _tf2_error(self, exc: TfError) -> TransformException:
        if isinstance(exc, LoopError):
            return LookupException(f"{LOOP_TEXT}\n{self.all_frames_as_string()}\n")
        if isinstance(exc, ExtrapolationError):
            return ExtrapolationException(str(exc))
        if isinstance(exc, ConnectivityError):
            return ConnectivityException(str(exc))
        if isinstance(exc, FrameNotFoundError):
            return LookupException(str(exc))
        return TransformException(str(exc))

    # -- lookups ---------------------------------------------------------------------------
    def _lookup(self, target: str, source: str, time: int) -> Any:
        if target != source:
            self._validate(target, "lookupTransform argument target_frame")
            self._validate(source, "lookupTransform argument source_frame")
        try:
            with self._lock:
                return self._buffer.lookup_transform(target, source, time)
        except TfError as exc:
            raise self._tf2_error(exc) from None

    def lookup_transform_core(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """The ``geometry_msgs/TransformStamped`` taking points in ``source_frame`` into ``target_frame`` at ``time``.

        ``time`` zero means the latest time the whole chain has data for.
        """
        st = self._lookup(target_frame, source_frame, time_ns(time))
        return _transform_stamped(target_frame, source_frame, st.stamp_ns, st.transform)

    def lookup_transform_full_core(self, target_frame: str, target_time: Any, source_frame: str,
                                   source_time: Any, fixed_frame: str) -> Any:
        """The transform from ``source_frame`` at ``source_time`` to ``target_frame`` at ``target_time``, through a frame fixed in time."""
        for frame, arg in ((target_frame, "target_frame"), (source_frame, "source_frame"), (fixed_frame, "fixed_frame")):
            self._validate(frame, f"lookupTransform argument {arg}")
        fixed_from_source = self._lookup(fixed_frame, source_frame, time_ns(source_time))
        target_from_fixed = self._lookup(target_frame, fixed_frame, time_ns(target_time))
        return _transform_stamped(target_frame, source_frame, target_from_fixed.stamp_ns,
                                  compose_as_matrices(target_from_fixed.transform, fixed_from_source.transform))

    def _can_frames(self, frames: list[tuple[str, str]]) -> tuple[bool, str]:
        """Whether every frame id is valid and known; tf2's warning for a malformed one, its text for unknown ones."""
        for frame, arg in frames:
            problem = _invalid_frame_text(frame, f"canTransform argument {arg}")
            if problem is not None:
                _print_problem("Warning", problem)
                return False, ""
        missing = [f"canTransform: {arg} {frame} does not exist." for frame, arg in frames
                   if not self._buffer.has_exact_frame(frame)]
        return not missing, " ".join(missing)

    def _can(self, target: str, source: str, time: int) -> tuple[bool, str]:
        try:
            with self._lock:
                self._buffer.lookup_transform(target, source, time)
        except TfError as exc:
            return False, str(self._tf2_error(exc))
        return True, ""

    def can_transform_core(self, target_frame: str, source_frame: str, time: Any) -> tuple[int, str]:
        """``(1, "")`` when the lookup would answer, else ``(0, why)``; never raises for a missing frame."""
        if target_frame == source_frame:
            return 1, ""
        ok, why = self._can_frames([(target_frame, "target_frame"), (source_frame, "source_frame")])
        if ok:
            ok, why = self._can(target_frame, source_frame, time_ns(time))
        return int(ok), why

    def can_transform_full_core(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                                fixed_frame: str) -> tuple[int, str]:
        """:meth:`can_transform_core` for :meth:`lookup_transform_full_core`'s arguments."""
        for frame, arg in ((target_frame, "target_frame"), (source_frame, "source_frame"), (fixed_frame, "fixed_frame")):
            problem = _invalid_frame_text(frame, f"canTransform argument {arg}")
            if problem is not None:
                _print_problem("Warning", problem)
                return 0, ""
        target_known, source_known = self._buffer.has_exact_frame(target_frame), self._buffer.has_exact_frame(source_frame)
        ok = target_known and source_known and self._buffer.has_exact_frame(fixed_frame)
        why = "" if target_known else f"canTransform: target_frame {target_frame} does not exist."
        if not source_known:  # tf2 (Noetic) words the fixed frame's part so, and adds it when the source is missing
            why += ("" if target_known else " ") + f"canTransform: source_frame {source_frame} does not exist."
            why += f" fixed_frame: {fixed_frame}does not exist."
        if ok:
            ok, why = self._can(target_frame, fixed_frame, time_ns(target_time))
        if ok:
            ok, why = self._can(fixed_frame, source_frame, time_ns(source_time))
        return int(ok), why

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        """The newest ``rospy.Time`` at which both frames' chain has data (zero when it is all static)."""
        self._validate(target_frame, "get_latest_common_time")
        self._validate(source_frame, "get_latest_common_time")
        try:
            with self._lock:
                return ros_time(self._buffer.latest_common_time(target_frame, source_frame))
        except TfError as exc:
            raise TransformException(str(self._tf2_error(exc))) from None

    # -- listings --------------------------------------------------------------------------
    def all_frames_as_string(self) -> str:
        """``Frame C exists with parent P.`` for each frame that has a parent."""
        with self._lock:
            return self._buffer.all_frames_as_string()

    def all_frames_as_yaml(self, *_: Any) -> str:
        """Each frame with its parent, broadcaster, rate and the span of its data, as tf2's YAML."""
        out = []
        with self._lock:
            rows = [(edge, _edge_numbers(edge)) for edge in self._buffer.edges_in_order()]
        for edge, (newest, oldest, rate, length) in rows:
            out.append(f"{edge.child}: \n  parent: '{edge.parent}'\n  broadcaster: '{edge.broadcaster}'\n"
                       f"  rate: {rate:.3f}\n  most_recent_transform: {newest:.3f}\n"
                       f"  oldest_transform: {oldest:.3f}\n  buffer_length: {length:.3f}\n")
        return "".join(out)

    def _allFramesAsDot(self, current_time: Any = None) -> str:  # noqa: N802 (tf2's name)
        """The tree as a Graphviz digraph, as tf2's view_frames draws it."""
        with self._lock:
            edges = self._buffer.edges_in_order()
            numbers = [_edge_numbers(edge) for edge in edges]
            roots = [e.parent for e in edges if self._buffer.edge(e.parent) is None]
        if not edges:
            return 'digraph G {\n"no tf data recieved"}'
        now = None if current_time is None else seconds(time_ns(current_time))
        lines = ["digraph G {"]
        for edge, (newest, _, rate, length) in zip(edges, numbers):
            old = "" if now is None else f"( {now - newest:.3f} sec old)"
            lines.append(f'"{edge.parent}" -> "{edge.child}"[label="Broadcaster: {edge.broadcaster}\\n'
                         f"Average rate: {rate:.3f} Hz\\nMost recent transform: {newest:.3f} {old}\\n"
                         f'Buffer length: {length:.3f} sec\\n"];')
        if now is not None:
            for root in dict.fromkeys(roots):
                lines.append("edge [style=invis];")
                lines.append(' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";')
                lines.append(f'"Recorded at time: {now:.3f}"[ shape=plaintext ] ;')
                lines.append(f' }}->"{root}";')
        lines.append("}")
        return "\n".join(lines)

    def _frameExists(self, frame_id: str) -> bool:  # noqa: N802 (tf2's name)
        """Whether a transform named ``frame_id`` (exactly: no slash is stripped)."""
        return self._buffer.has_exact_frame(frame_id)

    def _getFrameStrings(self) -> list[str]:  # noqa: N802 (tf2's name)
        """Every frame id, in the order transforms first named them."""
        return self._buffer.frames_in_order()

    def _chain(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
               fixed_frame: str) -> list[str]:
        """The frames a lookup from ``source_frame`` through ``fixed_frame`` to ``target_frame`` passes."""
        for frame, arg in ((target_frame, "target_frame"), (source_frame, "source_frame"), (fixed_frame, "fixed_frame")):
            self._validate(frame, f"lookupTransform argument {arg}")
        try:
            with self._lock:
                first = self._buffer.frames_between(fixed_frame, source_frame, time_ns(source_time))
                second = self._buffer.frames_between(target_frame, fixed_frame, time_ns(target_time))
        except TfError as exc:
            raise self._tf2_error(exc) from None
        return first + [f for f in second if f not in first]


def _edge_numbers(edge: Any) -> tuple[float, float, float, float]:
    """Newest and oldest stamp, rate and span of an edge, as tf2 reports them (a static edge: all at zero)."""
    if edge.static:
        return 0.0, 0.0, 1 / 0.0001, 0.0
    newest, oldest = seconds(edge.stamps[-1]), seconds(edge.stamps[0])
    rate = len(edge.stamps) / max(newest - oldest, 0.0001)
    return newest, oldest, rate, seconds(edge.stamps[-1] - edge.stamps[0])
