"""A transform buffer fed by ``tf2_msgs/TFMessage`` from /tf and /tf_static, as tf2's BufferCore.

Each child frame has one edge to its parent. Static edges (from /tf_static) keep their one
transform forever; dynamic edges keep the samples of the last ``cache_time`` (by stamp)
and interpolate between them. Every edge also remembers who broadcast it (the publishing
node's name, the ``callerid`` of its connection header), when it was last received and its rate.

Stamps are integer nanoseconds, as tf2 keeps them, so two stamps 1 ns apart stay two and an
interpolation's fraction is tf2's. A lookup walks the tree the way tf2 walks it (up from the
source, then up from the target to where the first walk stopped), so it answers, and fails with
the same words, where tf2 does. Nothing here reads a clock: ``received`` and ``now`` are passed
in, in seconds.
"""

from __future__ import annotations

import bisect
from collections import deque
from dataclasses import dataclass, field
from typing import Any

from rostui.tools.topic.rates import window_rate
from rostui.tools.tf.transform import Transform

NS = 1_000_000_000
"""Nanoseconds in a second."""

DEFAULT_CACHE_TIME = 10.0
"""Seconds of dynamic transforms kept per edge (tf2's default)."""

MAX_FRAMES = 10_000
"""Frames one buffer accepts; a peer naming more is refused, not remembered."""

MAX_SAMPLES = 20_000
"""Samples one dynamic edge keeps at most (2 kHz for ten seconds); past it the oldest go first."""

MAX_GRAPH_DEPTH = 1000
"""Links a lookup walks up from a frame before it gives up, as tf2's BufferCore (deeper is taken for a loop)."""

LOOP_TEXT = "The tf tree is invalid because it contains a loop."
"""tf2's sentence for a loop, and for a chain deeper than :data:`MAX_GRAPH_DEPTH`."""

_MAX_RECEIPTS = 4096
#: Frames of a loop named in its error; a longer loop is shortened in the middle.
_LOOP_NAMES_SHOWN = 6


class TfError(Exception):
    """A lookup that cannot be answered; the message says why, in tf2's words where tf2 has them."""


class FrameNotFoundError(TfError):
    """A frame no transform names."""


class ConnectivityError(TfError):
    """Two frames in different trees."""


class LoopError(TfError):
    """The parent links of a frame go round in a circle."""


class DepthError(LoopError):
    """A frame more than :data:`MAX_GRAPH_DEPTH` links below its root: tf2 takes it for a loop, and so do lookups."""


class ExtrapolationError(TfError):
    """A lookup time outside the data an edge holds."""


class OldDataError(TfError):
    """A transform older than the edge's newest by more than the cache time (refused when the buffer says so)."""


class RepeatedDataError(OldDataError):
    """A second transform of an edge at a stamp it already has (refused when the buffer refuses old data)."""


def strip_frame(name: str) -> str:
    """A frame id as tf2 keys it: without leading slashes."""
    return name.lstrip("/")


def seconds(ns: int) -> float:
    """Nanoseconds as float seconds, as ROS's ``toSec()`` computes them (whole seconds plus the rest)."""
    whole, rest = divmod(ns, NS)
    return float(whole) + 1e-9 * float(rest)


def stamp_ns(stamp: Any) -> int:
    """A ROS time (``secs``/``nsecs``) or float seconds, in integer nanoseconds."""
    secs = getattr(stamp, "secs", None)
    if secs is None:
        return round(float(stamp) * NS)
    return int(secs) * NS + int(stamp.nsecs)


def _holds(stamps: list[int], stamp: int) -> bool:
    i = bisect.bisect_left(stamps, stamp)
    return i < len(stamps) and stamps[i] == stamp


def _earliest(common: int, stamp: int) -> int:
    """The earlier of two stamps, where 0 means none (a static link, or nothing seen yet)."""
    if not stamp:
        return common
    return min(common, stamp) if common else stamp


def _lookup_suffix(target: str, source: str) -> str:
    """What tf2 appends to an extrapolation error of a lookup."""
    return f", when looking up transform from frame [{source}] to frame [{target}]"


def _connectivity_text(target: str, source: str) -> str:
    return (f"Could not find a connection between '{target}' and '{source}' because they are not part of the "
            "same tree.Tf has two or more unconnected trees.")


