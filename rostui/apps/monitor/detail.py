"""The expanded view: live message trees of the expanded topics, and sparklines of rate, bandwidth and a field."""

from __future__ import annotations

from typing import Iterable, Sequence

from rich.text import Text
from textual.app import ComposeResult
from textual.markup import escape
from textual.containers import Vertical
from textual.widgets import Sparkline, Static, Tree
from textual.widgets.tree import TreeNode

from rostui.core.monitor.rows import bandwidth_text, rate_text
from rostui.core.monitor.source import FieldPlot
from rostui.core.monitor.tree import FieldItem

__all__ = ["MessageTree", "Charts", "TopicKey", "Line"]


class Line(Static):
    """A text of fixed height that repaints only when its text changes, without laying the screen out again."""

    def __init__(self, text: str = "", *, id: str | None = None) -> None:
        super().__init__(text, id=id)
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


class Charts(Vertical):
    """Sparklines of the rate and bandwidth of one topic, and of the plotted field."""

    DEFAULT_CSS = """
    Charts > Sparkline {
        height: 2;
        margin-bottom: 1;
    }
    Charts > Line {
        height: 1;
    }
    """

    def compose(self) -> ComposeResult:
        """Title, rate, bandwidth and field plot lines, each above its sparkline."""
        yield Line(id="chart-title")
        yield Line(id="rate-label")
        yield Sparkline([], id="rate-spark")
        yield Line(id="bw-label")
        yield Sparkline([], id="bw-spark")
        yield Line(id="plot-label")
        yield Sparkline([], id="plot-spark")

    def show(self, topic: str | None, rates: list[float], bandwidths: list[float], plot: FieldPlot | None) -> None:
        """Draw the history of ``topic`` and the plotted field."""
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
        _set_data(self.query_one("#rate-spark", Sparkline), rates)
        _set_data(self.query_one("#bw-spark", Sparkline), bandwidths)
        label = self.query_one("#plot-label", Line)
        spark = self.query_one("#plot-spark", Sparkline)
        if plot is None:
            label.set("field plot: f on a number in the tree")
            _set_data(spark, [])
            return
        values = list(plot.values)
        if plot.error and not values:
            label.set(escape(f"{plot.topic}/{plot.path}: {plot.error}"))
        elif not values:
            label.set(escape(f"{plot.topic}/{plot.path}: waiting for a message"))
        else:
            label.set(escape(f"{plot.topic}/{plot.path} = {values[-1]:.6g}  "
                                f"[{min(values):.6g} … {max(values):.6g}]"))
        _set_data(spark, values[-120:])


def _set_data(spark: Sparkline, values: list[float]) -> None:
    if list(spark.data or []) != values:
        spark.data = values
