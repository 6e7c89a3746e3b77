"""ViewPanel and ViewGrid: one bordered panel per topic, holding the view its type has in the registry.

A panel learns its topic's type (from whoever owns the node: the master's
topic types), mounts the registered view, and keeps a
:class:`~rostui.apps.view.feed.TopicFeed` subscribed only while it is
mounted.  Each arrival schedules one delivery; a delivery takes only the
newest message, decodes it (lazily: numeric arrays stay numpy views over the
received bytes, :mod:`rostui.models.sensors.lazy_msg`) and hands it to the
view, so frames that came while the screen was busy are dropped, not queued.
Each panel's :class:`~rostui.models.frame_budget.FrameBudget` is charged the
CPU its own deliveries take (and its part of what the grid's screen and node
cost besides) and spaces them so the panel stays within its share of a core
however fast or heavy its frames come; a heavy topic drops its own frames,
never its neighbours'.  A type no view shows
is one line in the panel naming the types that can be shown.

A view draws its type by its fields, so the panel hears only publishers of
exactly that type under rostui's md5sum
(:func:`~rostui.core.node.header_check.of_type`): a publisher whose header
says another type or md5sum (whatever it told the master) is refused, one
line in the panel says so, and the topic's honest publishers are drawn as
before.

A view class with ``SHARED = True`` (the top-down view) draws several topics
in one picture: the first panel of that class mounts the view, each later
panel of the class hands its topic to that view (``add_topic``), delivers to
it (``show_topic_message``) and hides itself.  ``view_options`` reach the
views whose class lists them in ``OPTIONS`` (``--frame``).  A view class with
``OWN_SUBSCRIPTIONS = True`` (the tf tree, which needs every message with its
publisher's name) subscribes itself; its panel subscribes to nothing.
"""

from __future__ import annotations

import asyncio
import time
from typing import Any, Callable, Mapping, Sequence

from textual.app import ComposeResult
from textual.containers import Container, Horizontal, Vertical
from textual.markup import escape
from textual.widgets import Static

from rostui.apps.view.feed import TopicFeed
from rostui.apps.view.registry import TopicView, UnknownViewError, view_class
from rostui.core.msg import foreign_version
from rostui.core.node import AsyncNode
from rostui.core.node.header_check import RefusalLog, of_type
from rostui.models.frame_budget import FrameBudget, SharedCost
from rostui.models.master_link import MASTER_ERRORS
from rostui.models.sensors.markers2d import MARKER_TYPES

__all__ = ["ViewPanel", "ViewGrid", "NodeOf", "TypeOf", "decode_for_view"]

#: Returns the node to subscribe with (None while no master answers).
NodeOf = Callable[[], "AsyncNode | None"]
#: Returns the type the master knows for a topic (None when it has no publisher or subscriber).
TypeOf = Callable[[str], "str | None"]

#: Seconds between checks of each panel's type and subscription.
CHECK_EVERY = 0.5

#: Types whose every message changes the picture (markers add and delete some): none is skipped for a newer one.
EVERY_MESSAGE_TYPES = frozenset(MARKER_TYPES)

#: Most such messages waiting for the screen; the oldest is dropped past it.
KEEP_EVERY = 512


def decode_for_view(raw: Any) -> Any:
    """A received message as the views read it: lazily (arrays as numpy views), when its publisher sends rostui's
    version of its type; ValueError (one line) for any other, which no view can read by its fields."""
    from rostui.models.sensors.lazy_msg import decode_lazily
    from rostui.tools.topic.echo import decode

    msg = decode_lazily(raw)
    if msg is None:
        other = foreign_version(decode(raw))
        raise ValueError(f"{other}: not drawn" if other else "not a message a view draws")
    return msg


