"""The expanded view: live message trees of the expanded topics, and sparklines of rate and bandwidth."""

from __future__ import annotations

from typing import Iterable, Sequence

from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Vertical
from textual.markup import escape
from textual.widgets import Static, Tree
from textual.widgets.tree import TreeNode

from rostui.models.monitor.rows import bandwidth_text, rate_text
from rostui.models.monitor.tree import FieldItem

__all__ = ["MessageTree", "Charts", "TopicKey", "Line"]


class Line(Static):
    """A text of fixed height that repaints only when its text changes, without laying the screen out again."""

    def __init__(self, text: str = "", *, id: str | None = None, classes: str | None = None) -> None:
        super().__init__(text, id=id, classes=classes)
        self.text = text

    def set(self, text: str) -> None:
        """Show ``text`` (markup) unless it is already shown."""
        if text != self.text:
            self.text = text
            self.update(text, layout=False)


class TopicKey(str):
    """The data of a topic's root node in the tree (a field's node holds its path, a plain str)."""


class MessageTree(Tree[str]):
    """One branch per expanded topic holding its newest message; updated in place, so folds and cursor stay."""

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__("topics", id=id)
        self.show_root = False
        self.guide_depth = 2

    def process_label(self, label: str | Text) -> Text:
        """Labels are plain text: a string field holding ``[b]`` shows as typed."""
        text = Text(label) if isinstance(label, str) else label
        return text.split()[0] if text.plain else text

    def topics(self) -> list[str]:
        """The expanded topics, in order."""
        return [str(node.data) for node in self.root.children]

    def set_topics(self, topics: Sequence[str]) -> None:
        """Keep exactly ``topics`` as branches (new ones at the end, expanded)."""
        for node in list(self.root.children):
            if node.data not in topics:
                node.remove()
        have = self.topics()
        for topic in topics:
            if topic not in have:
                self.root.add(topic, data=TopicKey(topic), expand=True)

    def topic_node(self, topic: str) -> TreeNode[str] | None:
        """The branch of ``topic``."""
        return next((n for n in self.root.children if n.data == topic), None)

    def show_message(self, topic: str, heading: str, items: Sequence[FieldItem] | None, note: str = "") -> None:
        """Show ``items`` (the fields of the newest message) under ``topic``'s branch titled ``heading``."""
        node = self.topic_node(topic)
        if node is None:
            return
        label = heading + (f"  {note}" if note else "")
        if str(node.label) != label:
            node.set_label(label)
        _sync(node, items or ())

    def cursor_topic_and_path(self) -> tuple[str, str] | None:
        """``(topic, field path)`` under the cursor (path "" on a topic's own line)."""
        node = self.cursor_node
        if node is None or node is self.root:
            return None
        path = "" if isinstance(node.data, TopicKey) else str(node.data)
        while node.parent is not None and node.parent is not self.root:
            node = node.parent
        return str(node.data), path


def _sync(node: TreeNode[str], items: Iterable[FieldItem]) -> None:
    """Make ``node``'s children show ``items``, reusing children whose path and shape match."""
    items = list(items)
    children = list(node.children)
    for index, item in enumerate(items):
        child = children[index] if index < len(children) else None
        branch = bool(item.children)
        if child is not None and (child.data != item.path or child.allow_expand != branch):
            for stale in children[index:]:
                stale.remove()
            children = children[:index]
            child = None
        if child is None:
            if branch:
                child = node.add(item.line, data=item.path, expand=not item.text)
            else:
                child = node.add_leaf(item.line, data=item.path)
            children.append(child)
        elif str(child.label) != item.line:
            child.set_label(item.line)
        if branch:
            _sync(child, item.children)
    for stale in children[len(items):]:
        stale.remove()


#: Eighths of a cell, lowest first, for sparklines.
BARS = " ▁▂▃▄▅▆▇█"


def sparkline(values: Sequence[float], width: int, height: int, *, floor: float | None = 0.0) -> list[str]:
    """The last ``width`` values as ``height`` lines of bars, from ``floor`` (None: the smallest value) to the largest.

    A rate or a bandwidth starts at zero, so noise of 0.01 Hz on 100 Hz stays flat; a field's plot spans its range.
    """
    values = list(values)[-width:] if width > 0 else []
    if not values or height < 1:
        return [""] * max(height, 0)
    low = min(values) if floor is None else min(floor, min(values))
    span = max(values) - low
    eighths = [round((v - low) / span * 8 * height) if span > 0 else (4 * height if floor is None else 0)
               for v in values]
    lines = []
    for row in range(height - 1, -1, -1):
        lines.append("".join(BARS[max(0, min(8, e - 8 * row))] for e in eighths))
    return lines


class Charts(Vertical):
    """Sparklines of the rate and bandwidth of one topic (fields are plotted in the plot panel)."""

    DEFAULT_CSS = """
    Charts > Line {
        height: 1;
    }
    Charts > .chart {
        height: 2;
        color: $primary;
        margin-bottom: 1;
    }
    """

    #: Rows of each sparkline.
    CHART_ROWS = 2

    def compose(self) -> ComposeResult:
        """Title, rate and bandwidth lines, each above its sparkline."""
        yield Line(id="chart-title")
        yield Line(id="rate-label")
        yield Line(id="rate-spark", classes="chart")
        yield Line(id="bw-label")
        yield Line(id="bw-spark", classes="chart")

    def show(self, topic: str | None, rates: list[float], bandwidths: list[float]) -> None:
        """Draw the rate and bandwidth history of ``topic``."""
        title = self.query_one("#chart-title", Line)
        if topic is None:
            title.set("no topic selected")
        else:
            title.set(f"[b]{escape(topic)}[/b]" + ("" if rates else "  (not measured: off screen)"))
        last_rate = rates[-1] if rates else None
        last_bw = bandwidths[-1] if bandwidths else None
        self.query_one("#rate-label", Line).set(
            f"rate {rate_text(last_rate)} Hz  (max {rate_text(max(rates)) if rates else '-'})")
        self.query_one("#bw-label", Line).set(
            f"bandwidth {bandwidth_text(last_bw)}  (max {bandwidth_text(max(bandwidths)) if bandwidths else '-'})")
        self._draw("#rate-spark", rates, floor=0.0)
        self._draw("#bw-spark", bandwidths, floor=0.0)

    def _draw(self, selector: str, values: Sequence[float], *, floor: float | None) -> None:
        line = self.query_one(selector, Line)
        line.set("\n".join(sparkline(values, line.content_region.width, self.CHART_ROWS, floor=floor)))
