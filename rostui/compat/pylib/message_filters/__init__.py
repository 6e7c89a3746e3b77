"""message_filters for unmodified ROS 1 scripts: chains of filters over rospy subscribers.

``Subscriber`` feeds messages of a topic into the chain; ``Cache`` keeps the last N by stamp;
``TimeSynchronizer`` calls back with one message from each input when all have the same
``header.stamp``; ``ApproximateTimeSynchronizer`` when their stamps are within ``slop`` seconds. A filter's
callbacks get its messages followed by the extra arguments given at registration. Under simulated time
with ``reset=True`` a synchronizer forgets an input's queue when time jumps back.
"""

from __future__ import annotations

import functools
import itertools
import threading
from typing import Any, Callable, Sequence

import rospy

__all__ = ["ApproximateTimeSynchronizer", "Cache", "SimpleFilter", "Subscriber", "TimeSynchronizer"]

_NO_STAMP = ("Cannot use message filters with non-stamped messages. Use the 'allow_headerless' constructor option "
             "to auto-assign ROS time to headerless messages.")


def _stamp_of(msg: Any, allow_headerless: bool) -> Any:
    """``msg.header.stamp``; for a message without one, now (if allowed) or None after a warning."""
    header = getattr(msg, "header", None)
    if header is not None and hasattr(header, "stamp"):
        return header.stamp
    if not allow_headerless:
        rospy.logwarn(_NO_STAMP)
        return None
    return rospy.Time.now()


class SimpleFilter:
    """A filter: callbacks registered on it are called with what it lets through."""

    def __init__(self) -> None:
        self.callbacks: dict[int, tuple[Callable[..., Any], tuple[Any, ...]]] = {}

    def registerCallback(self, cb: Callable[..., Any], *args: Any) -> int:  # noqa: N802 (ROS's name)
        """Call ``cb(*messages, *args)`` on output; returns the connection's number."""
        conn = len(self.callbacks)
        self.callbacks[conn] = (cb, args)
        return conn

    def signalMessage(self, *msg: Any) -> None:  # noqa: N802 (ROS's name)
        """Pass ``msg`` to every callback."""
        for cb, args in list(self.callbacks.values()):
            cb(*(msg + args))


class Subscriber(SimpleFilter):
    """A rospy subscription as the head of a chain: the same arguments as ``rospy.Subscriber``."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        SimpleFilter.__init__(self)
        self.topic = args[0]
        kwargs["callback"] = self.callback
        self.sub = rospy.Subscriber(*args, **kwargs)

    def callback(self, msg: Any) -> None:
        """Pass a received message on."""
        self.signalMessage(msg)

    def getTopic(self) -> str:  # noqa: N802 (ROS's name)
        """The topic name as given."""
        return str(self.topic)

    def __getattr__(self, key: str) -> Any:
        if key == "sub":
            raise AttributeError(key)
        return getattr(self.sub, key)


class Cache(SimpleFilter):
    """The last ``cache_size`` messages of its input, with their stamps, in arrival order."""

    def __init__(self, f: SimpleFilter, cache_size: int = 1, allow_headerless: bool = False) -> None:
        SimpleFilter.__init__(self)
        self.connectInput(f)
        self.cache_size = cache_size
        self.cache_msgs: list[Any] = []
        self.cache_times: list[Any] = []
        self.allow_headerless = allow_headerless

    def connectInput(self, f: SimpleFilter) -> None:  # noqa: N802 (ROS's name)
        """Take messages from ``f``."""
        self.incoming_connection = f.registerCallback(self.add)

    def add(self, msg: Any) -> None:
        """Keep ``msg`` (the oldest goes past ``cache_size``) and pass it on."""
        stamp = _stamp_of(msg, self.allow_headerless)
        if stamp is None:
            return
        self.cache_times.append(stamp)
        self.cache_msgs.append(msg)
        if len(self.cache_msgs) > self.cache_size:
            del self.cache_msgs[0]
            del self.cache_times[0]
        self.signalMessage(msg)

    def getInterval(self, from_stamp: Any, to_stamp: Any) -> list[Any]:  # noqa: N802 (ROS's names, here on)
        """The messages stamped from ``from_stamp`` to ``to_stamp``, both included."""
        assert from_stamp <= to_stamp
        return [m for m, t in zip(self.cache_msgs, self.cache_times) if from_stamp <= t <= to_stamp]

    def getElemAfterTime(self, stamp: Any) -> Any:  # noqa: N802
        """The first message stamped at or after ``stamp``, or None."""
        return next((m for m, t in zip(self.cache_msgs, self.cache_times) if t >= stamp), None)

    def getElemBeforeTime(self, stamp: Any) -> Any:  # noqa: N802
        """The last message stamped at or before ``stamp``, or None."""
        older = [m for m, t in zip(self.cache_msgs, self.cache_times) if t <= stamp]
        return older[-1] if older else None

    def getLatestTime(self) -> Any:  # noqa: N802
        """The newest message's stamp, or None."""
        return self.cache_times[-1] if self.cache_times else None

    def getLastestTime(self) -> Any:  # noqa: N802 (the misspelling message_filters keeps for old scripts)
        """:meth:`getLatestTime`."""
        return self.getLatestTime()

    def getOldestTime(self) -> Any:  # noqa: N802
        """The oldest message's stamp, or None."""
        return self.cache_times[0] if self.cache_times else None

    def getLast(self) -> Any:  # noqa: N802
        """The newest message, or None."""
        latest = self.getLatestTime()
        return None if latest is None else self.getElemAfterTime(latest)


