"""TopDownApp: one :class:`~rostui.apps.view.topdown_view.TopDownView` of live topics, fed by a MonitorSource.

The app subscribes (md5 ``*``, no decoding on arrival) to its topics once
they have publishers, and every 1/20 s hands the view the newest message of
each topic that has a new one, decoded then: messages that came in between
are dropped, never queued.  ``q`` quits, ``?`` lists the keys.
"""

from __future__ import annotations

import time
from typing import Any, ClassVar, Sequence

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.widgets import Static

from rostui.apps.terminal import terminal_missing
from rostui.apps.view.topdown_view import TopDownView
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core.msg import MessageError
from rostui.core.network import master_uri_from_env
from rostui.models.master_link import SourceState, failure_reason
from rostui.models.monitor.source import MonitorSource
from rostui.models.sensors.scene2d import Lookup, same_frame_only

__all__ = ["TopDownApp", "run_app"]


class TopDownApp(ReleasesOnExit, KeysApp):
    """``topics`` from above in ``frame`` (None: the first message's frame), live from the master."""

    TITLE = "rostui view"
    CSS = """
    #status { height: 1; background: $panel; }
    """
    BINDINGS: ClassVar[list[BindingType]] = [Binding("q", "quit", "quit")]

    def __init__(self, topics: Sequence[str], *, frame: str | None = None, lookup: Lookup = same_frame_only,
                 master_uri: str | None = None, period: float = 1.0) -> None:
        super().__init__()
        self.topics = list(dict.fromkeys(topics))
        self.master_uri = master_uri_from_env(master_uri)
        self.source = MonitorSource(self.master_uri, period=period, on_state=self._on_state)
        self.frame = frame
        self.lookup = lookup
        self._fed: dict[str, Any] = {}
        self._state = ""

    def compose(self) -> ComposeResult:
        """The view, then a status line."""
        yield TopDownView(topics=self.topics, frame=self.frame, lookup=self.lookup, id="topdown")
        yield Static(id="status")

    @property
    def view(self) -> TopDownView:
        """The top-down view."""
        return self.query_one(TopDownView)

    def on_mount(self) -> None:
        """Subscribe, start feeding the view, focus it."""
        quit_on_signals(self)
        self.view.focus()
        self.source.want(self.topics)
        self.run_worker(self.source.run(), group="source", exit_on_error=False)
        self.set_interval(1.0 / TopDownView.FRAME_RATE, self.feed)
        self.set_interval(1.0, self.update_status)

    def _on_state(self, state: SourceState) -> None:
        self._state = state.text(marks=True)

    def feed(self) -> None:
        """Hand the view the newest message of each topic that has a new one."""
        for topic in self.topics:
            try:
                msg = self.source.latest(topic)
            except MessageError as exc:
                self._state = f"{topic}: cannot decode: {failure_reason(exc)}"
                continue
            if msg is not None and self._fed.get(topic) is not msg:
                self._fed[topic] = msg
                self.view.show_topic_message(topic, msg, time.time())

    def update_status(self) -> None:
        """Master state and, per topic, its rate."""
        parts = [self._state]
        for topic in self.topics:
            stats = self.source.stats(topic)
            rate = stats.sample().rate if stats is not None else None
            shown = self.view.scene.received(topic)
            parts.append(f"{topic} {rate:.1f} Hz, {shown} drawn" if rate is not None else f"{topic} no messages")
        self.query_one("#status", Static).update("   ".join(p for p in parts if p))

    async def release(self) -> None:
        """Unsubscribe and leave the master."""
        await self.source.stop()


def run_app(topics: Sequence[str], *, frame: str | None = None) -> int:
    """Run :class:`TopDownApp` in this terminal; returns the exit status (1 without a TTY)."""
    if terminal_missing("rostui view", "use `rostui topic echo` without one"):
        return 1
    app = TopDownApp(topics, frame=frame)
    app.run()
    return app.return_code or 0
