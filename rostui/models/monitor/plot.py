"""The monitor's plot as data: numeric fields of topics sampled over time, a time window and pause.

Pure data (no Textual): a :class:`PlotModel` holds one :class:`Series` per
plotted field, each a ring buffer of ``(arrival time, value)``.  The shown
window ends at "now", or at the moment :meth:`PlotModel.pause` was called:
while paused the buffers keep filling and counting, only the picture stands
still.  Field names follow rqt_plot: ``/turtle1/pose/x`` is field ``x`` of
topic ``/turtle1/pose``, ``/turtle1/pose/x:y:theta`` three fields of it,
and nested fields are written ``linear/x`` or ``linear.x``.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field
from typing import Any, Iterable, Sequence

from rostui.core.rostime import TVal
from rostui.models.monitor.tree import ARRAY_SHOWN, PathError, value_at

__all__ = [
    "PlotModel", "Series", "SeriesView", "PlotFieldError", "WINDOWS", "DEFAULT_WINDOW", "CAPACITY",
    "numeric_fields", "check_numeric", "normal_path", "split_spec", "expand_spec", "nice_ticks", "thin",
]

#: Time windows (seconds) the plot steps through with + and -.
WINDOWS: tuple[float, ...] = (1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0, 120.0, 300.0)
#: The window a new plot shows, as rqt_plot's default of 10 s.
DEFAULT_WINDOW = 10.0
#: Points kept per field: 300 s of turtlesim's 62 Hz pose (the oldest go first; anything older than the longest window too).
CAPACITY = 20_000


class PlotFieldError(ValueError):
    """A field that cannot be plotted (not in the message, or not a number), said in one line."""


def normal_path(path: str) -> str:
    """``linear.x`` and ``/linear/x`` as the tree writes them: ``linear/x``."""
    return "/".join(part for part in path.replace(".", "/").split("/") if part)


def _is_message(value: Any) -> bool:
    return hasattr(value, "__slots__") and hasattr(value, "_slot_types")


def _kind(value: Any) -> str:
    if _is_message(value):
        return f"a message ({getattr(value, '_type', type(value).__name__)})"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, (bytes, bytearray, list, tuple)):
        return f"an array of {len(value)}"
    return f"a {type(value).__name__}"


def _walk(msg: Any, path: str) -> Any:
    """The raw value at ``path`` (PathError when there is none)."""
    value = msg
    for part in path.split("/"):
        name, _, rest = part.partition("[")
        if not _is_message(value) or name not in value.__slots__:
            raise PathError(f"no field {name!r}")
        value = getattr(value, name)
        while rest:
            number, _, rest = rest.partition("]")
            rest = rest.removeprefix("[")
            try:
                value = value[int(number)]
            except (ValueError, IndexError, TypeError):
                raise PathError(f"no item [{number}]") from None
    return value


def check_numeric(msg: Any, topic: str, path: str) -> float:
    """The value of field ``path`` of ``msg`` (received on ``topic``); :class:`PlotFieldError` if it is no number."""
    path = normal_path(path)
    where = f"{topic}/{path}"
    if not path:
        raise PlotFieldError(f"{topic} is a topic: name one of its numeric fields, as {topic}/x")
    try:
        raw = _walk(msg, path)
    except PathError as exc:
        raise PlotFieldError(f"{where}: {exc} in {getattr(msg, '_type', 'the message')}") from None
    if isinstance(raw, (bool, int, float, TVal)):
        return value_at(msg, path)
    hint = ""
    if _is_message(raw):
        numbers = numeric_fields(raw)
        if numbers:
            hint = f", e.g. {where}/{numbers[0]}"
    raise PlotFieldError(f"{where} is {_kind(raw)}, not a number: only numeric fields can be plotted{hint}")


def numeric_fields(msg: Any, prefix: str = "") -> list[str]:
    """Paths of every numeric field of ``msg``, nested ones too (``linear/x``); arrays by their first items."""
    paths: list[str] = []
    for name in msg.__slots__:
        value = getattr(msg, name)
        path = f"{prefix}/{name}" if prefix else name
        if isinstance(value, (bool, int, float, TVal)):
            paths.append(path)
        elif _is_message(value):
            paths.extend(numeric_fields(value, path))
        elif isinstance(value, (list, tuple)) or (isinstance(value, (bytes, bytearray)) and len(value) <= ARRAY_SHOWN):
            for index, item in enumerate(value[:ARRAY_SHOWN]):
                if isinstance(item, (bool, int, float, TVal)):
                    paths.append(f"{path}[{index}]")
                elif _is_message(item):
                    paths.extend(numeric_fields(item, f"{path}[{index}]"))
    return paths


def expand_spec(spec: str) -> list[str]:
    """rqt_plot's shorthand: ``/turtle1/pose/x:y:theta`` is ``/turtle1/pose/x``, ``…/y`` and ``…/theta``."""
    first, *more = spec.split(":")
    base = first.rsplit("/", 1)[0]
    return [first] + [f"{base}/{name}" for name in more if name]


