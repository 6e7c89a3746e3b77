"""The console's one-line bars: filters (top), status and key help (bottom), the detail pane's text.

Each bar is a plain widget that repaints only when its text changes, so the
ingest timer can update it many times a second without layout work.  The
texts are built by pure functions from the model and the app's state.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from textual.markup import escape
from textual.content import Content
from textual.widget import Widget

from rostui.apps.console.filters import FilterSpec, HighlightRule
from rostui.apps.console.model import ConsoleModel
from rostui.apps.console.table import HIGHLIGHT_COLOURS
from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry

__all__ = ["Bar", "KEY_HELP", "LEVEL_KEYS", "StatusInfo", "detail_markup", "filter_markup", "status_markup"]

#: The key that toggles each level, as the filter bar shows it.
LEVEL_KEYS: dict[Level, str] = {Level.DEBUG: "1", Level.INFO: "2", Level.WARN: "3", Level.ERROR: "4",
                                Level.FATAL: "5"}

_LEVEL_COLOURS = {Level.DEBUG: "$text-success", Level.INFO: "$foreground", Level.WARN: "$text-warning",
                  Level.ERROR: "$text-error", Level.FATAL: "$text-error"}

_HIGHLIGHT_COLOURS = ["$secondary 35%", "$accent 35%", "$success 30%", "$warning 30%"]

#: The key help line.
KEY_HELP = ("1-5 levels  / search  r regex  h highlight  n/x node  p pause  c clear  "
            "⏎ detail  s save  F follow  q quit")


class Bar(Widget):
    """A one-line widget showing Textual markup; repaints only when the markup changes."""

    DEFAULT_CSS = """
    Bar { height: 1; }
    """

    def __init__(self, markup: str = "", *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._markup = markup
        self._content = Content.from_markup(markup)

    @property
    def markup(self) -> str:
        """The markup shown."""
        return self._markup

    @property
    def plain(self) -> str:
        """The text shown, without styles."""
        return self._content.plain

    def show(self, markup: str) -> None:
        """Display ``markup``."""
        if markup != self._markup:
            self._markup = markup
            self._content = Content.from_markup(markup)
            self.refresh()

    def render(self) -> Content:
        """The current content."""
        return self._content


def _count(value: int) -> str:
    return f"{value:,}"


def filter_markup(spec: FilterSpec, model: ConsoleModel, highlights: list[HighlightRule],
                  regex_error: str = "") -> str:
    """The filter bar: level toggles with their counts, node filters, search, highlight rules."""
    parts = []
    for level, key in LEVEL_KEYS.items():
        count = model.level_counts.get(int(level), 0)
        action = f"@click=app.toggle_level({int(level)})"
        if int(level) < model.min_level:
            parts.append(f"[{action} dim strike]{key} {level.name}[/]")
        elif int(level) in spec.levels:
            parts.append(f"[{action}][b {_LEVEL_COLOURS[level]}]{key} {level.name}[/] {_count(count)}[/]")
        else:
            parts.append(f"[{action} dim]{key} [strike]{level.name}[/strike] {_count(count)}[/]")
    line = "  ".join(parts)
    nodes = [f"+{escape(n)}" for n in sorted(spec.include_nodes)] + [f"−{escape(n)}" for n in
                                                                       sorted(spec.exclude_nodes)]
    if nodes:
        line += " │ nodes " + " ".join(nodes)
    if spec.search or regex_error:
        kind = "regex" if spec.regex else "text"
        if regex_error:
            line += f" │ [b $text-error]{escape(regex_error)}[/]"
        else:
            line += f" │ {kind} [b]{escape(spec.search)}[/]"
    elif spec.regex:
        line += " │ regex mode"
    for index, rule in enumerate(highlights):
        colour = _HIGHLIGHT_COLOURS[index % HIGHLIGHT_COLOURS]
        line += f" [on {colour}] {escape(rule.pattern)} [/]"
    return line


@dataclass(frozen=True)
class StatusInfo:
    """What the status line shows besides the model's counters."""

    follow: bool
    source: str
    source_ok: bool = True
    malformed: str = ""
    notice: str = ""


def status_markup(model: ConsoleModel, info: StatusInfo) -> str:
    """Mode, rows shown of kept, drops, malformed lines, the source (master or file) and a notice."""
    if model.paused:
        mode = f"[b reverse $text-warning] PAUSED [/] [b]{_count(model.pending)} new[/]"
    elif info.follow:
        mode = "[b reverse $text-success] FOLLOW [/]"
    else:
        mode = "[b reverse $text-primary] SCROLL [/]"
    parts = [mode, f"{_count(len(model))} shown / {_count(model.kept)} kept"]
    if model.dropped:
        parts.append(f"[b $text-warning]{_count(model.dropped)} dropped[/] (max {_count(model.capacity)})")
    if info.malformed:
        parts.append(f"[b $text-error]⚠ {escape(info.malformed)}[/]")
    source = escape(info.source)
    parts.append(source if info.source_ok else f"[b $text-error]{source}[/]")
    if info.notice:
        parts.append(escape(info.notice))
    return " │ ".join(parts)


def _full_stamp(stamp: int) -> str:
    secs, nsecs = divmod(stamp, 1_000_000_000)
    wall = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(secs))
    return f"{secs}.{nsecs:09d}  ({wall}.{nsecs // 1_000_000:03d})"


def detail_markup(seq: int | None, entry: RosoutEntry | None, source_name: str = "") -> str:
    """Every field of the selected message, its full text last."""
    if seq is None or entry is None:
        return "[dim]no message selected[/]"
    colour = _LEVEL_COLOURS.get(Level(entry.level), "$foreground") if entry.level in Level._value2member_map_ \
        else "$foreground"
    lines = [
        f"[b]#{seq + 1}[/]  [b {colour}]{entry.level_name}[/]  [b]{escape(entry.node) or '(no node)'}[/]",
        f"[dim]stamp[/]     {_full_stamp(entry.stamp)}",
        f"[dim]location[/]  {escape(entry.location) or '-'}   [dim](file:function:line)[/]",
        f"[dim]topics[/]    {escape(', '.join(entry.topics)) or '-'}",
    ]
    if entry.source_line and source_name:
        lines.append(f"[dim]read from[/] {escape(source_name)}:{entry.source_line}")
    lines.append(escape(entry.message) if entry.message else "[dim](empty message)[/]")
    return "\n".join(lines)
