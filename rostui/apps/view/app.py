"""ViewApp: `rostui view TOPIC...`, each topic in a panel drawn by the view its type has in the registry.

The app keeps one node registered with the master (a
:class:`~rostui.models.sensors.source.ViewSource`) and the panels subscribe on
it while they are on screen.  :class:`ViewScreen` is the same grid of
panels over another app's node (the monitor's Enter).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any, ClassVar, Sequence

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.markup import escape
from textual.screen import Screen
from textual.widgets import Static

from rostui.apps.terminal import terminal_missing
from rostui.apps.view.panel import NodeOf, TypeOf, ViewGrid
from rostui.models.sensors.source import ViewSource
from rostui.models.sensors.tools2d import ToolTopics
from rostui.models.sensors.view_file import ViewSpec, write_view_file
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.keys import key_line
from rostui.apps.widgets.lifecycle import ReleasesOnExit, quit_on_signals
from rostui.core.network import master_uri_from_env
from rostui.models.master_link import MasterState, SourceState

__all__ = ["ViewApp", "ViewScreen", "app_of", "run_app", "KEYS"]

#: Key help at the bottom.
KEYS = key_line("")
#: Key help of the view opened over another app.
SCREEN_KEYS = key_line("Esc back")


class ViewApp(ReleasesOnExit, KeysApp):
    """``topics`` of the master at ``master_uri`` (ROS_MASTER_URI by default), each in a panel."""

    CSS_PATH = Path(__file__).with_name("app.tcss")
    TITLE = "rostui view"

    BINDINGS: ClassVar[list[BindingType]] = [Binding("q", "quit", "quit")]

    def __init__(self, topics: Sequence[str], *, master_uri: str | None = None, period: float = 1.0,
                 frame: str | None = None, tool_topics: ToolTopics | None = None,
                 topdown: dict[str, Any] | None = None, save: Path | None = None,
                 spec: ViewSpec | None = None) -> None:
        """``topdown`` holds more options of the top-down view (footprint, robot_frame, follow, span, centre);
        ``save``: the view file written on quit, from ``spec`` (what the command was given) and the view as it
        stands."""
        super().__init__()
        self.master_uri = master_uri_from_env(master_uri)
        self.source = ViewSource(self.master_uri, period=period, on_state=self._on_state)
        self.topics = list(dict.fromkeys(topics))
        self.save_path = save
        self.spec = spec or ViewSpec(list(self.topics), frame)
        self.saved: str = ""
        """What saving on quit did (one line: the file written, or why not)."""
        options: dict[str, object] = {"frame": frame} if frame else {}
        if tool_topics is not None:
            options["tool_topics"] = tool_topics
        options.update(topdown or {})
        self.grid = ViewGrid(self.topics, lambda: self.source.node, self.source.type_of, id="views",
                             view_options=options or None)

    def compose(self) -> ComposeResult:
        """The master line, the panels, the keys."""
        yield Static(id="status")
        yield self.grid
        yield Static(KEYS, id="keys")

    def on_mount(self) -> None:
        """Start the node."""
        quit_on_signals(self)
        self._on_state(self.source.state)
        self.run_worker(self.source.run(), group="source", exit_on_error=False)

    def _on_state(self, state: SourceState) -> None:
        if self.released:
            return
        text = state.text(marks=True)
        if state.status is MasterState.WAITING:
            text += "; start one with `rostui core` (retrying)"
        for line in self.query("#status").results(Static):
            line.update(escape(text))
            line.set_class(state.status is not MasterState.CONNECTED, "problem")

    async def release(self) -> None:
        """Write the view file (``--save``); unsubscribe, leave the master."""
        if self.save_path is not None:
            self.saved = self._save(self.save_path)
        await self.grid.stop()
        await self.source.stop()

    def current_spec(self) -> ViewSpec:
        """The view as it stands: the topics, and the top-down view's fixed frame, zoom and centre."""
        from rostui.apps.view.topdown_view import TopDownView

        spec = ViewSpec(**{**self.spec.__dict__, "topics": list(self.topics)})
        for view in self.query(TopDownView):
            viewport = view.viewport
            spec.frame = view.scene.fixed_frame or spec.frame
            if viewport is not None:
                spec.span = 2 * viewport.cols * viewport.scale
                spec.centre = (viewport.cx, viewport.cy)
            spec.follow = view.follow
            break
        return spec

    def _save(self, path: Path) -> str:
        try:
            write_view_file(self.current_spec(), path)
        except OSError as exc:
            return f"rostui view: cannot write {path}: {exc.strerror or exc}"
        return f"rostui view: saved the view to {path} (`rostui view {path}` opens it)"


class ViewScreen(Screen[None]):
    """The views of ``topics`` over another app, subscribed on its node; Escape goes back."""

    DEFAULT_CSS = """
    ViewScreen > #view-keys { height: 1; background: $panel; }
    """

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "back", "back")]

    def __init__(self, topics: Sequence[str], node_of: NodeOf, type_of: TypeOf) -> None:
        super().__init__()
        self.grid = ViewGrid(topics, node_of, type_of)

    def compose(self) -> ComposeResult:
        """The panels and the keys."""
        yield self.grid
        yield Static(SCREEN_KEYS, id="view-keys")

    async def action_back(self) -> None:
        """Escape: unsubscribe and go back."""
        await self.grid.stop()
        self.dismiss(None)

    async def on_unmount(self) -> None:
        """However the screen goes, its subscriptions go with it."""
        await self.grid.stop()


def app_of(spec: ViewSpec, *, period: float = 1.0, footprint: Any = None, save: Path | None = None,
           master_uri: str | None = None) -> ViewApp:
    """The app showing ``spec`` (``footprint``: the robot's outline, already read)."""
    defaults = ToolTopics()
    tools = ToolTopics(goal=spec.goal_topic or defaults.goal, pose=spec.pose_topic or defaults.pose,
                       cmd_vel=spec.cmd_vel_topic or defaults.cmd_vel)
    topdown: dict[str, Any] = {"footprint": footprint, "follow": spec.follow, "span": spec.span,
                               "centre": spec.centre}
    if spec.robot_frame:
        topdown["robot_frame"] = spec.robot_frame
    return ViewApp(spec.topics, master_uri=master_uri, period=period, frame=spec.frame, tool_topics=tools,
                   topdown=topdown, save=save, spec=spec)


def run_app(spec: ViewSpec, *, period: float = 1.0, footprint: Any = None, save: Path | None = None) -> int:
    """Run :class:`ViewApp` on ``spec`` in this terminal (``footprint``: its outline, already read); returns the
    exit status (1 without a TTY)."""
    if terminal_missing("rostui view", "use `rostui topic echo` without one"):
        return 1
    from rostui.apps.view.image_view import detect_graphics

    detect_graphics()  # the terminal is asked what it draws before Textual owns stdin
    app = app_of(spec, period=period, footprint=footprint, save=save)
    app.run()
    if app.saved:
        print(app.saved, file=sys.stderr)
    return app.return_code or 0