def split_spec(spec: str, topics: Iterable[str]) -> tuple[str, str] | None:
    """``(topic, field path)`` for ``spec`` (``/turtle1/pose/x``), the topic being the longest of ``topics`` it starts with.

    None when no topic in ``topics`` is a proper prefix of ``spec`` (a spec that is itself a topic is none).
    """
    spec = "/" + spec.strip("/")
    best = ""
    for topic in topics:
        if spec.startswith(topic.rstrip("/") + "/") and len(topic) > len(best):
            best = topic
    if not best:
        return None
    return best, normal_path(spec[len(best.rstrip("/")):])


def nice_ticks(low: float, high: float, most: int = 5) -> list[float]:
    """At most ``most`` (>= 2) round values, 1, 2 or 5 times a power of ten apart, from below ``low`` to above ``high``."""
    if not (math.isfinite(low) and math.isfinite(high)):
        raise ValueError("ticks need finite bounds")
    if high < low:
        low, high = high, low
    if high == low:
        low, high = low - (abs(low) * 0.1 or 1.0), high + (abs(high) * 0.1 or 1.0)
    most = max(2, most)
    raw = (high - low) / (most - 1)
    power = 10.0 ** math.floor(math.log10(raw))
    for factor in (1.0, 2.0, 5.0, 10.0, 20.0):
        step = factor * power
        first, last = math.floor(low / step), math.ceil(high / step)
        if last - first + 1 <= most:
            break
    return [round(k * step, 12) for k in range(first, last + 1)]


def thin(times: Sequence[float], values: Sequence[float], start: float, end: float,
         buckets: int) -> tuple[list[float], list[float]]:
    """At most two points per ``buckets`` equal slices of ``start`` … ``end``: each slice's lowest and highest.

    A line drawn through them has the same envelope as one through every
    point when a slice is no wider than a plot's dot, at a fraction of the cost.
    """
    if buckets < 1 or len(times) <= 2 * buckets or end <= start:
        return list(times), list(values)
    width = (end - start) / buckets
    kept_t: list[float] = []
    kept_v: list[float] = []
    current = -1
    low = high = 0

    def flush() -> None:
        for index in sorted({low, high}):
            kept_t.append(times[index])
            kept_v.append(values[index])

    for index, when in enumerate(times):
        bucket = min(buckets - 1, max(0, int((when - start) / width)))
        if bucket != current:
            if current >= 0:
                flush()
            current, low, high = bucket, index, index
        elif values[index] < values[low]:
            low = index
        elif values[index] > values[high]:
            high = index
    if current >= 0:
        flush()
    return kept_t, kept_v


@dataclass
class Series:
    """One plotted field: ``topic`` and ``path``, its last points, how many came, and why the last one did not."""

    topic: str
    path: str
    times: deque[float] = field(default_factory=lambda: deque(maxlen=CAPACITY))
    values: deque[float] = field(default_factory=lambda: deque(maxlen=CAPACITY))
    count: int = 0
    error: str = ""

    @property
    def name(self) -> str:
        """``/turtle1/pose/x``: as rqt_plot names it."""
        return f"{self.topic}/{self.path}"

    def add(self, when: float, msg: Any) -> None:
        """Take the field's value from ``msg`` received at ``when`` (or remember why there is none)."""
        try:
            value = check_numeric(msg, self.topic, self.path)
        except PlotFieldError as exc:
            self.error = str(exc)
            return
        self.error = ""
        self.times.append(when)
        self.values.append(value)
        self.count += 1
        horizon = when - WINDOWS[-1]
        while self.times and self.times[0] < horizon:
            self.times.popleft()
            self.values.popleft()

    def between(self, start: float, end: float) -> tuple[list[float], list[float]]:
        """The points with ``start <= time <= end``: their times and values."""
        times: list[float] = []
        values: list[float] = []
        for when, value in zip(self.times, self.values):
            if start <= when <= end:
                times.append(when)
                values.append(value)
        return times, values


