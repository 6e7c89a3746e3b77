"""A bag transport: publishes time-ordered messages with their recorded spacing, under control.

One scheduler serves ``rostui bag play`` and ``rostui bag view``: play, pause,
step (exactly one message per step), seek (to a bag time or a fraction of the
bag), rate change, loop and per-topic enable. It knows nothing of nodes or
screens: messages come from a :class:`MessageSource` and leave through the
``publish`` callback; ``on_tick`` is called while it waits (for ``/clock`` and
status lines).

Timing: a *bag clock* runs at ``rate`` from an anchor ``(wall, bag time)``.
Pausing freezes it, resuming re-anchors it where it stopped (so the wait left
before the next message is kept), a rate change re-anchors it at its current
value, a seek re-anchors it at the target. A message is published when the bag
clock reaches its time: the loop sleeps on asyncio until the last few
milliseconds (asyncio timers are millisecond-grained), then sleeps without the
loop, with the timer slack lowered and no spin
(:func:`~rostui.core.bag.precise_sleep.sleep_until`).
"""

from __future__ import annotations

import asyncio
import collections
import itertools
import time
from collections.abc import Callable, Iterator
from typing import Any, Protocol

from rostui.core.bag.model import Connection
from rostui.core.bag.precise_sleep import lower_timer_slack, sleep_until

#: ``(connection, time_ns, bytes)``: one recorded message; the transport hands its bytes to ``publish`` unlooked-at
#: (bag view's: the payload; a player's: the frame, in memory or where it lies in the file).
MessageItem = tuple[Connection, int, Any]
#: ``(connection, wanted, sender)``: whether a connection's messages are published and its own sender (None:
#: the transport's ``publish``).
_Route = tuple[Connection, bool, "Callable[[Any], None] | None"]

SPIN_BEFORE = 0.003  # the last moments before a message are slept without the loop (its timers are ms-grained)
LOOP_TURN_PERIOD = 0.02
"""The longest the transport publishes messages due close together without giving the event loop a turn (s), by
default: keys, signals, new subscribers, slow sockets and a screen (bag view's) wait at most this long, and a turn
is not paid per message.  A player without a screen takes longer (``turn_period``)."""
TICK_PERIOD = 0.1
READ_AHEAD = 64
"""Messages a :class:`StreamSource` reads at a time."""
SKIP_BATCH = 1000  # messages skipped (disabled topics) between two turns of the loop


async def _turn() -> None:
    """Give the event loop a turn: what it finds ready (sends, connections, signals, keys, timers) runs before this
    returns.  One yield would only let the loop look: what it found runs after the caller's next step."""
    await asyncio.sleep(0)
    await asyncio.sleep(0)


class MessageSource(Protocol):
    """Messages in time order with a read position that can be moved."""

    def peek(self) -> MessageItem | None:
        """The message at the read position, or None at the end."""
        ...

    def advance(self) -> None:
        """Move past the message at the read position."""
        ...

    def seek(self, t_ns: int) -> None:
        """Move the read position to the first message whose time is ``t_ns`` or later."""
        ...


class StreamSource:
    """Messages from a stream that can only be read forwards (files read in order).

    ``open_stream`` starts a new pass over the messages; seeking backwards
    starts a new pass and skips to the target. Messages are read
    :data:`READ_AHEAD` at a time: a player sleeps before each message, and the
    stream's code, run once between two sleeps, ran with cold caches every time
    (bench/README.md, "Bag play CPU", sixth pass).
    An error of the stream is raised where it stands, after the messages
    before it.
    """

    def __init__(self, open_stream: Callable[[], Iterator[MessageItem]]) -> None:
        self._open = open_stream
        self._stream: Iterator[MessageItem] | None = None
        self._ahead: collections.deque[MessageItem] = collections.deque()
        self._error: BaseException | None = None
        self._last_ns: int | None = None  # time of the last message moved past

    def _start(self) -> None:
        self._stream = self._open()
        self._ahead.clear()
        self._error = None
        self._last_ns = None
        self._read_ahead()

    def _read_ahead(self) -> None:
        """Read up to READ_AHEAD more messages; an error is kept for when the messages before it are used, and
        ends the stream."""
        if self._stream is None:
            return
        try:
            self._ahead.extend(itertools.islice(self._stream, READ_AHEAD))
        except Exception as exc:  # noqa: BLE001 - raised again in its place (peek)
            self._error = exc
            self._stream = iter(())

    def peek(self) -> MessageItem | None:
        """The message at the read position, or None at the end."""
        if self._ahead:
            return self._ahead[0]
        if self._stream is None:
            self._start()
        else:
            self._read_ahead()
        if self._ahead:
            return self._ahead[0]
        if self._error is not None:
            error, self._error = self._error, None
            raise error  # once, as the stream itself raised it; it has ended
        return None

    def advance(self) -> None:
        """Move past the message at the read position."""
        if self._ahead or self.peek() is not None:
            self._last_ns = self._ahead.popleft()[1]

    def seek(self, t_ns: int) -> None:
        """Move to the first message at ``t_ns`` or later (a new pass when that lies behind)."""
        if self._stream is None or (self._last_ns is not None and self._last_ns >= t_ns):
            self._start()
        while True:
            head = self.peek()
            if head is None or head[1] >= t_ns:
                return
            self.advance()