class ViewPanel(Vertical):
    """The panel of ``topic``: a note line, and the registered view once the topic's type is known."""

    DEFAULT_CSS = """
    ViewPanel { border: round $primary; height: 1fr; width: 1fr; }
    ViewPanel > .view-note { height: auto; color: $text-muted; }
    ViewPanel > .view-note.problem { color: $error; }
    ViewPanel > .view-refused { height: auto; color: $error; }
    """

    def __init__(self, topic: str, *, msg_type: str | None = None,
                 view_options: Mapping[str, Any] | None = None, shared: SharedCost | None = None) -> None:
        super().__init__(classes="view-panel")
        self.topic = topic
        self.msg_type = msg_type
        self.view_options = dict(view_options or {})
        self.joined = False
        self.view: TopicView | None = None
        self.budget = FrameBudget(shared=shared)
        self.feed = TopicFeed(topic, self._arrived)
        self.note = Static(classes="view-note")
        self.refused_line = Static(classes="view-refused")
        """The newest publisher refused for sending another type or md5sum than the view's (hidden before one)."""
        self.refused_line.display = False
        self.problem = ""
        self._delivery_pending = False
        self.border_title = escape(topic)

    def compose(self) -> ComposeResult:
        """The note line and the refusal line; the view is mounted once the type is known."""
        yield self.note
        yield self.refused_line

    def on_mount(self) -> None:
        """Say what the panel waits for."""
        self.say(f"waiting for {self.topic} to be published")

    def say(self, text: str, *, problem: bool = False) -> None:
        """The panel's note line (red when ``problem``); empty hides it."""
        self.note.update(escape(text))
        self.note.set_class(problem, "problem")
        self.note.display = bool(text)

    async def check(self, node: AsyncNode | None, msg_type: str | None) -> None:
        """Mount the view for ``msg_type`` once it is known, and keep the feed subscribed on ``node``."""
        if msg_type and self.view is None and not self.problem:
            self.msg_type = msg_type
            try:
                cls = view_class(msg_type)
            except UnknownViewError as exc:
                self.problem = f"{self.topic}: {exc}"
                self.say(self.problem, problem=True)
                return
            self.feed.check = RefusalLog(of_type(msg_type), self._refused)
            self.feed.keep_every = KEEP_EVERY if msg_type in EVERY_MESSAGE_TYPES else 0
            host = self._shared_host(cls)
            if host is not None:
                host.add_topic(self.topic)  # type: ignore[attr-defined]
                self.view, self.joined, self.display = host, True, False
            else:
                self.border_subtitle = escape(msg_type)
                options = {k: v for k, v in self.view_options.items() if k in getattr(cls, "OPTIONS", ())}
                self.view = cls(self.topic, **options)
                self.view.arrivals = self.feed.received
                await self.mount(self.view)
                self.say("" if self.own_subscriptions else "waiting for the first message")
        if self.view is not None and not self.own_subscriptions:
            await self.feed.attach(node)

    @property
    def own_subscriptions(self) -> bool:
        """True when the mounted view subscribes itself (the panel's feed stays detached)."""
        return bool(getattr(type(self.view), "OWN_SUBSCRIPTIONS", False))

    def _refused(self, why: str) -> None:
        """A publisher of this topic was refused (another type or md5sum than the view draws): one line says so,
        in this panel or, when it joined another panel's view, in that one's."""
        shown = self
        if self.joined and self.parent is not None:
            shown = next((panel for panel in self.parent.query_children(ViewPanel)
                          if panel.view is self.view and not panel.joined), self)
        shown.refused_line.update(escape(f"{self.topic}: refused {why}: its messages are not drawn"
                                         if shown is not self else f"refused {why}: its messages are not drawn"))
        shown.refused_line.display = True

    def _shared_host(self, cls: type[TopicView]) -> TopicView | None:
        """The view of class ``cls`` another panel of this grid mounted, when ``cls`` shares one view."""
        if not getattr(cls, "SHARED", False) or self.parent is None:
            return None
        for panel in self.parent.query_children(ViewPanel):
            if panel is not self and not panel.joined and isinstance(panel.view, cls):
                return panel.view
        return None

    async def stop(self) -> None:
        """Unsubscribe."""
        await self.feed.detach()

    def _arrived(self) -> None:
        if not self._delivery_pending and self.view is not None:
            self._delivery_pending = True
            wait = self.budget.wait()
            if wait > 0:
                self.set_timer(wait, self.deliver)
            else:
                self.call_later(self.deliver)

    def deliver(self) -> None:
        """Decode the newest message (only it) and hand it to the view, charging the CPU it takes to this panel.

        A view with work to do off the event loop (:meth:`TopicView.off_loop`: decoding a compressed image)
        gets it done on a worker thread, so a heavy frame does not hold the other panels' frames back; the
        next frame is taken once it is drawn.
        """
        if self.feed.keep_every and self.view is not None:
            self._deliver_every()
            return
        taken = self.feed.take()
        if taken is None or self.view is None:
            self._delivery_pending = False
            return
        raw, received = taken
        with self.budget.spending():
            msg = self._decode(raw)
            job = None if msg is None or self.joined else self.view.off_loop(msg, received)
            if job is None:
                self._delivery_pending = False
                if msg is not None:
                    self._show(msg, received)
                return
        self.run_worker(self._deliver_off_loop(job, received), group="panel-deliver", exit_on_error=False)

    def _deliver_every(self) -> None:
        """Hand the view every waiting message, in the order they came (their CPU charged to this panel)."""
        self._delivery_pending = False
        with self.budget.spending():
            while (taken := self.feed.take()) is not None:
                msg = self._decode(taken[0])
                if msg is not None:
                    self._show(msg, taken[1])
        if self.feed.dropped and self.view is not None:
            self.view.dropped(self.topic, self.feed.dropped)

    async def _deliver_off_loop(self, job: Callable[[], Any], received: float) -> None:
        """Run ``job`` on a worker thread (its CPU charged to this panel), then draw what it made on the loop."""
        def timed() -> tuple[Any, float]:
            start = time.thread_time()
            result = job()
            return result, time.thread_time() - start

        try:
            prepared, cost = await asyncio.to_thread(timed)
            self.budget.charge(cost)
            if self.view is not None:
                with self.budget.spending():
                    self._clear_note()
                    self.view.show_prepared(prepared, received)
        finally:
            self._delivery_pending = False
            if self.feed.waiting and self.is_attached:
                self._arrived()

    def _decode(self, raw: Any) -> Any:
        """The message the view reads (None, and the reason on the note line, when it cannot be decoded)."""
        try:
            return decode_for_view(raw)
        except Exception as exc:  # a message its own definition cannot read: said, and the next one tried
            self.say(f"cannot decode a message on {self.topic}: {str(exc).splitlines()[0] if str(exc) else exc!r}",
                     problem=True)
            return None

    def _clear_note(self) -> None:
        if self.note.display:
            self.say("")

    def _show(self, msg: Any, received: float) -> None:
        assert self.view is not None
        if self.joined:
            self.view.show_topic_message(self.topic, msg, received)  # type: ignore[attr-defined]
            return
        self._clear_note()
        self.view.show_message(msg, received)


