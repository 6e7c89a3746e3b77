"""The monitor's plot panel (rqt_plot in the terminal) and the chooser of a topic's numeric fields.

:class:`PlotPanel` only draws what a :class:`~rostui.models.monitor.plot.PlotModel`
shows: a heading line (window, pause, value range) and the fields' lines
drawn by plotext through textual-plotext, with axes, ticks and a legend.
:class:`FieldChooser` lists the numeric fields of one topic's newest message
as checkboxes; closing it says which are to be plotted.
"""

from __future__ import annotations

from typing import ClassVar, Sequence

from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Vertical
from textual.markup import escape
from textual.screen import ModalScreen
from textual.widgets import SelectionList, Static
from textual.widgets.selection_list import Selection
from textual_plotext import PlotextPlot

from rostui.apps.monitor.detail import Line
from rostui.apps.widgets.focus import focus_now
from rostui.models.monitor.plot import PlotModel, SeriesView, nice_ticks

__all__ = ["PlotPanel", "FieldChooser", "plot_heading", "EMPTY_HINT"]

#: What the panel says with no field plotted.
EMPTY_HINT = ("no field plotted: f on a topic picks its numeric fields, f on a number in the tree plots it, "
              "or start with `rostui monitor /turtle1/pose/x:y`")


def _number(value: float) -> str:
    return f"{value:.4g}"


def plot_heading(model: PlotModel, views: Sequence[SeriesView]) -> str:
    """The panel's first line: fields, window, value range, and pause with the points received since."""
    parts = [f"{len(views)} field{'s' if len(views) != 1 else ''}", f"last {model.window:g} s"]
    span = model.value_range(views)
    parts.append(f"range {_number(span[0])} … {_number(span[1])}" if span else "no points in the window")
    if model.paused:
        parts.append(f"‖ paused ({model.since_pause} new points)")
    else:
        parts.append("▶ live")
    return "  │  ".join(parts)


class PlotPanel(Vertical):
    """The plotted fields over the last ``window`` seconds: heading line, then the plot (or a hint)."""

    DEFAULT_CSS = """
    PlotPanel > #plot-heading {
        height: 1;
        text-wrap: nowrap;
        text-overflow: ellipsis;
    }
    PlotPanel > #plot-notes {
        height: auto;
        max-height: 2;
        color: $warning;
    }
    PlotPanel > #plot-empty {
        color: $text-muted;
        padding: 1 2;
    }
    """

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._drawn: object = None

    def compose(self) -> ComposeResult:
        """Heading, notes (errors, fields still waiting), the plot, and the hint shown when nothing is plotted."""
        yield Line(id="plot-heading")
        yield Static(id="plot-notes")
        yield PlotextPlot(id="plot-canvas")
        yield Static(escape(EMPTY_HINT), id="plot-empty")

    @property
    def canvas(self) -> PlotextPlot:
        """The plotext widget."""
        return self.query_one("#plot-canvas", PlotextPlot)

    def show(self, model: PlotModel, now: float) -> None:
        """Draw ``model``'s window ending at ``now`` (or at its pause); only what changed is redrawn."""
        # plotext draws two dots a cell across: more points than that per column cost time and show nothing more
        views = model.view(now, buckets=2 * max(1, self.canvas.size.width))
        heading = plot_heading(model, views)
        notes = [f"✖ {v.error}" for v in views if v.error]
        waiting = [v.name for v in views if not v.values and not v.error]
        if waiting:
            notes.append(f"no points in the window yet: {', '.join(waiting)}")
        key = (heading, tuple(notes), tuple((v.name, v.times, v.values) for v in views), model.window,
               self.canvas.size)
        if key == self._drawn:
            return
        self._drawn = key
        self.query_one("#plot-heading", Line).set(escape(heading))
        note_lines = self.query_one("#plot-notes", Static)
        note_lines.update(escape("\n".join(notes)))
        note_lines.display = bool(notes)
        self.query_one("#plot-empty").display = not views
        canvas = self.canvas
        canvas.display = bool(views)
        if views:
            self._draw(canvas, model, views)

    @staticmethod
    def _draw(canvas: PlotextPlot, model: PlotModel, views: Sequence[SeriesView]) -> None:
        """Lines with a legend of the last values, x from -window to 0 s, y ticks at round values."""
        plt = canvas.plt
        plt.clear_figure()
        for view in views:
            if view.last is not None:  # plotext cannot draw the legend of a line without points
                plt.plot(list(view.times), list(view.values), label=f"{view.name} = {_number(view.last)}")
        plt.xlim(-model.window, 0.0)
        # round seconds (-10, -8 … 0), about one tick per 12 columns
        seconds = nice_ticks(-model.window, 0.0, most=min(11, max(2, canvas.size.width // 12)))
        plt.xticks(seconds, [f"{t:g}" for t in seconds])
        span = model.value_range(views)
        if span is not None:
            # a tick every other row at most: the frame, the x ticks and their label take 3 rows
            ticks = nice_ticks(*span, most=min(7, max(2, (canvas.size.height - 3) // 2)))
            plt.ylim(ticks[0], ticks[-1])
            plt.yticks(ticks, [f"{t:g}" for t in ticks])
        plt.xlabel("seconds before the pause" if model.paused else "seconds before now")
        canvas.refresh()


class FieldChooser(ModalScreen[list[str] | None]):
    """Checkboxes for the numeric fields of ``topic``'s newest message; Enter or Escape closes with the checked ones."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("escape", "done", "done", show=False),
        Binding("enter", "done", "done", show=False, priority=True),
    ]

    DEFAULT_CSS = """
    FieldChooser {
        align: center middle;
    }
    FieldChooser > Vertical {
        width: 70%;
        max-width: 70;
        height: auto;
        max-height: 90%;
        border: round $accent;
        background: $surface;
        padding: 0 1;
    }
    FieldChooser SelectionList {
        height: auto;
        max-height: 24;
    }
    FieldChooser .hint {
        height: auto;
        color: $text-muted;
    }
    """

    def __init__(self, topic: str, fields: Sequence[tuple[str, str]], plotted: Sequence[str]) -> None:
        """``fields`` are ``(path, value text)`` pairs; those in ``plotted`` start checked."""
        super().__init__()
        self.topic = topic
        self.fields = list(fields)
        self.plotted = set(plotted)

    def compose(self) -> ComposeResult:
        """Title, the checkboxes and the keys."""
        with Vertical():
            yield Static(f"[b]{escape(self.topic)}[/b]: numeric fields to plot", classes="hint")
            yield SelectionList[str](*[Selection(f"{path}  {text}", path, path in self.plotted)
                                       for path, text in self.fields], id="choose-fields")
            yield Static("space checks or unchecks · enter or esc plots the checked fields", classes="hint")

    def on_mount(self) -> None:
        """The list has the keyboard."""
        focus_now(self.query_one(SelectionList))

    @property
    def checked(self) -> list[str]:
        """The checked paths, in the message's order."""
        chosen = set(self.query_one(SelectionList).selected)
        return [path for path, _ in self.fields if path in chosen]

    def action_done(self) -> None:
        """Close and hand back the checked paths."""
        self.dismiss(self.checked)
