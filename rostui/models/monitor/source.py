"""MonitorSource: the master's topics, and subscriptions to exactly the topics the monitor shows.

One anonymous node ``/rostui_monitor_<pid>_<ms>``, kept registered by a
:class:`~rostui.models.master_link.MasterLink`, runs on the caller's event
loop.  Every ``period`` seconds it asks the master for ``getSystemState``
and ``getTopicTypes``; whenever the wanted set changes (the app says which
topics are on screen or expanded) it subscribes to the new ones with md5
``*`` (no decoding: arrivals and sizes are all the table needs) and
unsubscribes from those no longer wanted.  A publisher whose connection
header gives no class (a definition that does not hash to its md5sum,
another version of a type rostui knows) is refused, its connection dropped
and the reason kept for the topic (:meth:`MonitorSource.refusals`); the
topic's other publishers are heard as before.  Messages are decoded only for a
tree or for the fields the :class:`~rostui.models.monitor.plot.PlotModel`
plots.  When the master stops answering (or another one
answers) the link drops the node and registers again once a master answers.
"""

from __future__ import annotations

import asyncio
import time
from dataclasses import dataclass
from typing import Any, Callable, Iterable

from rostui.core.msg import MessageError
from rostui.core.node import AnyMsg, AsyncNode, Publisher, Subscriber
from rostui.core.node.header_check import RefusalLog, decodable
from rostui.core.xmlrpc import XmlRpcProtocolError
from rostui.models.master_link import CALL_TIMEOUT, LinkedSource, MasterLink, SourceState, failure_reason
from rostui.models.monitor.rows import Liveness, TopicRow
from rostui.models.monitor.stats import TopicStats
from rostui.models.monitor.plot import PlotModel, Series

__all__ = ["MonitorSource", "TopicInfo", "NODE_NAME", "topics_from_wire"]

#: The monitor's node name (made anonymous).
NODE_NAME = "rostui_monitor"


@dataclass(frozen=True)
class TopicInfo:
    """What the master says about one topic."""

    name: str
    type: str
    publishers: tuple[str, ...]
    subscribers: tuple[str, ...]


class _Watch:
    """One subscription: its handle, statistics and the newest raw message."""

    __slots__ = ("handle", "stats", "latest", "arrived", "decoded", "decoded_from", "refused")

    def __init__(self) -> None:
        self.handle: Subscriber | None = None
        self.refused = RefusalLog(decodable)
        self.stats = TopicStats()
        self.latest: AnyMsg | None = None
        self.arrived = 0.0
        self.decoded: Any = None
        self.decoded_from: Any = None