class Transport:
    """Plays a :class:`MessageSource` between ``start_ns`` and ``end_ns`` through ``publish``.

    ``accepts(conn)`` says whether a connection can be published at all (a
    publisher exists); topics can further be switched off and on while
    playing. ``play_from``/``play_until`` bound what one pass plays (``-s``,
    ``-u``); ``hold_at_end`` keeps :meth:`run` alive, paused, at the end
    instead of returning (the app). ``turn_period`` is the longest the event
    loop goes without a turn while messages are due close together
    (:data:`LOOP_TURN_PERIOD`). ``clock`` is the wall clock in seconds.
    ``sender_for(conn)`` may give a connection's own sender, called with a
    message's bytes alone in place of ``publish`` (None: ``publish``): a
    player without a per-message hook sends straight to the publication.
    """

    def __init__(self, source: MessageSource, publish: Callable[[Connection, int, bytes], None], *,
                 start_ns: int, end_ns: int, rate: float = 1.0, loop: bool = False, paused: bool = False,
                 play_from: int | None = None, play_until: int | None = None, hold_at_end: bool = False,
                 accepts: Callable[[Connection], bool] | None = None,
                 on_tick: Callable[[int], None] | None = None, tick_period: float = TICK_PERIOD,
                 turn_period: float = LOOP_TURN_PERIOD, clock: Callable[[], float] = time.perf_counter,
                 sender_for: Callable[[Connection], Callable[[Any], None] | None] | None = None) -> None:
        if not rate > 0:
            raise ValueError("the rate must be greater than 0")
        self.source = source
        self.publish = publish
        self.start_ns = start_ns
        self.end_ns = max(end_ns, start_ns)
        self.play_from = start_ns if play_from is None else play_from
        self.play_until = play_until
        self.rate = rate
        self.loop = loop
        self.paused = paused
        self.hold_at_end = hold_at_end
        self.accepts = accepts
        self.on_tick = on_tick
        self.tick_period = tick_period
        self.turn_period = turn_period
        self.clock = clock
        self.sender_for = sender_for
        self.disabled: set[str] = set()
        # id(connection): the connection's _route, until a control call (the id alone could be a later
        # connection's, once a reader lets its first go)
        self._routes: dict[int, _Route] = {}
        self.published = 0
        self.lateness: list[float] = []
        self.last_ns: int | None = None  # time of the last message published
        self.stopped = False
        self._steps = 0
        self._gen = 0  # bumped by every control call that moves the schedule
        self._wake = asyncio.Event()
        self._anchor_wall = 0.0
        self._anchor_bag = self.play_from
        self._anchor_next = True  # anchor the bag clock at the next message (start, loop)
        self._frozen_ns = self.play_from
        self._started = False
        self._positioned = False  # run() starts at play_from unless seek() came first
        self._pass_published = 0

    # -- the bag clock -------------------------------------------------------------------
    @property
    def end_bound(self) -> int:
        """Where one pass ends: ``play_until`` or the end of the bag."""
        return self.end_ns if self.play_until is None else min(self.play_until, self.end_ns)

    def bag_ns(self) -> int:
        """The bag clock now: frozen while paused, running at ``rate`` while playing."""
        if self.paused or self._anchor_next or not self._started:
            return self._frozen_ns
        now = self._anchor_bag + int((self.clock() - self._anchor_wall) * self.rate * 1e9)
        return max(self.start_ns, min(now, self.end_ns))

    def fraction(self) -> float:
        """Where the bag clock stands between start and end, 0..1."""
        span = self.end_ns - self.start_ns
        return 0.0 if span <= 0 else (self.bag_ns() - self.start_ns) / span

    def _wall_of(self, t_ns: int) -> float:
        return self._anchor_wall + (t_ns - self._anchor_bag) / 1e9 / self.rate

    def _anchor(self, bag_ns: int) -> None:
        self._anchor_wall = self.clock()
        self._anchor_bag = bag_ns
        self._anchor_next = False

    def _changed(self) -> None:
        self._gen += 1
        self._routes.clear()
        self._wake.set()

    # -- control (call from the loop the transport runs on) -----------------------------------
    @property
    def at_end(self) -> bool:
        """True when nothing is left to play in this pass."""
        return self._pass_head() is None

    def pause(self) -> None:
        """Stop the bag clock where it is."""
        if not self.paused:
            self._frozen_ns = self.bag_ns()
            self.paused = True
            self._changed()

    def resume(self) -> None:
        """Run the bag clock on from where it stopped (from the start when at the end)."""
        if not self.paused:
            return
        if self.hold_at_end and self.at_end:
            self._seek_to(self.play_from)
        self.paused = False
        if not self._anchor_next:  # (never moved since the start: the first message goes at once)
            self._anchor(self._frozen_ns)
        self._changed()

    def toggle_pause(self) -> None:
        """Pause or resume."""
        if self.paused:
            self.resume()
        else:
            self.pause()

    def step(self) -> bool:
        """While paused: publish the next message (one per call); False when playing."""
        if not self.paused:
            return False
        self._steps += 1
        self._wake.set()
        return True

    def _seek_to(self, t_ns: int) -> None:
        t_ns = max(self.start_ns, min(t_ns, self.end_ns))
        self.source.seek(t_ns)
        self._frozen_ns = t_ns
        self._steps = 0
        self._positioned = True
        self._pass_published = 0
        if self.paused:
            self._anchor_next = False
        else:
            self._anchor(t_ns)

    def seek(self, t_ns: int) -> None:
        """Move to bag time ``t_ns`` (clamped to the bag): the next message is the first at or after it."""
        self._seek_to(t_ns)
        self._changed()

    def seek_fraction(self, fraction: float) -> None:
        """Move to ``fraction`` (0..1) of the bag's time span."""
        fraction = max(0.0, min(1.0, fraction))
        self.seek(self.start_ns + round((self.end_ns - self.start_ns) * fraction))

    def seek_by(self, seconds: float) -> None:
        """Move the bag clock by ``seconds`` (negative: back)."""
        self.seek(self.bag_ns() + int(seconds * 1e9))

    def set_rate(self, rate: float) -> None:
        """Play ``rate`` times as fast from now on."""
        if not rate > 0:
            raise ValueError("the rate must be greater than 0")
        if not self.paused and not self._anchor_next:
            self._anchor(self.bag_ns())
        self.rate = rate
        self._changed()

    def set_loop(self, loop: bool) -> None:
        """Start over at the end (True) or stop there."""
        self.loop = loop
        self._changed()

    def set_topic_enabled(self, topic: str, enabled: bool) -> None:
        """Publish ``topic`` (True) or skip its messages (False)."""
        if enabled:
            self.disabled.discard(topic)
        else:
            self.disabled.add(topic)
        self._changed()

    def stop(self) -> None:
        """End :meth:`run`."""
        self.stopped = True
        self._changed()

    # -- running -----------------------------------------------------------------------------
    def _wanted(self, conn: Connection) -> bool:
        return conn.topic not in self.disabled and (self.accepts is None or self.accepts(conn))

    def _route(self, conn: Connection) -> _Route:
        """``conn``'s route, remembered until a control call."""
        route = self._routes.get(id(conn))
        if route is None or route[0] is not conn:
            wanted = self._wanted(conn)
            sender = self.sender_for(conn) if wanted and self.sender_for is not None else None
            route = self._routes[id(conn)] = (conn, wanted, sender)
        return route

    def _pass_head(self) -> MessageItem | None:
        """The message at the read position; None at the end of the pass (or past ``play_until``)."""
        item = self.source.peek()
        if item is None or (self.play_until is not None and item[1] > self.play_until):
            return None
        return item

    def _tick(self, horizon: int | None = None) -> None:
        """Tell ``on_tick`` the bag time; while waiting for a message, never past that message's time
        (so a /clock tick cannot run ahead of the message published next)."""
        if self.on_tick is not None:
            now = self.bag_ns()
            self.on_tick(now if horizon is None else min(now, horizon))

    async def _sleep(self, seconds: float) -> None:
        """Sleep up to ``seconds``; a control call wakes it early."""
        try:
            await asyncio.wait_for(self._wake.wait(), max(0.0, seconds))
        except asyncio.TimeoutError:
            pass
        self._wake.clear()

    async def _wait_bag(self, t_ns: int) -> float | None:
        """Wait until the bag clock reaches ``t_ns``; returns that wall time, or None when paused, stopped or
        moved meanwhile."""
        gen = self._gen
        while True:
            if self.stopped or self.paused or gen != self._gen:
                return None
            target = self._wall_of(t_ns)
            remaining = target - self.clock()
            if remaining <= 0:
                return target
            if remaining > SPIN_BEFORE:
                await self._sleep(min(remaining - SPIN_BEFORE, self.tick_period))
                self._tick(horizon=t_ns)
                continue
            sleep_until(target, self.clock)  # the loop's timers are ms-grained
            return target

    def _emit(self, item: MessageItem, target: float | None) -> None:
        conn, t, data = item
        send = self._route(conn)[2]
        actual = self.clock()
        if send is None:
            self.publish(conn, t, data)
        else:
            send(data)
        self.source.advance()
        self.last_ns = t
        self._frozen_ns = t
        self._anchor_next = False
        self.published += 1
        self._pass_published += 1
        if target is not None:
            self.lateness.append(actual - target)

    async def _at_pass_end(self) -> bool:
        """The pass is over: loop, hold or finish; False when :meth:`run` should return."""
        if self.loop and self._pass_published:
            if not self.paused:
                if await self._wait_bag(self.end_bound) is None:
                    return True  # paused, moved or stopped while waiting for the end
                self._anchor_next = True
            self.source.seek(self.play_from)
            self._frozen_ns = self.play_from
            self._pass_published = 0
            return True
        if not self.hold_at_end:
            return False
        if not self.paused:
            self._frozen_ns = min(self.bag_ns(), self.end_bound)
            self.paused = True
        self._steps = 0
        await self._sleep(self.tick_period)
        self._tick()
        return True

    async def run(self) -> int:
        """Play to the end (for ever with ``loop`` or ``hold_at_end``) or until :meth:`stop`; returns messages published."""
        self._started = True
        lower_timer_slack()
        if not self._positioned:
            self.source.seek(self.play_from)
            self._positioned = True
        while not self.stopped:
            await _turn()
            item = self._pass_head()
            wanted = item is None or self._route(item[0])[1]
            skipped = 0
            while not wanted and skipped < SKIP_BATCH:
                self.source.advance()
                skipped += 1
                item = self._pass_head()
                wanted = item is None or self._route(item[0])[1]
            if not wanted:
                continue  # a long run of skipped messages: give the loop its turn first
            if item is None:
                if not await self._at_pass_end():
                    break
                continue
            if self.paused:
                if self._steps > 0:
                    self._steps -= 1
                    self._emit(item, None)
                    continue
                await self._sleep(self.tick_period)
                self._tick()
                continue
            if self._anchor_next:
                self._anchor(item[1])
            target = await self._wait_bag(item[1])
            if target is not None:
                self._emit(item, target)
                self._emit_due(target + self.turn_period)
        return self.published

    def _emit_due(self, turn_by: float) -> None:
        """Publish the messages that follow while each is due within SPIN_BEFORE and the loop's next turn is not
        due (``turn_by``, a wall time): the loop cannot change anything meanwhile, so each is only slept for and
        sent.  A message not wanted, the pass's end, or one due later leaves it to :meth:`run`.

        :meth:`_emit`, :meth:`_route` and :meth:`_wall_of` are written out here: after the sleep before each
        message every call runs with cold caches, and the calls saved were about 7% of a player's CPU
        (bench/README.md, "Bag play CPU", third pass)."""
        clock = self.clock
        sleep = time.sleep
        source = self.source
        publish = self.publish
        lateness = self.lateness
        routes = self._routes
        until = self.play_until
        anchor_wall, anchor_bag, rate = self._anchor_wall, self._anchor_bag, self.rate
        while True:
            item = source.peek()
            if item is None:
                return
            conn, t, data = item
            if until is not None and t > until:
                return
            route = routes.get(id(conn))
            if route is None or route[0] is not conn:
                route = self._route(conn)
            if not route[1]:
                return
            target = anchor_wall + (t - anchor_bag) / 1e9 / rate
            left = target - clock()
            if target > turn_by or left > SPIN_BEFORE:
                return
            if left > 0:
                sleep(left)
            send = route[2]
            actual = clock()
            if send is None:
                publish(conn, t, data)
            else:
                send(data)
            source.advance()
            self.last_ns = self._frozen_ns = t
            self.published += 1
            self._pass_published += 1
            lateness.append(actual - target)