class ViewGrid(Container):
    """A panel per topic side by side; subscribes through ``node_of()``, learns types through ``type_of(topic)``.

    Topics nobody publishes yet (an rviz file names many) do not take a column each: while more than one waits,
    or one waits beside a drawn view, their panels are hidden and one line above the panels names them.
    """

    DEFAULT_CSS = """
    ViewGrid { layout: vertical; height: 1fr; }
    ViewGrid > #waiting { height: auto; max-height: 2; color: $text-muted; }
    ViewGrid > #panels { layout: horizontal; height: 1fr; }
    """

    def __init__(self, topics: Sequence[str], node_of: NodeOf, type_of: TypeOf, *, id: str | None = None,
                 view_options: Mapping[str, Any] | None = None) -> None:
        super().__init__(id=id)
        self.topics = list(dict.fromkeys(topics))
        self.node_of = node_of
        self.type_of = type_of
        self.shared_cost = SharedCost()
        """What the viewer costs beyond the panels' own frames (composing, writing, receiving), shared out."""
        self.panels = [ViewPanel(topic, view_options=view_options, shared=self.shared_cost) for topic in self.topics]
        self._checking = False

    def compose(self) -> ComposeResult:
        """The line of topics waiting to be published, and one panel per topic."""
        waiting = Static(id="waiting")
        waiting.display = False
        yield waiting
        with Horizontal(id="panels"):
            yield from self.panels

    def _show_waiting(self) -> None:
        """Hide the panels still waiting for their topic's type when they would crowd the screen; name them."""
        waiting = [panel for panel in self.panels if panel.view is None and not panel.problem]
        drawn = [panel for panel in self.panels if panel not in waiting and not panel.joined]
        collapse = len(waiting) > 1 or (waiting and drawn)
        for panel in waiting:
            panel.display = not collapse
        for panel in drawn:
            panel.display = True
        line = self.query_one("#waiting", Static)
        line.display = bool(collapse)
        if collapse:
            line.update(escape(f"waiting for {len(waiting)} topic{'s' if len(waiting) != 1 else ''} to be "
                               f"published: {', '.join(panel.topic for panel in waiting)}"))

    def on_mount(self) -> None:
        """Check types and subscriptions now and every :data:`CHECK_EVERY` seconds."""
        self.set_interval(CHECK_EVERY, self.check)
        self.call_later(self.check)

    async def check(self) -> None:
        """Each panel: mount its view once its type is known, subscribe on the current node."""
        if self._checking:
            return
        self._checking = True
        try:
            node = self.node_of()
            for panel in self.panels:
                try:
                    await panel.check(node, self.type_of(panel.topic))
                except MASTER_ERRORS:  # the master went while subscribing: the next check tries again
                    await panel.stop()
            if self.is_mounted:
                self._show_waiting()
        finally:
            self._checking = False

    async def stop(self) -> None:
        """Leave the views' tools (a teleop stops its robot first), then unsubscribe every panel."""
        for view in {id(panel.view): panel.view for panel in self.panels if panel.view is not None}.values():
            stop_tools = getattr(view, "stop_tools", None)
            if stop_tools is not None:
                await stop_tools()
        await asyncio.gather(*(panel.stop() for panel in self.panels), return_exceptions=True)