@dataclass(frozen=True)
class Sample:
    """One transform of an edge at one stamp."""

    stamp_ns: int
    transform: Transform

    @property
    def stamp(self) -> float:
        """The stamp in seconds."""
        return seconds(self.stamp_ns)


@dataclass
class Edge:
    """The link from a child frame to its parent, with its history and who sends it."""

    child: str
    parent: str
    static: bool
    broadcaster: str
    samples: list[Sample] = field(default_factory=list)
    stamps: list[int] = field(default_factory=list)
    receipts: deque[float] = field(default_factory=lambda: deque(maxlen=_MAX_RECEIPTS))
    count: int = 0

    @property
    def latest(self) -> Sample:
        """The newest sample (an edge always has one)."""
        return self.samples[-1]

    @property
    def last_received(self) -> float:
        """When the newest message for this edge arrived (the ``received`` time given to the buffer)."""
        return self.receipts[-1] if self.receipts else 0.0

    def rate(self) -> float | None:
        """Messages per second over the receipts kept, or None (static, fewer than two, or all at once)."""
        if self.static or len(self.receipts) < 2:
            return None
        return window_rate(self.receipts) or None  # a burst of the first receipts counts once, as in the monitor

    def age(self, now: float) -> float:
        """Seconds between the newest stamp and ``now`` (for a static edge: since it was received)."""
        return now - (self.last_received if self.static else self.latest.stamp)

    def oldest_stamp(self) -> float:
        """The stamp of the oldest sample kept, in seconds."""
        return self.samples[0].stamp

    def latest_time_ns(self) -> int:
        """The newest stamp, or 0 for a static edge (valid at every time), as tf2's caches answer."""
        return 0 if self.static else self.stamps[-1]

    def at(self, time_ns: int) -> Transform:
        """The transform at ``time_ns`` (0: the newest), interpolated; a static edge answers for any time.

        Raises :class:`ExtrapolationError` in tf2's words (the lookup adds which frames it was between).
        """
        if self.static:
            return self.latest.transform
        samples, stamps = self.samples, self.stamps
        if time_ns == 0 or time_ns == stamps[-1]:
            return samples[-1].transform
        # tf2 (Noetic) writes these into fixed buffers of 116 and 163 bytes: with today's ten-digit stamps the
        # end of the sentence is cut off, and tf2's users (tf_echo, scripts printing the error) see it cut
        if len(stamps) == 1:
            raise ExtrapolationError(
                (f"Lookup would require extrapolation at time {seconds(time_ns):.9f}, but only time "
                 f"{seconds(stamps[0]):.9f} is in the buffer")[:115])
        if time_ns > stamps[-1]:
            raise ExtrapolationError(
                (f"Lookup would require extrapolation {seconds(time_ns - stamps[-1]):.9f}s into the future.  "
                 f"Requested time {seconds(time_ns):.9f} but the latest data is at time "
                 f"{seconds(stamps[-1]):.9f}")[:162])
        if time_ns < stamps[0]:
            raise ExtrapolationError(
                (f"Lookup would require extrapolation {seconds(stamps[0] - time_ns):.9f}s into the past.  "
                 f"Requested time {seconds(time_ns):.9f} but the earliest data is at time "
                 f"{seconds(stamps[0]):.9f}")[:162])
        i = bisect.bisect_left(stamps, time_ns)
        after = samples[i]
        if after.stamp_ns == time_ns:
            return after.transform
        before = samples[i - 1]
        fraction = seconds(time_ns - before.stamp_ns) / seconds(after.stamp_ns - before.stamp_ns)
        return before.transform.interpolate(after.transform, fraction)


def _loop_text(loop: list[str]) -> str:
    """``a -> b -> a``; a long loop keeps its first and last frames and says how many are left out."""
    if len(loop) > _LOOP_NAMES_SHOWN:
        left_out = len(loop) - _LOOP_NAMES_SHOWN
        loop = loop[:_LOOP_NAMES_SHOWN - 2] + [f"({left_out} more)"] + loop[-2:]
    return " -> ".join(loop)


@dataclass(frozen=True)
class StampedTransform:
    """A lookup's answer: ``transform`` maps points in ``source`` into ``target``, valid at ``stamp_ns``."""

    target: str
    source: str
    stamp_ns: int
    transform: Transform

    @property
    def stamp(self) -> float:
        """The stamp in seconds."""
        return seconds(self.stamp_ns)


