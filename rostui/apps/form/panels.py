"""The form app's parts: the table of fields (with a slider for each number) and the one-line editor screen."""

from __future__ import annotations

from typing import Callable, ClassVar

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Vertical
from textual.message import Message
from textual.screen import ModalScreen
from textual.widgets import DataTable, Input, Static

from rostui.apps.widgets.bar_text import BAR_CELLS, bar_text
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.line_input import LineInput
from rostui.models.message_form.rows import FieldRow

__all__ = ["FieldTable", "LineScreen", "slider_cell", "detail_text"]

#: Widest expression cell; longer expressions end in an ellipsis (the detail line shows them whole).
EXPRESSION_CELLS = 40


def slider_cell(row: FieldRow) -> Text:
    """A numeric row's bar in its range, or nothing (a row that is not a number, or an expression such as
    ``sin(t)``, has no position to show)."""
    fraction = row.fraction()
    if fraction is None:
        return Text(" " * BAR_CELLS)
    return Text(bar_text(fraction), style="bold")


def _expression_cell(row: FieldRow) -> Text:
    text = row.expression if len(row.expression) <= EXPRESSION_CELLS else row.expression[:EXPRESSION_CELLS - 1] + "…"
    return Text(text)


def detail_text(row: FieldRow | None) -> str:
    """One line about the row under the cursor: its path and type, its slider's range, its whole expression."""
    if row is None:
        return ""
    facts = [row.type]
    if row.number() is not None:
        low, high = row.slider_range()
        facts.append(f"slider {low:g} … {high:g}")
    return f"{row.path} ({', '.join(facts)}) = {row.expression}"


class FieldTable(DataTable[Text]):
    """The form's rows: field, type, expression and slider. ←/→ move a number's slider a hundredth of its
    range, shift+←/→ a tenth; Enter edits the expression."""

    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("left", "nudge(-1)", "slider down", show=False),
        Binding("right", "nudge(1)", "slider up", show=False),
        Binding("shift+left", "nudge(-10)", "slider down ×10", show=False),
        Binding("shift+right", "nudge(10)", "slider up ×10", show=False),
    ]

    class Nudged(Message):
        """A row's slider moved (its expression is a new number)."""

        def __init__(self, row: FieldRow) -> None:
            super().__init__()
            self.row = row

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, cursor_type="row", zebra_stripes=False)
        self.rows_shown: list[FieldRow] = []

    @property
    def highlighted(self) -> FieldRow | None:
        """The row under the cursor."""
        if not self.rows_shown or not 0 <= self.cursor_row < len(self.rows_shown):
            return None
        return self.rows_shown[self.cursor_row]

    def show_rows(self, rows: list[FieldRow]) -> None:
        """Show ``rows`` (a new form: the cursor goes to the first)."""
        self.clear(columns=True)
        self.rows_shown = list(rows)
        self.add_column("Field", key="field", width=max([5, *(len(row.path) for row in rows)]))
        self.add_column("Type", key="type", width=max([4, *(len(row.type) for row in rows)]))
        self.add_column("Slider", key="slider", width=BAR_CELLS)
        self.add_column("Expression", key="expression")  # sized to its cells, and widened as they grow
        for row in rows:
            self.add_row(Text(row.path), Text(row.type, style="italic"), slider_cell(row), _expression_cell(row),
                         key=row.path)

    def refresh_row_of(self, row: FieldRow) -> None:
        """Redraw ``row``'s expression and slider after a change."""
        self.update_cell(row.path, "expression", _expression_cell(row), update_width=True)
        self.update_cell(row.path, "slider", slider_cell(row))

    def action_nudge(self, steps: int) -> None:
        """Move the highlighted number's slider ``steps`` hundredths of its range."""
        row = self.highlighted
        if row is not None and row.nudge(steps):
            self.refresh_row_of(row)
            self.post_message(self.Nudged(row))


class LineScreen(ModalScreen["str | None"]):
    """One line to type (an expression, a file's path): Enter gives it when ``check`` finds nothing wrong with
    it (else its one-line complaint shows under the field); Escape gives None."""

    DEFAULT_CSS = """
    LineScreen {
        align: center middle;
    }
    LineScreen > #line-box {
        width: 80%;
        max-width: 90;
        height: auto;
        border: round $accent;
        border-title-color: $accent;
        padding: 0 1;
        background: $surface;
    }
    LineScreen #line-error {
        color: $error;
        text-style: bold;
        height: auto;
    }
    """

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "cancel")]

    def __init__(self, title: str, about: str, value: str, check: Callable[[str], str | None]) -> None:
        super().__init__()
        self.title_text = title
        self.about = about
        self.value = value
        self.check = check

    def compose(self) -> ComposeResult:
        """What the line is for, the field, and a line for errors."""
        with Vertical(id="line-box"):
            yield Static(Text(self.about), id="line-about")
            yield LineInput(value=self.value, id="line")
            yield Static("", id="line-error")

    def on_mount(self) -> None:
        """The title; the cursor in the field."""
        focus_now(self.query_one("#line", Input))
        self.query_one("#line-box").border_title = f"{self.title_text} · Enter takes it · Esc cancels"

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """Give the line, or say what is wrong with it."""
        event.stop()
        problem = self.check(event.value)
        if problem:
            self.query_one("#line-error", Static).update(Text(problem))
            return
        self.dismiss(event.value)

    def action_cancel(self) -> None:
        """Leave without a line."""
        self.dismiss(None)
