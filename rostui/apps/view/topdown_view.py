"""TopDownView: laser scans, odometry, paths, poses, occupancy grids and point clouds from above, in braille.

Several topics share one view and one fixed frame (:class:`~rostui.models.sensors.scene2d.Scene2D`
does the geometry).  The widget's first row is the legend (each topic in its
colour, with a note when it is not drawn), the last row a scale bar, the fixed
frame and the grid spacing; the rows between are the canvas, 2 x 4 braille dots
per cell.  Keys: ``+``/``-`` zoom, arrows pan, ``0`` back to the frame's origin,
``c`` fits everything drawn.

Only the newest message of each topic is kept; the picture is redrawn on a
timer at most :attr:`TopDownView.FRAME_RATE` times a second, and only when a
message came, tf changed or the view moved.

In `rostui view` the first top-down topic's panel holds the view and every
other top-down topic joins it (:attr:`TopDownView.SHARED`).  Without a given
``lookup`` the view listens to /tf and /tf_static on its own node while it is
mounted (a :class:`~rostui.models.tf.source.TfSource`), and ``f`` steps the
fixed frame through every frame tf and the messages name.
"""

from __future__ import annotations

import math
import time
from typing import Any, Callable, ClassVar

import numpy as np
from rich.segment import Segment
from rich.style import Style
from textual.binding import Binding, BindingType
from textual.geometry import Region
from textual.strip import Strip

from rostui.apps.view.feed import Rate
from rostui.apps.view.registry import TopicView
from rostui.apps.widgets.terminal_colors import color_system, shown_in, style_rgb
from rostui.models.contrast import RGB, keep_hue
from rostui.models.sensors.canvas2d import BRAILLE_BASE, Viewport
from rostui.models.sensors.pose2d import Points
from rostui.models.sensors.scene2d import Drawing, Lookup, Scene2D, same_frame_only
from rostui.core.rostime import Time
from rostui.models.sensors.pose2d import Pose2D
from rostui.models.sensors.tf_lookup import buffer_lookup
from rostui.models.sensors.tools2d import (Tool, ToolSender, ToolTopics, goal_message, initial_pose_message,
                                           twist_message)
from rostui.tools.tf.buffer import TfBuffer
from rostui.models.tf.source import TfSource

__all__ = ["TopDownView", "TOPIC_COLORS", "DEFAULT_SPAN"]

#: Topic colours in the order topics are added (then round again).
TOPIC_COLORS: tuple[RGB, ...] = ((255, 80, 80), (80, 220, 80), (90, 160, 255), (255, 200, 40), (230, 100, 255),
                                 (40, 220, 220), (255, 150, 60), (200, 200, 200))

#: The grid's colour: dim, under every topic.
GRID_COLOR: RGB = (90, 90, 90)

#: Metres across the canvas before any zoom.
DEFAULT_SPAN = 10.0

#: The character of each braille dot pattern (no dots: a space).
GLYPHS = np.array([" "] + [chr(BRAILLE_BASE + bits) for bits in range(1, 256)])

#: Each + or - zooms by this factor.
ZOOM_STEP = 1.5

#: The layer of the robot's footprint (given with --footprint), named as the legend shows it.
FOOTPRINT = "(footprint)"

#: Seconds the status line says what was sent.
SENT_SHOWN = 5.0

#: Each a or d turns the cursor by this much (radians).
TURN_STEP = math.radians(15)

#: Arrow keys in teleop: (forward, turn) in units of the teleop speeds.
DRIVE = {"up": (1.0, 0.0), "down": (-1.0, 0.0), "left": (0.0, 1.0), "right": (0.0, -1.0)}


