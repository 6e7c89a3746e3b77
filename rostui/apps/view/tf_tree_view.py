"""TfTreeView: the frames of /tf and /tf_static as a tree (rqt_tf_tree, ``view_frames``) in the terminal.

Each row is a frame under its parent with the edge's broadcaster (the node that publishes it),
rate, age of the newest stamp and whether it is static. The row under the cursor is spelled
out below the table: its transform in its parent and its pose in its tree's root.

The view listens on its own node (a :class:`~rostui.models.tf.source.TfSource`) while it is
mounted, not through the panel's newest-message feed: a tree needs every message of both
topics and the name of the node that sent each.
"""

from __future__ import annotations

import math
import time
from typing import ClassVar, Any, Callable

from rich.text import Text
from textual.app import ComposeResult
from textual.widgets import DataTable, Static

from rostui.apps.view.registry import TopicView
from rostui.core.msg import foreign_version
from rostui.models.master_link import MasterState
from rostui.models.frame_budget import FrameBudget
from rostui.tools.tf.buffer import Edge, TfBuffer, TfError
from rostui.models.tf.source import TfSource
from rostui.tools.tf.transform import Transform
from rostui.models.tf.tree import TreeRow, format_age, format_rate, summary, tree_rows

__all__ = ["TfTreeView", "REFRESH_EVERY"]

REFRESH_EVERY = 0.5
"""Seconds between redraws of the table (rates and ages move even when no frame is added)."""

FILL_BATCH = 200
"""Rows added to the table at a time: a tree of thousands of frames fills in batches, the app answering between."""

FILL_PAUSE = 0.01
"""Seconds at least between two batches."""

COLUMNS = ("frame", "broadcaster", "rate", "age")
MESSAGE_COLUMNS = ("frame", "stamp")
"""The columns of one message's tree (`bag view`'s inspector): no rates, no broadcasters."""

STALE = 2.0
"""Seconds after which a dynamic edge's age is drawn as a warning."""


def _pose_text(tr: Transform) -> str:
    x, y, z = (round(float(v), 3) + 0.0 for v in tr.translation)  # rounded, + 0.0: no "-0.0"
    roll, pitch, yaw = (round(math.degrees(a), 1) + 0.0 for a in tr.rpy())
    return f"xyz [{x:.3f}, {y:.3f}, {z:.3f}]  rpy° [{roll:.1f}, {pitch:.1f}, {yaw:.1f}]"