class MonitorSource(LinkedSource):
    """The master at ``master_uri`` as the monitor sees it; call :meth:`run` as a task, :meth:`stop` to end.

    ``clock`` (wall time in seconds) stamps arrivals and is "now" for ages
    and rates; tests pass one they step themselves.
    """

    def __init__(self, master_uri: str, *, period: float = 1.0,
                 on_state: Callable[[SourceState], None] | None = None,
                 on_topics: Callable[[], None] | None = None,
                 clock: Callable[[], float] = time.time) -> None:
        self.master_uri = master_uri
        self.period = period
        self.clock = clock
        self.on_topics = on_topics or (lambda: None)
        self.topics: dict[str, TopicInfo] = {}
        self.polls = 0
        self.plot = PlotModel()
        self.publishers: dict[str, Publisher] = {}
        self._wanted: frozenset[str] = frozenset()
        self._watches: dict[str, _Watch] = {}
        self._wake = asyncio.Event()
        self._lock = asyncio.Lock()
        self.link = MasterLink(NODE_NAME, master_uri, on_connect=self._poll, session=self._serve,
                               on_drop=self._forget, on_state=on_state, check_period=period)

    # -- what the app asks for -------------------------------------------------------
    @property
    def subscribed(self) -> frozenset[str]:
        """Topics subscribed right now."""
        return frozenset(self._watches)

    def want(self, topics: Iterable[str]) -> None:
        """Subscribe to exactly ``topics`` (those with publishers), soon; unsubscribe from the rest."""
        wanted = frozenset(topics)
        if wanted != self._wanted:
            self._wanted = wanted
            self._wake.set()

    def stats(self, topic: str) -> TopicStats | None:
        """The statistics of a subscribed topic."""
        watch = self._watches.get(topic)
        return watch.stats if watch is not None else None

    def refusals(self, topic: str) -> list[str]:
        """Why publishers of a subscribed topic were refused (one line each, oldest first; empty when none was)."""
        watch = self._watches.get(topic)
        return list(watch.refused.lines) if watch is not None else []

    def latest(self, topic: str) -> Any:
        """The newest message of a subscribed topic, decoded (None before one came)."""
        from rostui.tools.topic.echo import decode

        watch = self._watches.get(topic)
        if watch is None or watch.latest is None:
            return None
        raw = watch.latest
        if watch.decoded_from is not raw:  # a latched or slow topic is decoded once per message, not per repaint
            watch.decoded = decode(raw)
            watch.decoded_from = raw
        return watch.decoded

    def plot_field(self, topic: str, path: str) -> Series:
        """Plot ``topic``'s field ``path`` too, from its newest message on.

        Raises :class:`~rostui.models.monitor.plot.PlotFieldError` (nothing
        plotted) when the newest message of ``topic`` has no number there.
        """
        watch = self._watches.get(topic)
        msg = self.latest(topic)
        series = self.plot.add_field(topic, path, msg)
        if msg is not None and watch is not None and not series.count:
            series.add(watch.arrived, msg)
        return series

    def sample(self, now: float | None = None) -> None:
        """Compute every subscribed topic's rate and bandwidth (once a second: the sparklines' step)."""
        now = self.clock() if now is None else now
        for watch in self._watches.values():
            watch.stats.sample(now)

    def rows(self, now: float | None = None) -> list[TopicRow]:
        """Every topic the master knows (and every subscribed one) as a table row, in name order."""
        now = self.clock() if now is None else now
        me = self.node.name if self.node is not None else None
        rows = []
        names = set(self.topics) | set(self._watches)
        for name in sorted(names):
            info = self.topics.get(name) or TopicInfo(name, "unknown type", (), ())
            subs = tuple(s for s in info.subscribers if s != me)
            pubs = info.publishers
            watch = self._watches.get(name)
            if watch is None:
                rows.append(TopicRow(name, info.type, pubs, subs,
                                     liveness=Liveness.OFF if pubs else Liveness.NO_PUBLISHERS))
                continue
            st = watch.stats
            liveness = self._liveness(watch, pubs, now)
            if liveness is Liveness.STALE:  # the figures of messages that stopped coming are not a rate
                rows.append(TopicRow(name, info.type, pubs, subs, None, None, st.age(now), liveness))
            else:
                rows.append(TopicRow(name, info.type, pubs, subs, st.rate, st.bandwidth, st.age(now), liveness))
        return rows

    def _liveness(self, watch: _Watch, publishers: tuple[str, ...], now: float) -> Liveness:
        st = watch.stats
        connected = watch.handle.get_num_connections() if watch.handle is not None else 0
        if st.messages == 0:
            return Liveness.WAITING if publishers else Liveness.NO_PUBLISHERS
        if connected == 0 or st.stale_at(now):
            return Liveness.STALE
        return Liveness.LIVE

    def history(self, topic: str) -> tuple[list[float], list[float]]:
        """The last :data:`~rostui.models.monitor.stats.HISTORY` rate and bandwidth samples of ``topic`` (empty when not subscribed)."""
        watch = self._watches.get(topic)
        if watch is None:
            return [], []
        return list(watch.stats.rate_history), list(watch.stats.bw_history)

    # -- publishing ------------------------------------------------------------------
    async def publish(self, topic: str, cls: Any, msg: Any, *, latch: bool) -> None:
        """Publish ``msg`` on ``topic`` from the monitor's node (advertising it first, kept until the end)."""
        node = self.node
        if node is None:
            raise RuntimeError(f"no master at {self.master_uri}")
        pub = self.publishers.get(topic)
        if pub is not None and (pub.msg_class._md5sum != cls._md5sum or pub.impl.latch != latch):
            await pub.unregister()
            pub = None
        if pub is None:
            pub = await node.advertise(topic, cls, queue_size=100, latch=latch)
            self.publishers[topic] = pub
        pub.publish(msg)

    # -- the loop --------------------------------------------------------------------
    async def run(self) -> None:
        """Connect, poll the master, keep the subscriptions as wanted; reconnect after a master loss."""
        await self.link.run()

    async def _serve(self, node: AsyncNode) -> None:
        """While registered: keep the subscriptions as wanted, poll the master every ``period``."""
        next_poll = time.monotonic() + self.period
        while True:
            await self._apply_wanted(node)
            await self._sleep(max(0.0, next_poll - time.monotonic()))
            if time.monotonic() >= next_poll:
                await self._poll(node)
                next_poll = time.monotonic() + self.period

    async def _sleep(self, seconds: float) -> None:
        try:
            await asyncio.wait_for(self._wake.wait(), seconds)
        except asyncio.TimeoutError:
            pass
        self._wake.clear()

    async def _poll(self, node: AsyncNode) -> None:
        state = await asyncio.wait_for(node.master_call("getSystemState"), CALL_TIMEOUT)
        types = await asyncio.wait_for(node.master_call("getTopicTypes"), CALL_TIMEOUT)
        try:
            self.topics = topics_from_wire(state, types)
        except (TypeError, ValueError) as exc:
            raise XmlRpcProtocolError(node.master_uri, f"malformed system state: {exc}") from None
        self.polls += 1
        self.on_topics()

    async def _apply_wanted(self, node: AsyncNode) -> None:
        """Subscribe to wanted topics that have publishers; unsubscribe from the unwanted ones."""
        async with self._lock:
            for name in [t for t in self._watches if t not in self._wanted]:
                handle = self._watches.pop(name).handle
                if handle is not None:
                    await handle.unregister()
            for name in sorted(self._wanted):
                info = self.topics.get(name)
                if name in self._watches or info is None or not info.publishers:
                    continue
                watch = _Watch()
                self._watches[name] = watch
                watch.handle = await node.subscribe(name, AnyMsg, self._receiver(name, watch), check=watch.refused)

    def _receiver(self, topic: str, watch: _Watch) -> Callable[[Any], None]:
        add = watch.stats.add
        clock = self.clock

        def on_message(raw: Any) -> None:
            now = clock()
            add(now, len(raw._buff))
            watch.latest = raw
            watch.arrived = now
            plot = self.plot
            if topic in plot.topics:
                try:
                    plot.add_message(topic, now, self.latest(topic))
                except MessageError as exc:  # an undecodable message is a note on the plot, not a crash
                    plot.note_error(topic, f"cannot decode: {failure_reason(exc)}")

        return on_message

    def _forget(self) -> None:
        """The node is being dropped: its subscriptions and publishers go with it."""
        self._watches.clear()
        self.publishers.clear()

    async def stop(self) -> None:
        """Unsubscribe, unadvertise and shut the node down."""
        await self.link.stop()


def topics_from_wire(state: Any, types: Any) -> dict[str, TopicInfo]:
    """Every topic with a publisher or subscriber, from getSystemState's and getTopicTypes' answers.

    TypeError or ValueError when they are not shaped as a master answers.
    """
    pubs, subs, _ = state
    known = dict(types)
    publishers: dict[str, tuple[str, ...]] = {t: tuple(n) for t, n in pubs}
    subscribers: dict[str, tuple[str, ...]] = {t: tuple(n) for t, n in subs}
    return {name: TopicInfo(name, known.get(name, "unknown type"), publishers.get(name, ()), subscribers.get(name, ()))
            for name in set(publishers) | set(subscribers)}