class TopDownView(TopicView, can_focus=True):
    """A top-down picture of ``topics`` in ``frame`` (None: the first message's frame).

    ``lookup(target, source)`` gives the pose of frame ``source`` in ``target``;
    None: tf from the master at ``master_uri`` (ROS_MASTER_URI by default),
    listened to while the view is mounted in a `rostui view` panel (elsewhere,
    as in the bag inspector, only messages in the fixed frame are drawn).
    :attr:`frames` counts the frames drawn; the status line shows messages
    received and frames drawn per second unless ``show_rates`` is False.
    """

    #: Every top-down topic of a `rostui view` joins the first one's view (see :meth:`add_topic`).
    SHARED: ClassVar[bool] = True
    #: Keyword options `rostui view` passes through (``--frame``).
    OPTIONS: ClassVar[tuple[str, ...]] = ("frame", "tool_topics", "footprint", "robot_frame", "follow", "span",
                                          "centre")

    DEFAULT_CSS = """
    TopDownView {
        width: 1fr;
        height: 1fr;
        background: $background;
    }
    """

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("plus,equals_sign", "zoom(1)", "zoom in"),
        Binding("minus", "zoom(-1)", "zoom out"),
        Binding("left", "pan(-1,0)", "pan left", show=False),
        Binding("right", "pan(1,0)", "pan right", show=False),
        Binding("up", "pan(0,1)", "pan up", show=False),
        Binding("down", "pan(0,-1)", "pan down", show=False),
        Binding("0", "origin", "frame origin"),
        Binding("c", "fit", "fit all"),
        Binding("f", "next_frame", "fixed frame"),
        Binding("g", "tool('goal')", "2D nav goal"),
        Binding("p", "tool('pose')", "2D pose estimate"),
        Binding("t", "tool('teleop')", "teleop"),
        Binding("o", "follow", "follow the robot"),
        Binding("a", "turn(1)", "turn left", show=False),
        Binding("d", "turn(-1)", "turn right", show=False),
        Binding("space", "stop", "stop", show=False),
        Binding("enter", "confirm", "send", show=False),
        Binding("escape", "cancel", "leave the mode", show=False),
    ]

    FRAME_RATE = 20.0

    def __init__(self, topic: str | None = None, *, topics: tuple[str, ...] | list[str] = (),
                 frame: str | None = None, lookup: Lookup | None = None, master_uri: str | None = None,
                 show_rates: bool = True, tool_topics: ToolTopics | None = None, footprint: Points | None = None,
                 robot_frame: str = "base_link", follow: bool = False, span: float | None = None,
                 centre: tuple[float, float] | None = None, id: str | None = None, classes: str | None = None) -> None:
        names = ([topic] if topic else []) + [t for t in topics if t != topic]
        super().__init__(names[0] if names else "", id=id, classes=classes)
        self.tf_buffer: TfBuffer | None = None
        self.tf_source: TfSource | None = None
        self.master_uri = master_uri
        self._tf_changes = 0
        if lookup is None:
            self.tf_buffer = TfBuffer()
            lookup = buffer_lookup(self.tf_buffer)
        self.scene = Scene2D(names, frame, lookup)
        self.robot_frame = robot_frame.lstrip("/") or "base_link"
        """The robot's frame: where its footprint is drawn and what follow mode (``o``) keeps centred."""
        if footprint is not None:
            self.scene.set_drawing(FOOTPRINT, Drawing(self.robot_frame, polyline=footprint))
        self.follow = follow
        self.span = span if span is not None and span > 0 else DEFAULT_SPAN
        """Metres across the canvas at the starting zoom (``0`` comes back to it)."""
        self.centre = centre or (0.0, 0.0)
        """Where the view starts centred (``0`` comes back to it)."""
        self._view: Viewport | None = None
        self._drawn: tuple[int, int, str | None, Viewport | None, int, int, int] = (-1, -1, None, None, 0, 0, 0)
        self._strips: list[Strip] = []
        self._rows: list[str] = []
        self._owners: list[list[int]] = []
        self._layer_rgbs: list[RGB] = []
        self._keys: list[tuple[str, tuple[int, ...]]] = []
        self.frames = 0
        self.tool: Tool | None = None
        """The cursor's mode (None: the arrows pan)."""
        self.tool_topics = tool_topics or ToolTopics()
        self.sender: ToolSender | None = None
        self.last_sent = ""
        """What the last send did, in one line (shown on the status line)."""
        self._tool_changes = 0
        self._sent_at = 0.0
        self._press: tuple[float, float] | None = None
        self.one_message = False
        """True in the bag inspector: each message is shown alone (see :meth:`for_bag`)."""
        self.show_rates = show_rates
        self.received_rate = Rate()
        self.drawn_rate = Rate()

    # -- feeding ---------------------------------------------------------------------
    def add_topic(self, topic: str) -> None:
        """Draw ``topic`` too, in the next colour."""
        self.scene.add(topic)

    @classmethod
    def for_bag(cls, topic: str, *, classes: str | None = None) -> TopDownView:
        """The view of one recorded message at a time: a marker message shows its own markers only, not those
        the messages stepped through before it added."""
        view = cls(topic, classes=classes)
        view.one_message = True
        return view

    def dropped(self, topic: str, count: int) -> None:
        """Marker messages of ``topic`` dropped before they were shown: the legend says how many."""
        store = self.scene.markers(topic)
        if store is not None and store.dropped != count:
            store.dropped = count
            store.generation += 1
            self.scene.generation += 1

    def show_message(self, msg: Any, received: float = 0.0) -> None:
        """``msg`` is the newest message of this view's first topic."""
        self.show_topic_message(self.topic, msg, received)

    def show_topic_message(self, topic: str, msg: Any, received: float = 0.0) -> None:
        """``msg`` is the newest message of ``topic`` (the one before it is dropped)."""
        self.scene.offer(topic, msg, received, alone=self.one_message)
        self.received_rate.add(time.time())

    # -- what tests and tools read -----------------------------------------------------
    @property
    def viewport(self) -> Viewport | None:
        """The canvas' viewport (None before the widget has a size)."""
        return self._view

    @property
    def canvas_top(self) -> int:
        """The widget row of the canvas' first row (below the legend)."""
        return 1

    def row_text(self, y: int) -> str:
        """The text of widget row ``y`` as last drawn."""
        return self._rows[y] if 0 <= y < len(self._rows) else ""

    def cell_topic(self, col: int, row: int) -> str | None:
        """The topic whose colour canvas cell (``col``, ``row``) was drawn in: "" for the grid, None when empty."""
        if not (0 <= row < len(self._owners) and 0 <= col < len(self._owners[row])):
            return None
        layer = self._owners[row][col]
        if layer < 0:
            return None
        topics = self.scene.topics
        if layer > len(topics):
            return self.scene.layer_colors[layer - 1 - len(topics)][0]
        return "" if layer == 0 else topics[layer - 1]

    def cell_color(self, col: int, row: int) -> RGB | None:
        """The colour canvas cell (``col``, ``row``) was drawn in (None when empty)."""
        if not (0 <= row < len(self._owners) and 0 <= col < len(self._owners[row])):
            return None
        layer = self._owners[row][col]
        return None if layer < 0 else self._layer_rgbs[layer]

    def topic_color(self, topic: str) -> RGB:
        """The colour ``topic`` is drawn in (its palette colour, made readable on the background)."""
        index = self.scene.topics.index(topic)
        base = TOPIC_COLORS[index % len(TOPIC_COLORS)]
        shown = shown_in(color_system(self.app.console.color_system if self.is_mounted else None))
        return keep_hue(base, [self._background()], shown)

    # -- keys -------------------------------------------------------------------------
    def action_zoom(self, direction: int) -> None:
        """Zoom in (1) or out (-1) about the centre."""
        if self._view is not None:
            self._view = self._view.zoomed(ZOOM_STEP if direction > 0 else 1 / ZOOM_STEP)
            self.draw_frame()

    def action_pan(self, right: int, up: int) -> None:
        """Move the view an eighth of the canvas; with a goal or pose cursor, move the cursor a cell; in teleop,
        drive."""
        if self.tool is Tool.TELEOP:
            self._drive(*DRIVE[{(0, 1): "up", (0, -1): "down", (-1, 0): "left", (1, 0): "right"}[(right, up)]])
            return
        if self.tool is not None and self._view is not None and self.scene.cursor is not None:
            cursor = self.scene.cursor
            self._set_cursor(Pose2D(cursor.x + right * 2 * self._view.scale, cursor.y + up * 4 * self._view.scale,
                                    cursor.yaw))
            return
        if self._view is not None:
            self.follow = False  # panning by hand ends following the robot
            step_x, step_y = max(1, self._view.cols // 8), max(1, self._view.rows // 8)
            self._view = self._view.panned(right * step_x, up * step_y)
            self.draw_frame()

    def action_origin(self) -> None:
        """Back to the fixed frame's origin at the starting zoom."""
        if self._view is not None:
            self._view = self._home(self._view.cols, self._view.rows)
            self.draw_frame()

    def action_next_frame(self) -> None:
        """Make the next frame (by name) that tf or a message names the fixed frame."""
        frames = set(self.tf_buffer.frames()) if self.tf_buffer is not None else set()
        for topic in self.scene.topics:
            drawing = self.scene.drawing(topic)
            if drawing is not None and drawing.frame:
                frames.add(drawing.frame.lstrip("/"))
            store = self.scene.markers(topic)
            frames.update(shape.frame.lstrip("/") for _, shape, _ in (store.held() if store is not None else ()))
        frames.discard("")
        if not frames:
            return
        ordered = sorted(frames)
        current = self.scene.fixed_frame
        self.scene.set_fixed_frame(ordered[(ordered.index(current) + 1) % len(ordered)] if current in ordered
                                   else ordered[0])
        self.draw_frame()

    # -- the tools: goal, pose estimate, teleop -------------------------------------------
    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        """The mode's keys (Enter, Escape, a, d, space) only work in a mode; elsewhere they pass on."""
        if action in ("confirm", "cancel", "turn", "stop"):
            return self.tool is not None
        if action == "tool":
            return not self.one_message  # a recorded message in bag view: nothing to send from
        return True

    def action_tool(self, name: str) -> None:
        """g, p, t: place a goal or a pose estimate with the cursor, or drive; the same key again leaves."""
        tool = {"goal": Tool.GOAL, "pose": Tool.POSE, "teleop": Tool.TELEOP}[name]
        if self.tool is tool:
            self.action_cancel()
            return
        if self.tool is Tool.TELEOP:
            self._drive(0.0, 0.0)
        self.tool = tool
        self.run_worker(self._advertise(tool), group="topdown-send", exit_on_error=False)
        if tool is Tool.TELEOP:
            self.scene.cursor = None
        elif self.scene.cursor is None and self._view is not None:
            self.scene.cursor = Pose2D(*self._view.cell_centre(self._view.cols // 2, self._view.rows // 2), 0.0)
        self._tool_changed()

    def action_turn(self, direction: int) -> None:
        """a, d: turn the cursor's heading 15 degrees left or right (in teleop: turn the robot)."""
        if self.tool is Tool.TELEOP:
            self._drive(0.0, float(direction))
        elif self.scene.cursor is not None:
            c = self.scene.cursor
            yaw = math.atan2(math.sin(c.yaw + direction * TURN_STEP), math.cos(c.yaw + direction * TURN_STEP))
            self._set_cursor(Pose2D(c.x, c.y, yaw))

    def action_stop(self) -> None:
        """space in teleop: stop the robot."""
        if self.tool is Tool.TELEOP:
            self._drive(0.0, 0.0)

    def action_confirm(self) -> None:
        """Enter: send the goal or the pose estimate at the cursor, in the fixed frame."""
        cursor, frame = self.scene.cursor, self.scene.fixed_frame
        if self.tool not in (Tool.GOAL, Tool.POSE) or cursor is None:
            return
        if not frame:
            self._say_sent("no fixed frame yet: nothing sent")
            return
        make = goal_message if self.tool is Tool.GOAL else initial_pose_message
        tool = self.tool
        what = (f"{tool.value} x {cursor.x:.2f} y {cursor.y:.2f} θ {math.degrees(cursor.yaw):.0f}° "
                f"({frame})")
        self.run_worker(self._send(tool, lambda now: make(frame, cursor, now), what), group="topdown-send",
                        exit_on_error=False)
        self.tool = None
        self.scene.cursor = None
        self._tool_changed()

    def action_cancel(self) -> None:
        """Escape: leave the mode without sending (teleop sends a stop first)."""
        if self.tool is Tool.TELEOP:
            self._drive(0.0, 0.0)
        self.tool = None
        self.scene.cursor = None
        self._tool_changed()

    def on_mouse_down(self, event: Any) -> None:
        """With a goal or pose cursor: a click puts it there (a drag then gives its heading)."""
        place = self._world_at(event.x, event.y)
        if self.tool in (Tool.GOAL, Tool.POSE) and place is not None:
            self._set_cursor(Pose2D(place[0], place[1], self.scene.cursor.yaw if self.scene.cursor else 0.0))
            self._press = place

    def on_mouse_up(self, event: Any) -> None:
        """The end of a drag: the cursor faces from where the button went down to here."""
        start, self._press = self._press, None
        place = self._world_at(event.x, event.y)
        if self.tool in (Tool.GOAL, Tool.POSE) and start is not None and place is not None and place != start:
            self._set_cursor(Pose2D(start[0], start[1], math.atan2(place[1] - start[1], place[0] - start[0])))

    def _world_at(self, x: int, y: int) -> tuple[float, float] | None:
        view = self._view
        row = y - self.canvas_top
        if view is None or not (0 <= x < view.cols and 0 <= row < view.rows):
            return None
        return view.cell_centre(x, row)

    def _set_cursor(self, cursor: Pose2D) -> None:
        self.scene.cursor = cursor
        self._tool_changed()

    def _tool_changed(self) -> None:
        self._tool_changes += 1
        self.draw_frame()

    def _say_sent(self, text: str) -> None:
        self.last_sent, self._sent_at = text, time.monotonic()
        self._tool_changed()

    def _drive(self, forward: float, turn: float) -> None:
        twist = twist_message(forward, turn)
        self.run_worker(self._send(Tool.TELEOP, lambda now: twist,
                                   f"{twist.linear.x:+.1f} m/s {twist.angular.z:+.1f} rad/s"),
                        group="topdown-send", exit_on_error=False)

    def _listeners(self, tool: Tool) -> str:
        count = self.sender.connections(tool) if self.sender is not None else 0
        return f"{count} sub{'' if count == 1 else 's'}"

    def _tool_sender(self) -> ToolSender | None:
        node = self._node()
        if node is None:
            self._say_sent("not sent: no master answers" if self._in_panel()
                           else "not sent: no node here (the tools send from `rostui view`)")
            return None
        if self.sender is None or self.sender.node is not node:
            self.sender = ToolSender(node, self.tool_topics)
        return self.sender

    async def _advertise(self, tool: Tool) -> None:
        sender = self._tool_sender()
        try:
            if sender is not None:
                await sender.advertise(tool)
        except Exception as exc:  # the master or the node went away: said on the status line
            self._say_sent(f"cannot advertise {self.tool_topics.of(tool)}: {exc}")

    async def _send(self, tool: Tool, make: Callable[[Time], Any], what: str) -> None:
        """Publish what ``make(now)`` makes (``now`` in ROS time) on ``tool``'s topic, and say so, with how many
        subscribers had it."""
        sender = self._tool_sender()
        if sender is None:
            return
        try:
            await sender.advertise(tool)
            topic = await sender.send(tool, make(sender.now()))
        except Exception as exc:  # the master or the node went away: said on the status line
            self._say_sent(f"not sent: {exc}")
            return
        count = sender.connections(tool)
        heard = "nobody subscribes: nobody got it" if count == 0 else f"{count} sub{'' if count == 1 else 's'}"
        self._say_sent(f"sent {what} on {topic} ({heard})")

    def _node(self) -> Any:
        """The node of the `rostui view` panel holding this view (None elsewhere)."""
        from rostui.apps.view.panel import ViewPanel

        for node in self.ancestors:
            if isinstance(node, ViewPanel):
                return node.feed.node
        return None

    def action_fit(self) -> None:
        """Centre and zoom so that everything drawn shows."""
        if self._view is not None:
            self._view = self._view.fitting(self.scene.world_points())
            self.draw_frame()

    # -- Textual hooks -------------------------------------------------------------------
    def on_mount(self) -> None:
        """Start the frame timer; take the keys unless another widget has them; listen to tf (see the class)."""
        self.set_interval(1.0 / self.FRAME_RATE, self.draw_frame)
        if self.screen.focused is None:
            self.focus()
        if self.tf_buffer is not None and not self._in_panel():
            self.tf_buffer = None  # a recorded message (the bag inspector): drawn in its own frame, no live tf
            self.scene.lookup = same_frame_only
        if self.tf_buffer is not None:
            from rostui.core.network import master_uri_from_env

            uri = master_uri_from_env(self.master_uri or getattr(self.app, "master_uri", None))
            self.tf_source = TfSource(uri, node_name="rostui_view_tf", buffer=self.tf_buffer,
                                      on_change=self._tf_changed, clock=time.time)
            self.run_worker(self.tf_source.run(), group="topdown-tf", exit_on_error=False)

    def _in_panel(self) -> bool:
        """True inside a `rostui view` panel (live topics), False elsewhere (the bag inspector)."""
        from rostui.apps.view.panel import ViewPanel

        return any(isinstance(node, ViewPanel) for node in self.ancestors)

    def _tf_changed(self) -> None:
        self._tf_changes += 1

    async def on_unmount(self) -> None:
        """Stop listening to tf; unadvertise what the tools advertised."""
        source, self.tf_source = self.tf_source, None
        if source is not None:
            await source.stop()
        await self.stop_tools()

    async def stop_tools(self) -> None:
        """Leave the tools: in teleop, stop the robot first (as teleop keyboards do on exit); unadvertise."""
        sender, self.sender = self.sender, None
        if sender is not None:
            if self.tool is Tool.TELEOP:
                try:  # written to each subscriber's socket now; closing the connection flushes it
                    await sender.send(Tool.TELEOP, twist_message(0.0, 0.0))
                except Exception:  # the node or the master went first: nothing more to say to the robot
                    pass
            await sender.close()
        self.tool = None

    def on_resize(self) -> None:
        """Keep centre and scale over the new size, and redraw at once."""
        self.draw_frame()

    def render_line(self, y: int) -> Strip:
        """Line API: the stored strip of row ``y``."""
        if not self._strips or len(self._strips) != self.size.height:
            self.draw_frame()
        if 0 <= y < len(self._strips):
            return self._strips[y]
        return Strip.blank(self.size.width)

    # -- drawing -------------------------------------------------------------------------
    def _home(self, cols: int, rows: int) -> Viewport:
        return Viewport(cols, rows, self.centre[0], self.centre[1], self.span / max(1, 2 * cols))

    def action_follow(self) -> None:
        """o: keep the robot's frame in the middle of the view (again: stop)."""
        self.follow = not self.follow
        self._tool_changed()

    def _followed(self, view: Viewport) -> Viewport:
        """``view`` centred on the robot's frame when following it (unchanged when tf has no transform yet)."""
        if not self.follow or self.scene.fixed_frame is None:
            return view
        where = self.scene.transform(Drawing(self.robot_frame))
        if where is None:
            return view
        x, y = (float(v) for v in where.offset)
        if (x, y) == (view.cx, view.cy):
            return view
        return Viewport(view.cols, view.rows, x, y, view.scale)

    def _background(self) -> RGB:
        rgb = style_rgb(self.rich_style.bgcolor, foreground=False) if self.is_mounted else None
        return rgb or (0, 0, 0)

    def draw_frame(self) -> bool:
        """Redraw when a message came, the view moved or the size changed; True if it did."""
        width, height = self.size.width, self.size.height
        cols, rows = width, max(0, height - 2)
        if self._view is None:
            if cols <= 0:
                return False
            self._view = self._home(cols, rows)
        elif (self._view.cols, self._view.rows) != (cols, rows):
            # Not moved since it opened (its first size may be a passing one, as when panels join this
            # view): the starting zoom for the new size.  Moved by the user: the same centre and scale.
            at_home = self._view == self._home(self._view.cols, self._view.rows)
            self._view = self._home(cols, rows) if at_home else self._view.resized(cols, rows)
        self.scene.expire(time.time())
        self._view = self._followed(self._view)
        state = (self.scene.generation, self._tf_changes, self.scene.fixed_frame, self._view, width, height,
                 self._tool_changes)
        if state == self._drawn and self._strips:
            self._update_status(self._view, width, height)
            return False
        resized = (width, height) != self._drawn[4:6]
        self._drawn = state
        self.drawn_rate.add(time.time())
        old = self._keys
        self._draw(self._view, width, height)
        self.frames += 1
        if resized or len(old) != len(self._keys):
            self.refresh()
        else:
            for y, (before, after) in enumerate(zip(old, self._keys)):
                if before != after:  # only rows that changed go to the terminal
                    self.refresh(Region(0, y, width, 1))
        return True

    def _update_status(self, view: Viewport, width: int, height: int) -> None:
        """Rewrite only the status line when its text (the rates) changed."""
        if height < 2 or len(self._strips) != height:
            return
        status = self._status(view)
        if status != self._rows[-1]:
            self._rows[-1] = status
            self._keys[-1] = (status, ())
            self._strips[-1] = Strip([Segment(status, self.rich_style)]).crop_extend(0, width, self.rich_style)
            self.refresh(Region(0, height - 1, width, 1))

    def _draw(self, view: Viewport, width: int, height: int) -> None:
        base = self.rich_style
        canvas = self.scene.render(view) if view.rows > 0 and view.cols > 0 else None
        shown = shown_in(color_system(self.app.console.color_system if self.is_mounted else None))
        self._layer_rgbs = [GRID_COLOR] + [self.topic_color(t) for t in self.scene.topics]
        self._layer_rgbs += [keep_hue(rgb, [self._background()], shown) for _, rgb in self.scene.layer_colors]
        styles = [base + Style(color="rgb({},{},{})".format(*rgb)) for rgb in self._layer_rgbs]
        texts: list[str] = []
        strips: list[Strip] = []
        legend = self._legend(styles, base)
        texts.append("".join(s.text for s in legend))
        strips.append(Strip(legend).crop_extend(0, width, base))
        if canvas is not None:
            bits, top = canvas.compose()
            chars = GLYPHS[bits]
            for label in self.scene.labels:
                end = min(label.col + len(label.text), view.cols)
                chars[label.row, label.col:end] = list(label.text[:end - label.col])
                top[label.row, label.col:end] = label.layer
            self._owners = top.tolist()
            for r in range(view.rows):
                line = "".join(chars[r])
                texts.append(line)
                strips.append(Strip(self._runs(line, self._owners[r], styles, base), width))
        else:
            self._owners = []
        if height >= 2:
            status = self._status(view)
            texts.append(status)
            strips.append(Strip([Segment(status, base)]).crop_extend(0, width, base))
        owners = [()] + [tuple(row) for row in self._owners] + [()]
        self._rows, self._strips = texts[:height], strips[:height]
        self._keys = [(text, owner) for text, owner in zip(self._rows, owners)]

    def _runs(self, line: str, owner_list: list[int], styles: list[Style], base: Style) -> list[Segment]:
        """Segments of equal colour along one canvas row."""
        segments: list[Segment] = []
        start = 0
        for i in range(1, len(line) + 1):
            if i == len(line) or owner_list[i] != owner_list[start]:
                layer = owner_list[start]
                segments.append(Segment(line[start:i], styles[layer] if layer >= 0 else base))
                start = i
        return segments

    def _legend(self, styles: list[Style], base: Style) -> list[Segment]:
        segments: list[Segment] = []
        for i, topic in enumerate(self.scene.topics, start=1):
            note = self.scene.note(topic)
            segments.append(Segment("■ ", styles[i]))
            segments.append(Segment(topic, styles[i]))
            if note:
                segments.append(Segment(f" ({note})", base + Style(italic=True)))
            segments.append(Segment("  ", base))
        return segments

    def _status(self, view: Viewport) -> str:
        if self.tool is Tool.TELEOP:
            sent = self.last_sent.split(" on ")[0] if self.last_sent.startswith("sent ") else "↑↓←→ drive"
            return (f"TELEOP → {self.tool_topics.cmd_vel} ({self._listeners(Tool.TELEOP)})  {sent}  space stop  "
                    "Esc leave")
        if self.tool is not None and self.scene.cursor is not None:
            c = self.scene.cursor
            topic = self.tool_topics.of(self.tool)
            return (f"{'GOAL' if self.tool is Tool.GOAL else 'POSE'} {c.x:.2f},{c.y:.2f} {math.degrees(c.yaw):.0f}° "
                    f"→ {topic} ({self._listeners(self.tool)})  Enter send  Esc cancel  arrows click a d move")
        if self.last_sent and time.monotonic() - self._sent_at < SENT_SHOWN:
            return self.last_sent
        step = self.scene.grid_step(view)
        cells = max(2, round(step / (2 * view.scale)))
        metres = f"{step:g} m" if step >= 1 else f"{step * 100:g} cm"
        frame = self.scene.fixed_frame or "(waiting for a message)"
        where = f"following {self.robot_frame}" if self.follow else f"centre {view.cx:.2f}, {view.cy:.2f}"
        text = f"├{'─' * (cells - 2)}┤ {metres}   frame {frame}   {where}"
        if self.show_rates:
            now = time.time()
            text += f"   {self.received_rate.per_second(now):.1f} msg/s ({self.drawn_rate.per_second(now):.1f} drawn)"
        return text