class TfTreeView(TopicView):
    """The tf tree of the master at ``master_uri`` (the app's, else ROS_MASTER_URI).

    With ``buffer`` given the view draws that buffer and subscribes to nothing (tests,
    snapshots, a bag's transforms); ``clock`` is "now" for ages.
    """

    OWN_SUBSCRIPTIONS: ClassVar[bool] = True
    """Live, the tree subscribes to /tf and /tf_static itself (each message with its broadcaster)."""

    DEFAULT_CSS = """
    TfTreeView { height: 1fr; }
    TfTreeView > #tf-summary { height: 1; }
    TfTreeView > #tf-summary.problem { color: $error; }
    TfTreeView > DataTable { height: 1fr; }
    TfTreeView > #tf-detail { height: auto; max-height: 3; color: $text-muted; }
    """

    def __init__(self, topic: str = "/tf", *, master_uri: str | None = None, buffer: TfBuffer | None = None,
                 clock: Callable[[], float] = time.time, refresh_every: float = REFRESH_EVERY,
                 id: str | None = None, classes: str | None = None) -> None:
        super().__init__(topic, id=id, classes=classes)
        self.live = buffer is None
        self.buffer = buffer if buffer is not None else TfBuffer()
        self.clock = clock
        self.refresh_every = refresh_every
        self.master_uri = master_uri
        self.source: TfSource | None = None
        self.table: DataTable[Any] = DataTable(cursor_type="row", zebra_stripes=False, id="tf-table")
        self.summary_line = Static(id="tf-summary")
        self.detail = Static(id="tf-detail")
        self._frames: list[str] = []
        self._rows: list[TreeRow] = []
        self._shape = -1
        self._selected: str | None = None
        self._fills = 0
        self._filling = False
        self._placing = False
        self._shown: dict[int, tuple[str, ...]] = {}
        self.budget = FrameBudget()
        """The view's own CPU account: rebuilding the table of a large tree is spread out to stay within it."""
        self.one_message = False
        """True in `bag view`'s inspector: the tree of the transforms of the message shown last, no rates."""
        self._message_problems: list[str] = []
        self._message_count = 0

    @classmethod
    def for_bag(cls, topic: str, *, classes: str | None = None) -> TfTreeView:
        """The tree of one message's transforms (the message under the bag inspector's cursor); listens to nothing."""
        view = cls(topic, buffer=TfBuffer(), classes=classes)
        view.one_message = True
        return view

    def compose(self) -> ComposeResult:
        """Summary line, the table of frames, the selected frame's detail."""
        yield self.summary_line
        yield self.table
        yield self.detail

    def on_mount(self) -> None:
        """Columns; in live mode start listening; redraw now and every :data:`REFRESH_EVERY` seconds."""
        for name in MESSAGE_COLUMNS if self.one_message else COLUMNS:
            self.table.add_column(name, key=name)
        if self.live:
            from rostui.core.network import master_uri_from_env

            uri = master_uri_from_env(self.master_uri or getattr(self.app, "master_uri", None))
            self.source = TfSource(uri, node_name="rostui_tf_tree", buffer=self.buffer, clock=self.clock)
            self.run_worker(self.source.run(), group="tf-source", exit_on_error=False)
            self.set_interval(self.refresh_every, self.tick)
        self.redraw()

    async def on_unmount(self) -> None:
        """Unsubscribe and leave the master."""
        await self.stop()

    async def stop(self) -> None:
        """Stop listening (idempotent)."""
        source, self.source = self.source, None
        if source is not None:
            await source.stop()

    def show_message(self, msg: Any, received: float) -> None:
        """In a bag's inspector, the tree of ``msg``'s transforms; live, messages come through the view's own
        subscriptions (with their broadcasters) and the panel's are not needed."""
        if not self.one_message:
            return
        self.buffer.clear()
        other = foreign_version(msg)  # a bag's own version of TFMessage: not read as rostui's
        if other is not None:
            self._message_count, self._message_problems = 0, [f"{other}: not drawn"]
        else:
            self._message_count = len(msg.transforms)
            self._message_problems = self.buffer.add_message(msg, static=self.topic == "/tf_static", broadcaster="",
                                                             received=received)
        if self.is_mounted:
            self.redraw()

    def redraw(self) -> None:
        """Show the buffer now: its rows again when the tree's shape changed (the first :data:`FILL_BATCH` at
        once, the rest a batch at a time, the cursor kept on its frame), else the figures of the rows on screen."""
        if self.buffer.structure != self._shape:
            self._rebuild()
        else:
            self._refresh_shown()
        self._update_summary(self._rows)
        self._update_detail()

    def tick(self) -> None:
        """The periodic redraw: as :meth:`redraw`, but a new shape waits for the table being filled and for the
        view's CPU budget (a tree that keeps changing shape is rebuilt only as often as its share allows)."""
        if self.buffer.structure != self._shape and (self._filling or self.budget.wait() > 0):
            self._refresh_shown()
            self._update_summary(self._rows)
            return
        self.redraw()

    def _rebuild(self) -> None:
        with self.budget.spending():
            self._shape = self.buffer.structure
            rows = tree_rows(self.buffer)
            cursor = self.table.cursor_row
            if self.table.row_count and 0 <= cursor < len(self._frames):
                self._selected = self._frames[cursor]
            self._placing = True
            self._rows, self._frames = rows, [row.frame for row in rows]
            self._shown = {}
            self.table.clear()
            self._fills += 1
            self._fill(self._fills, self.clock())

    def _fill(self, fill: int, now: float) -> None:
        """Add the next batch of rows (``fill`` names the rebuild they belong to; a newer one drops them)."""
        if fill != self._fills:
            return
        with self.budget.spending():
            start = self.table.row_count
            for row in self._rows[start:start + FILL_BATCH]:
                self.table.add_row(*self._cells(row, now), key=row.frame)
            self._filling = self.table.row_count < len(self._rows)
            self._place_cursor()
        if self._filling:
            self.set_timer(max(FILL_PAUSE, self.budget.wait()), lambda: self._fill(fill, self.clock()))

    def _place_cursor(self) -> None:
        """The cursor back on the frame it was on (once its row is in), or on a message's first transform."""
        if not self._placing:
            return
        selected = self._selected
        if selected in self._frames and not (self.one_message and self.buffer.edge(selected) is None):
            index = self._frames.index(selected)
            if index < self.table.row_count:
                self.table.move_cursor(row=index, animate=False)
                self._placing = False
        elif self.one_message and len(self._frames) > 1:
            if self.table.row_count > 1:
                self.table.move_cursor(row=1, animate=False)  # the message's first transform, not its root
                self._placing = False
        else:
            self._placing = False

    def _cells(self, row: TreeRow, now: float) -> list[Text]:
        label = Text()
        label.append(row.prefix, style="dim")
        label.append(row.frame, style="bold" if row.depth == 0 else "")
        if row.in_loop:
            label.append("  (in a loop)", style="red")
        edge = row.edge
        if self.one_message:
            return [label, Text(f"{edge.latest.stamp:.6f}" if edge is not None else "")]
        return [label, *self._figures(edge, now)]

    def _figures(self, edge: Edge | None, now: float) -> list[Text]:
        """The broadcaster, rate and age cells of a row."""
        rate = format_rate(edge)
        return [
            Text(edge.broadcaster if edge else ""),
            Text(rate, style="cyan" if rate == "static" else ""),
            Text(format_age(edge, now), style="yellow" if edge and not edge.static and edge.age(now) > STALE
                 else ""),
        ]

    def _refresh_shown(self) -> None:
        """New broadcasters, rates and ages for the rows on screen (the others are redrawn when scrolled to)."""
        if self.one_message or not self.table.row_count:
            return
        now = self.clock()
        first = max(0, int(self.table.scroll_offset.y))
        for index in range(first, min(self.table.row_count, first + self.table.size.height + 1)):
            row = self._rows[index]
            edge = self.buffer.edge(row.frame)
            cells = self._figures(edge, now)
            key = tuple(cell.plain for cell in cells)
            if self._shown.get(index) == key:
                continue
            self._shown[index] = key
            for column, cell in zip(COLUMNS[1:], cells):
                self.table.update_cell(row.frame, column, cell)

    def _update_summary(self, rows: list[TreeRow]) -> None:
        source = self.source
        problem = False
        if source is not None and source.state.status is not MasterState.CONNECTED:
            text = source.state.text(marks=True)
            problem = True
        elif self.one_message:
            count = self._message_count
            text = f"{count} transform{'' if count == 1 else 's'} in this message: {summary(self.buffer, rows)}"
            if self._message_problems:
                text += f"  ·  {self._message_problems[-1]}"
                problem = True
        elif not self.buffer.frames():
            text = "waiting for transforms on /tf and /tf_static"
        else:
            text = summary(self.buffer, rows)
        if source is not None and source.problems:
            text += f"  ·  {source.problems[-1]}"
            problem = True
        self.summary_line.update(Text(text))
        self.summary_line.set_class(problem, "problem")

    def _update_detail(self) -> None:
        row = self.table.cursor_row
        if not 0 <= row < len(self._frames):
            self.detail.update("")
            return
        frame = self._frames[row]
        edge = self.buffer.edge(frame)
        lines: list[str] = []
        if edge is not None:
            count = "" if self.one_message else f"  ({edge.count} message{'' if edge.count == 1 else 's'})"
            lines.append(f"{frame} in {edge.parent}: {_pose_text(edge.latest.transform)}{count}")
            try:
                root = self.buffer.chain(frame)[-1]
                if root != edge.parent:
                    lines.append(f"{frame} in {root}: {_pose_text(self.buffer.lookup_transform(root, frame).transform)}")
            except TfError as exc:
                lines.append(str(exc))
        else:
            kids = self.buffer.children(frame)
            lines.append(f"{frame}: root, {len(kids)} child frame{'' if len(kids) == 1 else 's'}")
        self.detail.update(Text("\n".join(lines)))

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        """The cursor moved: spell out the new frame."""
        self._update_detail()
