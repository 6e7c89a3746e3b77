"""A transform buffer fed by ``tf2_msgs/TFMessage`` from /tf and /tf_static, as tf2's BufferCore.

Each child frame has one edge to its parent. Static edges (from /tf_static) keep their one
transform forever; dynamic edges keep the samples of the last ``cache_time`` seconds (by stamp)
and interpolate between them. Every edge also remembers who broadcast it (the publishing
node's name, the ``callerid`` of its connection header), when it was last received and its rate.

Nothing here reads a clock: times (``received``, ``now``) are passed in, in seconds.
"""

from __future__ import annotations

import bisect
from collections import deque
from dataclasses import dataclass, field
from typing import Any

from rostui.tools.topic.rates import window_rate
from rostui.tools.tf.transform import Transform

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


def strip_frame(name: str) -> str:
    """A frame id as tf2 keys it: without leading slashes."""
    return name.lstrip("/")


@dataclass(frozen=True)
class Sample:
    """One transform of an edge at one stamp."""

    stamp: float
    transform: Transform


@dataclass
class Edge:
    """The link from a child frame to its parent, with its history and who sends it."""

    child: str
    parent: str
    static: bool
    broadcaster: str
    samples: list[Sample] = field(default_factory=list)
    stamps: list[float] = field(default_factory=list)
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
        """The stamp of the oldest sample kept."""
        return self.samples[0].stamp

    def at(self, time: float) -> Transform:
        """The transform at ``time``, interpolated; a static edge answers for any time."""
        if self.static:
            return self.latest.transform
        samples = self.samples
        if time == samples[-1].stamp:
            return samples[-1].transform
        first, last = samples[0].stamp, samples[-1].stamp
        if time > last:
            raise ExtrapolationError(
                f"Lookup would require extrapolation into the future.  Requested time {time:.9f} but the latest "
                f"data is at time {last:.9f}, when looking up transform from frame [{self.child}] to frame "
                f"[{self.parent}]")
        if time < first:
            raise ExtrapolationError(
                f"Lookup would require extrapolation into the past.  Requested time {time:.9f} but the earliest "
                f"data is at time {first:.9f}, when looking up transform from frame [{self.child}] to frame "
                f"[{self.parent}]")
        i = bisect.bisect_left(self.stamps, time)
        after = samples[i]
        if after.stamp == time:
            return after.transform
        before = samples[i - 1]
        fraction = (time - before.stamp) / (after.stamp - before.stamp)
        return before.transform.interpolate(after.transform, fraction)


def _loop_text(loop: list[str]) -> str:
    """``a -> b -> a``; a long loop keeps its first and last frames and says how many are left out."""
    if len(loop) > _LOOP_NAMES_SHOWN:
        left_out = len(loop) - _LOOP_NAMES_SHOWN
        loop = loop[:_LOOP_NAMES_SHOWN - 2] + [f"({left_out} more)"] + loop[-2:]
    return " -> ".join(loop)


@dataclass(frozen=True)
class StampedTransform:
    """A lookup's answer: ``transform`` maps points in ``source`` into ``target``, valid at ``stamp``."""

    target: str
    source: str
    stamp: float
    transform: Transform


def _stamp_seconds(stamp: Any) -> float:
    secs = getattr(stamp, "secs", None)
    if secs is None:
        return float(stamp)
    return float(secs) + float(stamp.nsecs) * 1e-9


