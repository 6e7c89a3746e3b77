"""BagViewApp: a bag as a video player (rqt_bag in the terminal).

The bag's index (where each message lies, no payload) is read into a
:class:`~rostui.core.bag.index.BagIndex` in a worker thread; a :class:`~rostui.core.bag.transport.Transport` (the same scheduler as
``rostui bag play``) runs on Textual's loop. Nothing is published until the
user asks (rqt_bag's "Publish" box): ``t`` publishes the selected topic, ``a``
every topic, ``--publish``/``--topics`` from the start; only then does a node
``/bag_view_...`` join the master, advertising just those topics with their
recorded types.  Without a master (or with ``publish=False``) the app still
browses the bag. The
screen is refreshed ten times a second from the transport's state: the
timeline's cursor, the status line and the inspector (the selected topic's
message under the cursor, decoded as ``rostopic echo`` prints it).
"""

from __future__ import annotations

import asyncio
import os
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, ClassVar

from textual import work
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import VerticalScroll
from textual.widgets import Input, Static

from rostui.apps.bagview.bars import PLAY_KEYS, header_text, play_status, wall_text
from rostui.apps.bagview.inspect_view import InspectorView, inspected_text
from rostui.apps.bagview.timeline import TimelineView
from rostui.apps.terminal import terminal_missing
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.apps.widgets.line_input import LineInput
from rostui.core.bag.clock import DEFAULT_HZ, BagClock
from rostui.core.bag.index import BagIndex, IndexSource, MessageRef, load_index
from rostui.core.bag.model import BagError, Connection
from rostui.core.bag.transport import TICK_PERIOD, Transport
from rostui.core.node import AnyMsg

__all__ = ["BagViewApp", "RATES", "parse_goto", "run_app"]

#: Screen refreshes per second.
REFRESH_RATE = 10.0

#: The rates ``+`` and ``-`` step through.
RATES = (0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)

#: Messages larger than this (bytes) are inspected with arrays summarised (``rostopic echo --noarr``).
INSPECT_ARRAYS_UP_TO = 64 * 1024

#: Seconds between attempts to reach the master when none answered.
RETRY_SECONDS = 2.0

#: Seconds the node may take to shut down when the app quits.
SHUTDOWN_TIMEOUT = 3.0

#: What the header says while nothing is published.
NOT_PUBLISHING = "not publishing: t publishes the selected topic, a every topic"


def parse_goto(text: str, start_ns: int, end_ns: int) -> int:
    """A bag time from what the user typed: ``50%``, seconds from the start (``12.5``) or a bag stamp."""
    text = text.strip()
    try:
        if text.endswith("%"):
            fraction = float(text[:-1]) / 100.0
            if not 0.0 <= fraction <= 1.0:
                raise ValueError
            return start_ns + round((end_ns - start_ns) * fraction)
        seconds = float(text)
    except ValueError:
        raise ValueError(f"'{text}' is neither a percentage (50%), seconds from the start (12.5) "
                         "nor a bag time") from None
    if seconds * 1e9 >= start_ns > 0:
        return int(seconds * 1e9)
    return start_ns + int(seconds * 1e9)


class GotoPrompt(LineInput):
    """Where to go: a percentage, seconds from the start or a bag time; Escape closes it."""

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "close", "close", show=False)]

    def action_close(self) -> None:
        """Close without moving."""
        self.display = False
        self.app.query_one(TimelineView).focus()