@dataclass(frozen=True)
class SeriesView:
    """What the plot shows of one series: times relative to the window's end (so -10 … 0) and values."""

    name: str
    times: tuple[float, ...]
    values: tuple[float, ...]
    error: str

    @property
    def last(self) -> float | None:
        """The newest value shown."""
        return self.values[-1] if self.values else None


class PlotModel:
    """The fields plotted together, the time window and pause; fed with :meth:`add_message`."""

    def __init__(self, window: float = DEFAULT_WINDOW) -> None:
        self.series: list[Series] = []
        self.window = window
        self.paused_at: float | None = None
        self._counts_at_pause = 0

    # -- fields --------------------------------------------------------------------------
    @property
    def topics(self) -> set[str]:
        """The topics whose messages the plot wants."""
        return {s.topic for s in self.series}

    def find(self, topic: str, path: str) -> Series | None:
        """The series of ``topic``'s field ``path``."""
        path = normal_path(path)
        return next((s for s in self.series if s.topic == topic and s.path == path), None)

    def add_field(self, topic: str, path: str, msg: Any = None) -> Series:
        """Plot ``topic``'s field ``path`` too; with a message at hand, refuse a field that is no number.

        Raises :class:`PlotFieldError` (nothing added) when ``msg`` has no number at ``path``.
        """
        path = normal_path(path)
        if msg is not None:
            check_numeric(msg, topic, path)
        elif not path:
            raise PlotFieldError(f"{topic} is a topic: name one of its numeric fields, as {topic}/x")
        have = self.find(topic, path)
        if have is not None:
            return have
        series = Series(topic, path)
        self.series.append(series)
        return series

    def remove_field(self, topic: str, path: str) -> bool:
        """Stop plotting ``topic``'s field ``path``; False when it was not plotted."""
        series = self.find(topic, path)
        if series is None:
            return False
        self.series.remove(series)
        return True

    # -- data ----------------------------------------------------------------------------
    def add_message(self, topic: str, when: float, msg: Any) -> None:
        """A message of ``topic`` arrived at ``when``: every series of that topic takes its value."""
        for series in self.series:
            if series.topic == topic:
                series.add(when, msg)

    def note_error(self, topic: str, text: str) -> None:
        """A message of ``topic`` could not be read (``text`` says why)."""
        for series in self.series:
            if series.topic == topic:
                series.error = text

    @property
    def count(self) -> int:
        """Points received for all series so far."""
        return sum(s.count for s in self.series)

    # -- window and pause ----------------------------------------------------------------
    def longer(self) -> float:
        """The next longer window (the longest stays); returns it."""
        self.window = next((w for w in WINDOWS if w > self.window), WINDOWS[-1])
        return self.window

    def shorter(self) -> float:
        """The next shorter window (the shortest stays); returns it."""
        self.window = next((w for w in reversed(WINDOWS) if w < self.window), WINDOWS[0])
        return self.window

    @property
    def paused(self) -> bool:
        """Whether the picture stands still."""
        return self.paused_at is not None

    def pause(self, now: float) -> None:
        """Freeze the shown window at ``now``; points keep being received and counted."""
        if self.paused_at is None:
            self.paused_at = now
            self._counts_at_pause = self.count

    def resume(self) -> None:
        """Follow the newest points again."""
        self.paused_at = None

    def toggle_pause(self, now: float) -> bool:
        """Pause, or resume when paused; returns whether it is paused now."""
        if self.paused:
            self.resume()
        else:
            self.pause(now)
        return self.paused

    @property
    def since_pause(self) -> int:
        """Points received while paused (0 when running)."""
        return self.count - self._counts_at_pause if self.paused else 0

    def end(self, now: float) -> float:
        """Where the shown window ends: ``now``, or the moment of the pause."""
        return self.paused_at if self.paused_at is not None else now

    def view(self, now: float, buckets: int = 0) -> list[SeriesView]:
        """Every series' points in the window ending at :meth:`end`, times relative to that end.

        With ``buckets``, at most the lowest and highest point of each of that many time slices (see :func:`thin`).
        """
        end = self.end(now)
        views = []
        for series in self.series:
            times, values = series.between(end - self.window, end)
            times, values = thin(times, values, end - self.window, end, buckets)
            views.append(SeriesView(series.name, tuple(t - end for t in times), tuple(values), series.error))
        return views

    @staticmethod
    def value_range(views: Sequence[SeriesView]) -> tuple[float, float] | None:
        """The smallest and largest value shown, over every series (None when nothing is shown)."""
        values = [v for view in views for v in view.values]
        return (min(values), max(values)) if values else None