class TfBuffer:
    """Frames and the edges between them, fed message by message; answers lookups through the tree."""

    def __init__(self, cache_time: float = DEFAULT_CACHE_TIME, max_frames: int = MAX_FRAMES) -> None:
        self.cache_time = cache_time
        self.max_frames = max_frames
        self._edges: dict[str, Edge] = {}
        self._frames: set[str] = set()
        self.structure = 0
        """Counts changes of the tree's shape (a frame or an edge added, a parent or kind changed, cleared)."""

    # -- feeding ---------------------------------------------------------------------------
    def add_message(self, msg: Any, *, static: bool, broadcaster: str, received: float) -> list[str]:
        """Take every transform of a ``tf2_msgs/TFMessage``; returns why any of them was refused."""
        problems: list[str] = []
        for ts in msg.transforms:
            try:
                self.set_transform(ts.header.frame_id, ts.child_frame_id, Transform.from_msg(ts.transform),
                                   _stamp_seconds(ts.header.stamp), static=static, broadcaster=broadcaster,
                                   received=received)
            except (TfError, ValueError) as exc:
                problems.append(f"ignoring transform from [{broadcaster}]: {exc}")
        return problems

    def set_transform(self, parent: str, child: str, transform: Transform, stamp: float, *, static: bool,
                      broadcaster: str, received: float) -> None:
        """Add one transform of ``child`` in ``parent``; refuses empty or self-referring frame ids."""
        parent, child = strip_frame(parent), strip_frame(child)
        if not child:
            raise TfError(f"transform with parent [{parent}] has an empty child_frame_id")
        if not parent:
            raise TfError(f"transform of [{child}] has an empty frame_id")
        if parent == child:
            raise TfError(f"frame [{child}] cannot be its own parent")
        new_frames = {parent, child} - self._frames
        if len(self._frames) + len(new_frames) > self.max_frames:
            raise TfError(f"more than {self.max_frames} frames; [{child}] not added")
        edge = self._edges.get(child)
        if edge is None or edge.parent != parent or edge.static != static:
            edge = Edge(child, parent, static, broadcaster)
            self._edges[child] = edge
            self.structure += 1
        edge.broadcaster = broadcaster
        edge.count += 1
        edge.receipts.append(received)
        while len(edge.receipts) > 1 and edge.receipts[0] < received - self.cache_time:
            edge.receipts.popleft()
        self._frames |= new_frames
        sample = Sample(stamp, transform)
        if static:
            edge.samples = [sample]
            edge.stamps = [stamp]
            return
        self._insert(edge, sample)

    def _insert(self, edge: Edge, sample: Sample) -> None:
        samples, stamps = edge.samples, edge.stamps
        stamp = sample.stamp
        if stamps and stamp < stamps[-1] - self.cache_time:
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
        horizon = stamps[-1] - self.cache_time
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

    def edges(self) -> list[Edge]:
        """Every edge, sorted by child frame."""
        return [self._edges[c] for c in sorted(self._edges)]

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
        """Whether some transform names ``frame``."""
        return strip_frame(frame) in self._frames

    def chain(self, frame: str, max_depth: int | None = MAX_GRAPH_DEPTH) -> list[str]:
        """``frame`` and its ancestors up to its root.

        Raises :class:`LoopError` if they go round, :class:`DepthError` past ``max_depth`` links (None: no
        limit; tf2 walks at most :data:`MAX_GRAPH_DEPTH`).
        """
        return self._walk_up(strip_frame(frame), (), max_depth)

    def _walk_up(self, start: str, stops: tuple[str, ...], max_depth: int | None = MAX_GRAPH_DEPTH) -> list[str]:
        """``start`` and its ancestors up to the first of ``stops`` or the root, without recursion."""
        path = [start]
        seen = {start}
        frame = start
        while frame not in stops:
            edge = self._edges.get(frame)
            if edge is None:
                break
            frame = edge.parent
            if frame in seen:
                raise LoopError(f"{LOOP_TEXT} ({_loop_text(path[path.index(frame):] + [frame])})")
            if max_depth is not None and len(path) > max_depth:
                raise DepthError(f"{LOOP_TEXT} (more than {max_depth} links up from {start}; tf2 walks no further)")
            path.append(frame)
            seen.add(frame)
        return path

    def all_frames_as_string(self) -> str:
        """One line per edge, as tf2's allFramesAsString: ``Frame C exists with parent P.``"""
        return "".join(f"Frame {e.child} exists with parent {e.parent}.\n" for e in self.edges())

    # -- lookups ---------------------------------------------------------------------------
    def _path(self, target: str, source: str) -> tuple[list[str], list[str]]:
        """The source's frames up to where the two meet, and the target's (each starting at itself).

        Walked as tf2 walks them: the source up to the target or its root, then the target up to that root
        or the source, each at most :data:`MAX_GRAPH_DEPTH` links, so a lookup answers, or fails, as tf2's.
        """
        for frame, arg in ((target, "target_frame"), (source, "source_frame")):
            if frame not in self._frames:
                raise FrameNotFoundError(f'"{frame}" passed to lookupTransform argument {arg} does not exist. ')
        up_source = self._walk_up(source, (target,))
        if up_source[-1] == target:
            return up_source, [target]
        top = up_source[-1]
        up_target = self._walk_up(target, (top, source))
        if up_target[-1] == source:
            return [source], up_target
        if up_target[-1] != top:
            raise ConnectivityError(
                f"Could not find a connection between '{target}' and '{source}' because they are not part of the "
                "same tree.Tf has two or more unconnected trees.")
        return up_source, up_target

    def latest_common_time(self, target: str, source: str) -> float:
        """The newest time every dynamic edge between the frames has data for (0.0 if all are static)."""
        target, source = strip_frame(target), strip_frame(source)
        up_source, up_target = self._path(target, source)
        stamps = [e.latest.stamp for e in self._path_edges(up_source, up_target) if not e.static]
        return min(stamps) if stamps else 0.0

    def _path_edges(self, up_source: list[str], up_target: list[str]) -> list[Edge]:
        return [self._edges[f] for f in up_source[:-1]] + [self._edges[f] for f in up_target[:-1]]

    def lookup_transform(self, target: str, source: str, time: float | None = None) -> StampedTransform:
        """The transform taking points in ``source`` into ``target`` at ``time`` (None: the latest common time).

        Raises :class:`FrameNotFoundError`, :class:`ConnectivityError`, :class:`LoopError` or
        :class:`ExtrapolationError`.
        """
        target, source = strip_frame(target), strip_frame(source)
        up_source, up_target = self._path(target, source)
        if time is None or time == 0.0:
            stamps = [e.latest.stamp for e in self._path_edges(up_source, up_target) if not e.static]
            time = min(stamps) if stamps else 0.0
        anc_from_source = Transform.identity()
        for frame in up_source[:-1]:
            anc_from_source = self._edges[frame].at(time) * anc_from_source
        anc_from_target = Transform.identity()
        for frame in up_target[:-1]:
            anc_from_target = self._edges[frame].at(time) * anc_from_target
        return StampedTransform(target, source, time, anc_from_target.inverse() * anc_from_source)

    def can_transform(self, target: str, source: str, time: float | None = None) -> bool:
        """Whether :meth:`lookup_transform` would answer."""
        try:
            self.lookup_transform(target, source, time)
        except TfError:
            return False
        return True