class TfBuffer:
    """Frames and the edges between them, fed message by message; answers lookups through the tree.

    ``refuse_old_data``: a dynamic transform older than its edge's newest by more than ``cache_time``
    raises :class:`OldDataError`, as tf2 refuses it; otherwise (the views) time is taken to have jumped
    back (a bag played again) and the edge starts over.
    """

    def __init__(self, cache_time: float = DEFAULT_CACHE_TIME, max_frames: int = MAX_FRAMES, *,
                 refuse_old_data: bool = False) -> None:
        self.cache_time = cache_time
        self.cache_ns = round(cache_time * NS)
        self.max_frames = max_frames
        self.refuse_old_data = refuse_old_data
        self._edges: dict[str, Edge] = {}
        self._frames: dict[str, None] = {}
        self.structure = 0
        """Counts changes of the tree's shape (a frame or an edge added, a parent or kind changed, cleared)."""

    # -- feeding ---------------------------------------------------------------------------
    def add_message(self, msg: Any, *, static: bool, broadcaster: str, received: float) -> list[str]:
        """Take every transform of a ``tf2_msgs/TFMessage``; returns why any of them was refused."""
        problems: list[str] = []
        for ts in msg.transforms:
            try:
                self.set_transform(ts.header.frame_id, ts.child_frame_id, Transform.from_msg(ts.transform),
                                   stamp_ns(ts.header.stamp), static=static, broadcaster=broadcaster,
                                   received=received)
            except (TfError, ValueError) as exc:
                problems.append(f"ignoring transform from [{broadcaster}]: {exc}")
        return problems

    def set_transform(self, parent: str, child: str, transform: Transform, stamp: int, *, static: bool,
                      broadcaster: str, received: float) -> None:
        """Add one transform of ``child`` in ``parent`` at ``stamp`` (nanoseconds).

        Refuses empty or self-referring frame ids, and (``refuse_old_data``) data too old for the cache.
        """
        parent, child = strip_frame(parent), strip_frame(child)
        if not child:
            raise TfError(f"transform with parent [{parent}] has an empty child_frame_id")
        if not parent:
            raise TfError(f"transform of [{child}] has an empty frame_id")
        if parent == child:
            raise TfError(f"frame [{child}] cannot be its own parent")
        new_frames = [f for f in (child, parent) if f not in self._frames]
        if len(self._frames) + len(new_frames) > self.max_frames:
            raise TfError(f"more than {self.max_frames} frames; [{child}] not added")
        edge = self._edges.get(child)
        if (self.refuse_old_data and not static and edge is not None and not edge.static
                and edge.stamps[-1] > stamp + self.cache_ns):
            raise OldDataError("TF_OLD_DATA ignoring data from the past (Possible reasons are listed at "
                               f"http://wiki.ros.org/tf/Errors%20explained) for frame {child} at time "
                               f"{seconds(stamp):f} according to authority {broadcaster}")
        if (self.refuse_old_data and not static and edge is not None and not edge.static and edge.parent == parent
                and _holds(edge.stamps, stamp)):
            raise RepeatedDataError(f"TF_REPEATED_DATA ignoring data with redundant timestamp for frame {child} at "
                                    f"time {seconds(stamp):f} according to authority {broadcaster}")
        for frame in new_frames:
            self._frames[frame] = None
        if edge is None or edge.parent != parent or edge.static != static:
            edge = Edge(child, parent, static, broadcaster)
            self._edges[child] = edge
            self.structure += 1
        edge.broadcaster = broadcaster
        edge.count += 1
        edge.receipts.append(received)
        while len(edge.receipts) > 1 and edge.receipts[0] < received - self.cache_time:
            edge.receipts.popleft()
        sample = Sample(stamp, transform)
        if static:
            edge.samples = [sample]
            edge.stamps = [stamp]
            return
        self._insert(edge, sample)

    def _insert(self, edge: Edge, sample: Sample) -> None:
        samples, stamps = edge.samples, edge.stamps
        stamp = sample.stamp_ns
        if stamps and stamp < stamps[-1] - self.cache_ns:
            samples.clear()  # time jumped back (a bag played again, a simulator reset): start over
            stamps.clear()
        if not stamps or stamp > stamps[-1]:
            samples.append(sample)
            stamps.append(stamp)
        else:
            i = bisect.bisect_left(stamps, stamp)
            if i < len(stamps) and stamps[i] == stamp:
                samples[i] = sample
            else:
                samples.insert(i, sample)
                stamps.insert(i, stamp)
        horizon = stamps[-1] - self.cache_ns
        if stamps[0] < horizon or len(stamps) > MAX_SAMPLES:
            drop = max(min(bisect.bisect_left(stamps, horizon), len(stamps) - 1), len(stamps) - MAX_SAMPLES)
            del samples[:drop]
            del stamps[:drop]

    def clear(self) -> None:
        """Forget every frame and edge."""
        self._edges.clear()
        self._frames.clear()
        self.structure += 1

    # -- the tree --------------------------------------------------------------------------
    def frames(self) -> list[str]:
        """Every frame named by some transform, sorted."""
        return sorted(self._frames)

    def frames_in_order(self) -> list[str]:
        """Every frame in the order transforms first named them (a child before its parent), as tf2 numbers them."""
        return list(self._frames)

    def edges(self) -> list[Edge]:
        """Every edge, sorted by child frame."""
        return [self._edges[c] for c in sorted(self._edges)]

    def edges_in_order(self) -> list[Edge]:
        """Every edge, in the order of :meth:`frames_in_order` (tf2's listings)."""
        return [self._edges[f] for f in self._frames if f in self._edges]

    def edge(self, child: str) -> Edge | None:
        """The edge from ``child`` to its parent, or None for a root or unknown frame."""
        return self._edges.get(strip_frame(child))

    def parent(self, frame: str) -> str | None:
        """The parent of ``frame``, or None for a root or unknown frame."""
        edge = self._edges.get(strip_frame(frame))
        return edge.parent if edge else None

    def children(self, frame: str) -> list[str]:
        """The frames whose parent is ``frame``, sorted."""
        frame = strip_frame(frame)
        return sorted(e.child for e in self._edges.values() if e.parent == frame)

    def roots(self) -> list[str]:
        """Frames with no parent, sorted; a tree whose links form a loop has none."""
        return sorted(f for f in self._frames if f not in self._edges)

    def has_frame(self, frame: str) -> bool:
        """Whether some transform names ``frame`` (leading slashes ignored)."""
        return strip_frame(frame) in self._frames

    def has_exact_frame(self, frame: str) -> bool:
        """Whether some transform names exactly ``frame`` (``/map`` is not ``map``: tf2's frame ids have no slash)."""
        return frame in self._frames

    def chain(self, frame: str, max_depth: int | None = MAX_GRAPH_DEPTH) -> list[str]:
        """``frame`` and its ancestors up to its root.

        Raises :class:`LoopError` if they go round, :class:`DepthError` past ``max_depth`` links (None: no
        limit; tf2 walks at most :data:`MAX_GRAPH_DEPTH`).
        """
        start = strip_frame(frame)
        path = [start]
        seen = {start}
        frame = start
        while True:
            edge = self._edges.get(frame)
            if edge is None:
                return path
            frame = edge.parent
            if frame in seen:
                raise LoopError(f"{LOOP_TEXT} ({_loop_text(path[path.index(frame):] + [frame])})")
            if max_depth is not None and len(path) > max_depth:
                raise DepthError(f"{LOOP_TEXT} (more than {max_depth} links up from {start}; tf2 walks no further)")
            path.append(frame)
            seen.add(frame)

    def all_frames_as_string(self) -> str:
        """One line per edge, as tf2's allFramesAsString: ``Frame C exists with parent P.``"""
        return "".join(f"Frame {e.child} exists with parent {e.parent}.\n" for e in self.edges_in_order())

    # -- lookups ---------------------------------------------------------------------------
    def _too_deep(self, start: str) -> TfError:
        """The error for a walk from ``start`` past :data:`MAX_GRAPH_DEPTH` links: the loop named, if there is one."""
        try:
            self.chain(start)
        except LoopError as exc:
            return exc
        return DepthError(f"{LOOP_TEXT} (more than {MAX_GRAPH_DEPTH} links up from {start}; tf2 walks no further)")

    def _check_known(self, target: str, source: str) -> None:
        for frame, arg in ((target, "target_frame"), (source, "source_frame")):
            if frame not in self._frames:
                raise FrameNotFoundError(f'"{frame}" passed to lookupTransform argument {arg} does not exist. ')

    def latest_common_time(self, target: str, source: str) -> int:
        """The newest time (ns) every dynamic edge between the frames has data for (0 if all are static).

        Found as tf2's getLatestCommonTime finds it: up from the source, then up from the target until a
        parent the first walk met.
        """
        target, source = strip_frame(target), strip_frame(source)
        self._check_known(target, source)
        if source == target:
            edge = self._edges.get(source)
            return edge.latest_time_ns() if edge else 0
        source_links: list[tuple[int, str]] = []
        common = 0
        frame, depth = source, 0
        while (edge := self._edges.get(frame)) is not None:
            common = _earliest(common, edge.latest_time_ns())
            source_links.append((edge.latest_time_ns(), edge.parent))
            frame = edge.parent
            if frame == target:
                return common
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                raise self._too_deep(source)
        frame, depth, common = target, 0, 0
        meeting: str | None = None
        parents = {parent for _, parent in source_links}
        while (edge := self._edges.get(frame)) is not None:
            common = _earliest(common, edge.latest_time_ns())
            if edge.parent in parents:
                meeting = edge.parent
                break
            frame = edge.parent
            if frame == source:
                return common
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                raise self._too_deep(target)
        if meeting is None:
            raise ConnectivityError(_connectivity_text(target, source))
        for stamp, parent in source_links:
            common = _earliest(common, stamp)
            if parent == meeting:
                break
        return common

    def lookup_transform(self, target: str, source: str, time: int = 0) -> StampedTransform:
        """The transform taking points in ``source`` into ``target`` at ``time`` ns (0: the latest common time).

        Raises :class:`FrameNotFoundError`, :class:`ConnectivityError`, :class:`LoopError` or
        :class:`ExtrapolationError`, where tf2 raises its counterparts and with its words.
        """
        target, source = strip_frame(target), strip_frame(source)
        if target == source:
            edge = self._edges.get(target)
            stamp = edge.latest_time_ns() if time == 0 and edge is not None else time
            return StampedTransform(target, source, stamp, Transform.identity())
        self._check_known(target, source)
        if time == 0:
            time = self.latest_common_time(target, source)
        transform = self._walk(target, source, time)
        return StampedTransform(target, source, time, transform)

    def frames_between(self, target: str, source: str, time: int = 0) -> list[str]:
        """The frames a lookup of ``source`` in ``target`` at ``time`` passes, from the source on (tf2's chain)."""
        target, source = strip_frame(target), strip_frame(source)
        if target == source:
            return []
        self._check_known(target, source)
        walked: list[str] = []
        self._walk(target, source, time or self.latest_common_time(target, source), walked)
        return walked

    def _walk(self, target: str, source: str, time: int, walked: list[str] | None = None) -> Transform:
        """tf2's walkToTopParent: up from the source to its root or the target, then up from the target.

        ``walked`` (if given) receives the frames passed: the source's walk, then the target's reversed.
        """
        up: list[str] = []
        down: list[str] = []
        try:
            return self._walk_both(target, source, time, up, down)
        finally:
            if walked is not None:
                walked.extend(up + down[::-1])

    def _walk_both(self, target: str, source: str, time: int, up: list[str], down: list[str]) -> Transform:
        source_to_top = Transform.identity()
        frame, top, depth = source, source, 0
        extrapolation: str | None = None
        while (edge := self._edges.get(frame)) is not None:
            up.append(frame)
            try:
                link = edge.at(time)
            except ExtrapolationError as exc:
                top, extrapolation = frame, str(exc)
                break
            if frame == target:
                return source_to_top
            source_to_top = link * source_to_top
            top, frame = frame, edge.parent
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                raise self._too_deep(source)
        else:
            top = frame
            up.append(frame)
        target_to_top = Transform.identity()
        frame, depth = target, 0
        while frame != top and (edge := self._edges.get(frame)) is not None:
            down.append(frame)
            try:
                link = edge.at(time)
            except ExtrapolationError as exc:
                raise ExtrapolationError(f"{exc}{_lookup_suffix(target, source)}") from None
            if frame == source:
                return target_to_top.inverse()
            target_to_top = link * target_to_top
            frame = edge.parent
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                raise self._too_deep(target)
        if frame != top:
            if extrapolation is not None:
                raise ExtrapolationError(f"{extrapolation}{_lookup_suffix(target, source)}")
            raise ConnectivityError(_connectivity_text(target, source))
        return target_to_top.inverse() * source_to_top

    def can_transform(self, target: str, source: str, time: int = 0) -> bool:
        """Whether :meth:`lookup_transform` would answer."""
        try:
            self.lookup_transform(target, source, time)
        except TfError:
            return False
        return True