class TimeSynchronizer(SimpleFilter):
    """One callback per set of messages, one from each input, with exactly the same stamp."""

    def __init__(self, fs: Sequence[SimpleFilter], queue_size: int, reset: bool = False) -> None:
        SimpleFilter.__init__(self)
        self.connectInput(fs)
        self.queue_size = queue_size
        self.lock = threading.Lock()
        self.enable_reset = reset

    def connectInput(self, fs: Sequence[SimpleFilter]) -> None:  # noqa: N802 (ROS's name)
        """Take messages from each filter of ``fs``, one queue (stamp: message) each."""
        self.queues: list[dict[Any, Any]] = [{} for _ in fs]
        self.latest_stamps = [rospy.Time(0) for _ in fs]
        self.input_connections = [f.registerCallback(self.add, q, i) for i, (f, q) in enumerate(zip(fs, self.queues))]

    def _note_time(self, my_queue: dict[Any, Any], index: int | None) -> tuple[bool, Any]:
        """Forget ``my_queue`` if simulated time went back for it; (sim time with reset on, now)."""
        now = rospy.Time.now()
        resetting = self.enable_reset and not rospy.rostime.is_wallclock()
        if resetting and index is not None:
            if now < self.latest_stamps[index]:
                rospy.logdebug("Detected jump back in time. Clearing message filter queue")
                my_queue.clear()
            self.latest_stamps[index] = now
        return resetting, now

    def _trim(self, my_queue: dict[Any, Any]) -> None:
        while len(my_queue) > self.queue_size:
            del my_queue[min(my_queue)]

    def add(self, msg: Any, my_queue: dict[Any, Any], my_queue_index: int | None = None) -> None:
        """Queue ``msg`` by its stamp; signal every stamp now present in all queues, oldest first."""
        with self.lock:
            resetting, now = self._note_time(my_queue, my_queue_index)
            my_queue[msg.header.stamp] = msg
            self._trim(my_queue)
            if resetting and max(self.latest_stamps) != now:
                return
            common = functools.reduce(set.intersection, [set(q) for q in self.queues])
            for stamp in sorted(common):
                self.signalMessage(*[q[stamp] for q in self.queues])
                for q in self.queues:
                    del q[stamp]


class ApproximateTimeSynchronizer(TimeSynchronizer):
    """One callback per set of messages whose stamps lie within ``slop`` seconds of each other.

    Each new message is matched with the others' queued messages within ``slop`` of it, nearest first;
    the first combination spanning less than ``slop`` is signalled and taken out of the queues. ROS time
    going backwards clears every queue.
    """

    def __init__(self, fs: Sequence[SimpleFilter], queue_size: int, slop: float, allow_headerless: bool = False,
                 reset: bool = False) -> None:
        TimeSynchronizer.__init__(self, fs, queue_size)
        self.slop = rospy.Duration.from_sec(slop)
        self.allow_headerless = allow_headerless
        self.last_added = rospy.Time()
        self.enable_reset = reset

    def add(self, msg: Any, my_queue: dict[Any, Any], my_queue_index: int | None = None) -> None:
        """Queue ``msg`` and signal the first set within the slop that it completes."""
        stamp = _stamp_of(msg, self.allow_headerless)
        if stamp is None:
            return
        with self.lock:
            resetting, now = self._note_time(my_queue, my_queue_index)
            my_queue[stamp] = msg
            now = rospy.Time.now()
            if now < self.last_added:
                rospy.loginfo("ApproximateTimeSynchronizer: Detected jump back in time. Clearing buffer.")
                for q in self.queues:
                    q.clear()
            self.last_added = now
            self._trim(my_queue)
            if resetting and max(self.latest_stamps) != now:
                return
            others = self.queues if my_queue_index is None else (
                self.queues[:my_queue_index] + self.queues[my_queue_index + 1:])
            candidates: list[list[Any]] = []
            for queue in others:
                near = sorted(((s, abs(s - stamp)) for s in queue if not abs(s - stamp) > self.slop),
                              key=lambda pair: pair[1])
                if not near:
                    return
                candidates.append([s for s, _ in near])
            for combination in itertools.product(*candidates):
                stamps = list(combination)
                if my_queue_index is not None:
                    stamps.insert(my_queue_index, stamp)
                pairs = list(zip(self.queues, stamps))
                if max(stamps) - min(stamps) < self.slop and all(t in q for q, t in pairs):
                    self.signalMessage(*[q[t] for q, t in pairs])
                    for q, t in pairs:
                        del q[t]
                    break