class BagViewApp(ReleasesOnExit, KeysApp):
    """Play, pause, step, seek and inspect a bag; publish it on a live graph.

    ``clock`` is the transport's wall clock (a snapshot test freezes it); ``publish_clock`` publishes the
    bag time on ``/clock`` at ``clock_hz`` (``--clock``, ``--hz``).
    """

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui bag view"
    KEY_NOTES = (("click", "seek there (in the strips) or select the topic (on its name)"),)

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("q", "quit", "quit"),
        Binding("space,p", "toggle_play", "play/pause"),
        Binding("s", "step", "step"),
        Binding("left", "seek_by(-1)", "back 1 s", show=False),
        Binding("right", "seek_by(1)", "forward 1 s", show=False),
        Binding("pageup,shift+left", "seek_fraction_by(-0.1)", "back 10%", show=False),
        Binding("pagedown,shift+right", "seek_fraction_by(0.1)", "forward 10%", show=False),
        Binding("home", "seek_fraction(0)", "go to the start", show=False),
        Binding("end", "seek_fraction(1)", "go to the end", show=False),
        *[Binding(str(d), f"seek_fraction({d / 10})", f"go to {d * 10}%", show=False) for d in range(10)],
        Binding("comma", "message(-1)", "previous message of the topic", show=False),
        Binding("full_stop", "message(1)", "next message of the topic", show=False),
        Binding("g,percent_sign", "goto", "go to"),
        Binding("plus,equals_sign,right_square_bracket", "rate(1)", "faster"),
        Binding("minus,left_square_bracket", "rate(-1)", "slower"),
        Binding("l", "toggle_loop", "loop"),
        Binding("up", "select(-1)", "previous topic", show=False),
        Binding("down", "select(1)", "next topic", show=False),
        Binding("t,enter", "toggle_topic", "publish the topic on/off"),
        Binding("a", "all_topics", "publish every topic / none"),
        Binding("i", "toggle_inspector", "inspector"),
    ]

    def __init__(self, paths: Sequence[str], *, rate: float = 1.0, loop: bool = False, publish: bool = True,
                 topics: Sequence[str] = (), publish_all: bool = False, start_playing: bool = False,
                 master_uri: str | None = None,
                 queue_size: int = 100, clock: Callable[[], float] = time.perf_counter,
                 publish_clock: bool = False, clock_hz: float = DEFAULT_HZ) -> None:
        super().__init__()
        self.paths = list(paths)
        self.names = [os.path.basename(p) for p in self.paths]
        self.rate = rate
        self.loop_play = loop
        self.publish_allowed = publish
        self.start_topics = set(topics)
        self.publish_all_at_start = publish_all
        self.start_playing = start_playing
        self.master_uri = master_uri
        self.queue_size = queue_size
        self.clock = clock
        self.bag_clock = BagClock(clock_hz) if publish_clock else None
        self.index: BagIndex | None = None
        self.transport: Transport | None = None
        self.source: IndexSource | None = None
        self.node: Any = None
        self.publishers: dict[tuple[str, str], Any] = {}
        self.publishing: set[str] = set()
        self.published = 0
        self.link = NOT_PUBLISHING if publish else "browsing only (--no-publish)"
        self._connecting = False
        self._sync_lock = asyncio.Lock()
        self.selected = 0
        self.error = ""
        self.rosbag_duration: str | None = None
        """What ``bag info`` (rosbag's rules) gives as the duration, when it is not the messages' span."""
        self._header_shown = ""
        self._run_task: asyncio.Task[int] | None = None
        self._inspected: tuple[str | None, MessageRef | None] = (None, None)
        self.header = Static(header_text(self.names, None), id="header")
        self.timeline = TimelineView(id="timeline")
        self.inspector = VerticalScroll(id="inspector")
        self.inspector_title = Static(id="inspector-title")
        self.inspector_text = Static(id="inspector-text")
        self.inspector_view = InspectorView(self.inspector, self.inspector_text)
        self.prompt = GotoPrompt(placeholder="go to: 50%  ·  12.5 (seconds from the start)  ·  a bag time",
                                 id="prompt")
        self.status = Static(id="status")

    # -- composition ---------------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        """Header, timeline, inspector, prompt, status line and key help."""
        yield self.header
        yield self.timeline
        with self.inspector:
            yield self.inspector_title
            yield self.inspector_text
        yield self.prompt
        yield self.status
        yield Static(PLAY_KEYS, id="keys")

    def on_mount(self) -> None:
        """Read the bag (in a thread), then start the transport and, when publishing, the node."""
        self.prompt.display = False
        self.timeline.focus()
        quit_on_signals(self)
        self._read_bag()
        self.set_interval(1.0 / REFRESH_RATE, self.refresh_view)

    @work(thread=True, exit_on_error=False)
    def _read_bag(self) -> None:
        def progress(text: str) -> None:
            self.call_from_thread(self.header.update, header_text(self.names, None, text))

        try:
            index = load_index(self.paths, progress)
        except BagError as exc:
            self.error = str(exc)
            self.call_from_thread(self.exit, None, 1)
            return
        self.rosbag_duration = _rosbag_duration(index)
        self.call_from_thread(self._bag_ready, index)

    def _bag_ready(self, index: BagIndex) -> None:
        self.index = index
        self.source = IndexSource(index)
        self.transport = Transport(self.source, self._publish, start_ns=index.start_ns, end_ns=index.end_ns,
                                   rate=self.rate, loop=self.loop_play, paused=not self.start_playing,
                                   hold_at_end=True, clock=self.clock,
                                   on_tick=self._on_tick if self.bag_clock else None,
                                   tick_period=self.bag_clock.tick_period(TICK_PERIOD) if self.bag_clock
                                   else TICK_PERIOD)
        self.timeline.set_index(index)
        for notice in index.notices:
            self.notify(notice, title="file cut short", severity="warning", timeout=8)
        self._run_task = asyncio.ensure_future(self.transport.run())
        if self.publish_allowed:
            self.publishing = set(index.topics) if self.publish_all_at_start else self.start_topics & set(index.topics)
            self._publishing_changed()
        self.refresh_view()

    def _publishing_changed(self) -> None:
        """Join the master once something is to be published, and (re)advertise what is switched on."""
        if self.node is not None:
            self.run_worker(self._sync_publishers(), group="publishers", exit_on_error=False)
        elif (self.publishing or self.bag_clock is not None) and not self._connecting:
            self._connecting = True
            self.link = "connecting to the master…"
            self.run_worker(self._connect(), name="node", exit_on_error=False)
        elif not self._connecting:
            self.link = NOT_PUBLISHING

    async def _connect(self) -> None:
        """Start the node; without a master, browse and try again now and then."""
        while not await self._try_connect():
            await asyncio.sleep(RETRY_SECONDS)
        self._connecting = False
        await self._sync_publishers()

    async def _try_connect(self) -> bool:
        from rostui.core.node import AsyncNode

        node = AsyncNode("bag_view", anonymous=True, master_uri=self.master_uri)
        node.log.console = None  # library warnings must not write over the screen
        try:
            await node.start(publish_rosout=False)
            await asyncio.wait_for(node.master_call("getPid"), 5.0)
            if self.bag_clock is not None:
                await self.bag_clock.advertise(node)
        except Exception:  # no master, or it refused us: browse without publishing
            try:
                await asyncio.wait_for(node.shutdown("rostui bag view: no master"), SHUTDOWN_TIMEOUT)
            except Exception:
                pass
            self.link = f"no master at {node.master_uri}: not publishing (trying again every {RETRY_SECONDS:g} s)"
            return False
        self.node = node
        self.link = f"advertising as {node.name}…"
        return True

    async def _sync_publishers(self) -> None:
        """Advertise the connections of the topics switched on; unregister those of topics switched off."""
        from rostui.tools.bag.player import advertise_connections

        async with self._sync_lock:
            node, index = self.node, self.index
            if node is None or index is None:
                return
            wanted = [c for c in index.connections if c.topic in self.publishing]
            new = [c for c in wanted if (c.topic, c.md5sum) not in self.publishers]
            if new:
                self.publishers.update(await advertise_connections(node, new, self.queue_size))
            keep = {(c.topic, c.md5sum) for c in wanted}
            for key in [key for key in self.publishers if key not in keep]:
                await self.publishers.pop(key).unregister()
            topics = len({topic for topic, _ in self.publishers})
            parts = [f"{topics} topic{'s' if topics != 1 else ''}"] if topics else []
            parts += ["/clock"] if self.bag_clock is not None else []
            self.link = f"publishing {' and '.join(parts)} as {node.name}" if parts else NOT_PUBLISHING

    # -- publishing ------------------------------------------------------------------------------------
    def _publish(self, conn: Connection, t: int, data: bytes) -> None:
        if self.bag_clock is not None:
            self.bag_clock.publish(t)
        pub = self.publishers.get((conn.topic, conn.md5sum)) if conn.topic in self.publishing else None
        if pub is not None:
            pub.publish(AnyMsg(data))
            self.published += 1

    def _on_tick(self, bag_ns: int) -> None:
        """The transport's tick (playing, paused or held at the end): the bag time on /clock."""
        if self.bag_clock is not None:
            self.bag_clock.publish(bag_ns)

    # -- the screen ------------------------------------------------------------------------------------
    def refresh_view(self) -> None:
        """Timer: cursor, status line and inspector from the transport's state."""
        transport, index = self.transport, self.index
        if transport is None or index is None:
            self.status.update(" reading " + ", ".join(self.names) + "…")
            return
        bag_ns = transport.bag_ns()
        self.timeline.show(bag_ns, self.selected, self.publishing)
        self.status.update(play_status(paused=transport.paused, at_end=transport.at_end, rate=transport.rate,
                                       loop=transport.loop, bag_ns=bag_ns, start_ns=index.start_ns,
                                       end_ns=index.end_ns, published=self.published if self.node else -1,
                                       problem=self.source.problem if self.source is not None else ""))
        header = header_text(self.names, index, self.link, self.rosbag_duration, self.header.size.width)
        if header.plain != self._header_shown:
            self._header_shown = header.plain
            self.header.update(header)
        if self.inspector.display:
            self._inspect(bag_ns)

    def _inspect(self, bag_ns: int) -> None:
        assert self.index is not None
        topic = self.timeline.selected_topic
        try:
            ref = self.index.message_at(topic, bag_ns) if topic is not None else None
        except BagError as exc:  # the entries of a chunk that cannot be read
            self.inspector_title.update(_escape(f"{topic}: {exc}"))
            return
        if (topic, ref) == self._inspected:
            return
        self._inspected = (topic, ref)
        if topic is None or ref is None:
            self.inspector_title.update("no message")
            self.inspector_text.update("")
            self.inspector_view.clear()
            return
        try:
            conn, t, data = self.index.item(ref)
        except BagError as exc:  # a damaged chunk, or a record the index misplaces
            self.inspector_title.update(_escape(topic))
            self.inspector_text.update(f"[b]{_escape(str(exc))}[/b]")
            self.inspector_view.clear()
            return
        track = self.index.tracks[topic]
        try:
            number = str(self.index.number_in_track(topic, ref))
        except BagError:
            number = "?"
        self.inspector_title.update(_escape(f"{topic}  {conn.type}  #{number} of {track.count}  bag {t / 1e9:.6f}  "
                                            f"{wall_text(t)}  {len(data)} B"))
        try:
            pictured = self.inspector_view.show(topic, conn, data, t)
            noarr = pictured or len(data) > INSPECT_ARRAYS_UP_TO
            self.inspector_text.update(_escape(inspected_text(conn, data, noarr=noarr,
                                                              cut_above=INSPECT_ARRAYS_UP_TO)))
        except BagError as exc:
            self.inspector_text.update(f"[b]{_escape(str(exc))}[/b]")

    # -- actions -----------------------------------------------------------------------------------------
    def action_toggle_play(self) -> None:
        """Play or pause."""
        if self.transport is not None:
            self.transport.toggle_pause()
            self.refresh_view()

    def action_step(self) -> None:
        """Publish the next message (pauses first when playing)."""
        if self.transport is None:
            return
        if not self.transport.paused:
            self.transport.pause()
        else:
            self.transport.step()
        self.refresh_view()

    def action_seek_by(self, seconds: float) -> None:
        """Move the cursor by ``seconds``."""
        if self.transport is not None:
            self.transport.seek_by(seconds)
            self.refresh_view()

    def action_seek_fraction(self, fraction: float) -> None:
        """Move the cursor to ``fraction`` of the bag."""
        if self.transport is not None:
            self.transport.seek_fraction(fraction)
            self.refresh_view()

    def action_seek_fraction_by(self, delta: float) -> None:
        """Move the cursor by ``delta`` of the bag."""
        if self.transport is not None:
            self.transport.seek_fraction(self.transport.fraction() + delta)
            self.refresh_view()

    def action_message(self, direction: int) -> None:
        """Move the cursor to the selected topic's previous or next message (nothing is published)."""
        topic = self.timeline.selected_topic
        if self.transport is None or self.index is None or topic is None:
            return
        try:
            target = self.index.neighbour_time(topic, self.transport.bag_ns(), direction)
        except BagError as exc:  # the entries of a chunk that cannot be read
            self.notify(str(exc), title="message", severity="error")
            return
        if target is not None:
            self.transport.seek(target)
            self.refresh_view()

    def on_timeline_view_seek(self, message: TimelineView.Seek) -> None:
        """A click in the strips."""
        self.action_seek_fraction(message.fraction)

    def on_timeline_view_selected(self, message: TimelineView.Selected) -> None:
        """A click on a topic's name."""
        self.selected = message.row
        self.refresh_view()

    def action_goto(self) -> None:
        """Open the go-to prompt."""
        self.prompt.value = ""
        self.prompt.display = True
        focus_now(self.prompt)

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """Go where the prompt says."""
        self.prompt.display = False
        self.timeline.focus()
        if self.transport is None or self.index is None:
            return
        try:
            target = parse_goto(event.value, self.index.start_ns, self.index.end_ns)
        except ValueError as exc:
            self.notify(str(exc), title="go to", severity="error")
            return
        self.transport.seek(target)
        self.refresh_view()

    def action_rate(self, direction: int) -> None:
        """One step up or down the rate ladder."""
        if self.transport is None:
            return
        rate = self.transport.rate
        faster = [r for r in RATES if r > rate * 1.0001]
        slower = [r for r in RATES if r < rate / 1.0001]
        if direction > 0 and faster:
            self.transport.set_rate(faster[0])
        elif direction < 0 and slower:
            self.transport.set_rate(slower[-1])
        self.refresh_view()

    def action_toggle_loop(self) -> None:
        """Loop on or off."""
        if self.transport is not None:
            self.transport.set_loop(not self.transport.loop)
            self.refresh_view()

    def action_select(self, delta: int) -> None:
        """Select the previous or next topic."""
        if self.index is not None and self.index.tracks:
            self.selected = max(0, min(len(self.index.tracks) - 1, self.selected + delta))
            self.refresh_view()

    def action_toggle_topic(self) -> None:
        """Publish the selected topic, or stop publishing it."""
        topic = self.timeline.selected_topic
        if self.index is not None and topic is not None and self._may_publish():
            self.publishing ^= {topic}
            self._publishing_changed()
            self.refresh_view()

    def action_all_topics(self) -> None:
        """Publish every topic; when every topic is published already, none."""
        if self.index is not None and self._may_publish():
            everything = set(self.index.topics)
            self.publishing = set() if self.publishing >= everything else everything
            self._publishing_changed()
            self.refresh_view()

    def _may_publish(self) -> bool:
        if not self.publish_allowed:
            self.notify("browsing only: opened with --no-publish", title="publish", severity="warning")
        return self.publish_allowed

    def action_toggle_inspector(self) -> None:
        """Show or hide the inspector."""
        self.inspector.display = not self.inspector.display
        self._inspected = (None, None)
        self.refresh_view()

    async def release(self) -> None:
        """Stop the transport and shut the node down."""
        if self.transport is not None:
            self.transport.stop()
        if self._run_task is not None:
            try:
                await asyncio.wait_for(self._run_task, SHUTDOWN_TIMEOUT)
            except Exception:
                pass
            self._run_task = None
        node, self.node = self.node, None
        if node is not None:
            try:
                await asyncio.wait_for(node.shutdown("rostui bag view closed"), SHUTDOWN_TIMEOUT)
            except Exception:
                pass
        if self.index is not None:
            self.index.close()


def _rosbag_duration(index: BagIndex) -> str | None:
    """bag info's duration of the one file viewed, when rosbag's rules (its first and last chunk) do not give
    the messages' span; None otherwise (and for several files, each with its own)."""
    from rostui.tools.bag.info import rosbag_duration

    if len(index.readers) != 1:
        return None
    try:
        return rosbag_duration(index.readers[0].summary())
    except BagError:
        return None


def _escape(text: str) -> str:
    from rich.markup import escape

    return escape(text)


def run_app(paths: Sequence[str], **options: Any) -> int:
    """Run :class:`BagViewApp` in this terminal; returns the exit status (1 without a terminal or a bag)."""
    if terminal_missing("rostui bag view", "use `rostui bag play` without one"):
        return 1
    app = BagViewApp(paths, **options)
    app.run()
    if app.error:
        print(f"rostui bag view: {app.error}", file=sys.stderr)
    return app.return_code or 0
