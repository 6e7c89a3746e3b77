"""The console's one-line bars: filters (top), status and key help (bottom), the detail pane's text.

Each bar is a plain widget that repaints only when its text changes, so the
ingest timer can update it many times a second without layout work.  The
texts are built by pure functions from the model and the app's state.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from textual.content import Content
from textual.widget import Widget

from rostui.apps.console.columns import printable
from rostui.apps.console.table import HIGHLIGHT_COLOURS
from rostui.apps.widgets.keys import key_line
from rostui.core.log.levels import Level
from rostui.core.log.rosout_read import RosoutEntry
from rostui.models.console.filters import FilterSpec, HighlightRule
from rostui.models.console.model import ConsoleModel

__all__ = ["Bar", "KEY_HELP", "LEVEL_KEYS", "StatusInfo", "detail_markup", "filter_markup", "status_markup"]

#: The key that toggles each level, as the filter bar shows it: 1 (DEBUG) to 5 (FATAL).
LEVEL_KEYS: dict[Level, str] = {level: str(key) for key, level in enumerate(Level, start=1)}

_LEVEL_COLOURS: dict[int, str] = {Level.DEBUG: "$text-success", Level.INFO: "$foreground",
                                  Level.WARN: "$text-warning", Level.ERROR: "$text-error", Level.FATAL: "$text-error"}

_HIGHLIGHT_COLOURS = ["$accent 30%", "$success 30%", "$secondary 80%", "$error 25%"]

#: The key help line.
KEY_HELP = key_line("1-5 levels  / search  r regex  h highlight  n/x node  p pause  c clear  "
                    "⏎ detail  s save  F follow")


class Bar(Widget):
    """A one-line widget showing :class:`Content`; repaints only when text or styles change."""

    DEFAULT_CSS = """
    Bar { height: 1; }
    """

    def __init__(self, content: Content | str = "", *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._content = Content(content) if isinstance(content, str) else content
        self._key = _key(self._content)

    @property
    def plain(self) -> str:
        """The text shown, without styles."""
        return self._content.plain

    def show(self, content: Content) -> None:
        """Display ``content``."""
        key = _key(content)
        if key != self._key:
            self._key = key
            self._content = content
            self.refresh()

    def render(self) -> Content:
        """The current content."""
        return self._content


def _key(content: Content) -> tuple[str, tuple[object, ...]]:
    return content.plain, tuple(content.spans)


def _count(value: int) -> str:
    return f"{value:,}"


def filter_markup(spec: FilterSpec, model: ConsoleModel, highlights: list[HighlightRule],
                  regex_error: str = "") -> Content:
    """The filter bar: level toggles with their counts (clickable), node filters, search, highlight rules."""
    parts: list[str | Content | tuple[str, str]] = []
    for level, key in LEVEL_KEYS.items():
        count = _count(model.level_counts.get(int(level), 0))
        action = f"@click=app.toggle_level({int(level)})"
        if parts:
            parts.append("  ")
        if int(level) < model.min_level:
            parts.append(Content.from_markup(f"[{action} dim]{key} [strike]{level.name}[/strike][/]"))
        elif int(level) in spec.levels:
            parts.append(Content.from_markup(f"[{action}][b {_LEVEL_COLOURS[level]}]{key} {level.name}[/] {count}[/]"))
        else:
            parts.append(Content.from_markup(f"[{action} dim]{key} [strike]{level.name}[/strike] {count}[/]"))
    if spec.include_nodes or spec.exclude_nodes:
        parts.append(" │ nodes")
        parts.extend(f" +{printable(n)}" for n in sorted(spec.include_nodes))
        parts.extend(f" −{printable(n)}" for n in sorted(spec.exclude_nodes))
    if regex_error:
        parts.extend([" │ ", (printable(regex_error), "bold $text-error")])
    elif spec.search:
        parts.extend([f" │ {'regex' if spec.regex else 'text'} ", (printable(spec.search), "bold")])
    elif spec.regex:
        parts.append(" │ regex mode")
    for index, rule in enumerate(highlights):
        parts.extend([" ", (f" {printable(rule.pattern)} ", f"on {_HIGHLIGHT_COLOURS[index % HIGHLIGHT_COLOURS]}")])
    return Content.assemble(*parts)


@dataclass(frozen=True)
class StatusInfo:
    """What the status line shows besides the model's counters."""

    follow: bool
    source: str
    source_ok: bool = True
    malformed: str = ""
    notice: str = ""


def status_markup(model: ConsoleModel, info: StatusInfo) -> Content:
    """Mode, rows shown of kept, drops, malformed lines, the source (master or file) and a notice."""
    if model.paused:
        mode = Content.from_markup(f"[b reverse $text-warning] PAUSED [/] [b]{_count(model.pending)} new[/]")
    elif info.follow:
        mode = Content.from_markup("[b reverse $text-success] FOLLOW [/]")
    else:
        mode = Content.from_markup("[b reverse $text-primary] SCROLL [/]")
    parts: list[str | Content | tuple[str, str]] = [
        mode, f" │ {_count(len(model))} shown / {_count(model.kept)} kept"]
    if model.dropped:
        parts.extend([" │ ", (f"{_count(model.dropped)} dropped", "bold $text-warning"),
                      f" (max {_count(model.capacity)})"])
    if info.malformed:
        parts.extend([" │ ", (f"⚠ {printable(info.malformed)}", "bold $text-error")])
    parts.extend([" │ ", (printable(info.source), "" if info.source_ok else "bold $text-error")])
    if info.notice:
        parts.extend([" │ ", printable(info.notice)])
    return Content.assemble(*parts)


def _full_stamp(stamp: int) -> str:
    secs, nsecs = divmod(stamp, 1_000_000_000)
    wall = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(secs))
    return f"{secs}.{nsecs:09d}  ({wall}.{nsecs // 1_000_000:03d})"


def detail_markup(seq: int | None, entry: RosoutEntry | None, source_name: str = "") -> Content:
    """Every field of the selected message, its full text last."""
    if seq is None or entry is None:
        return Content.from_markup("[dim]no message selected[/]")
    colour = _LEVEL_COLOURS.get(entry.level, "$foreground")
    parts: list[str | Content | tuple[str, str]] = [
        (f"#{seq + 1}", "bold"), "  ", (entry.level_name, f"bold {colour}"), "  ",
        (printable(entry.node) or "(no node)", "bold"),
        ("\nstamp     ", "dim"), _full_stamp(entry.stamp),
        ("\nlocation  ", "dim"), printable(entry.location) or "-", ("   (file:function:line)", "dim"),
        ("\ntopics    ", "dim"), printable(", ".join(entry.topics)) or "-",
    ]
    if entry.source_line and source_name:
        parts.extend([("\nread from ", "dim"), f"{printable(source_name)}:{entry.source_line}"])
    parts.append("\n")
    parts.append(printable(entry.message, keep_newlines=True) if entry.message else ("(empty message)", "dim"))
    return Content.assemble(*parts, strip_control_codes=False)
