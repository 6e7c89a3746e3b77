"""The reconfigure app's parts: the parameter table, the detail line under it, and the editor of one value."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding, BindingType
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import DataTable, Input, OptionList, Static
from textual.widgets.option_list import Option

from rostui.apps.widgets.bar_text import bar_text
from rostui.apps.widgets.focus import focus_now
from rostui.apps.widgets.line_input import LineInput
from rostui.models.reconfigure import GroupRow, ParamRow
from rostui.tools.reconfigure.values import ParameterValueError

__all__ = ["EditScreen", "ParamTable", "detail_text"]

def _name_cell(row: GroupRow | ParamRow) -> Text:
    if isinstance(row, GroupRow):
        indent = "  " * (row.depth - 1)
        return Text(f"{indent}▾ {row.name}", style="bold")
    return Text("  " * row.depth + row.name)


def _value_cell(row: GroupRow | ParamRow) -> Text:
    if isinstance(row, GroupRow):
        return Text(row.kind, style="italic")
    if row.value is None:
        return Text("…", style="dim")
    fraction = row.fraction()
    if fraction is None:
        if row.type == "bool":
            return Text("☑ true" if row.value else "☐ false")
        return Text(row.value_text())
    return Text.assemble((bar_text(fraction), "bold"), " ", row.value_text())


class ParamTable(DataTable[Text]):
    """A server's groups and parameters, one row each: name (indented by group) and value (a bar for a ranged
    number; the range and an enum's constants are in the detail line). The cursor stays on the same parameter
    when values change (the app's keys change the value under it)."""


    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id, cursor_type="row", zebra_stripes=False)
        self.rows_shown: list[GroupRow | ParamRow] = []

    def on_mount(self) -> None:
        """Two columns."""
        self._add_columns([])

    def _add_columns(self, rows: Sequence[GroupRow | ParamRow]) -> None:
        # The widths are set from the rows here: the table measures new rows only when it is next idle.
        names = [len(_name_cell(row)) for row in rows]
        values = [len(_value_cell(row)) for row in rows]
        self.add_column("Parameter", key="name", width=max([len("Parameter"), *names]))
        self.add_column("Value", key="value", width=max([len("Value"), *values]))

    @property
    def highlighted_row(self) -> GroupRow | ParamRow | None:
        """The row under the cursor, if any."""
        if not self.rows_shown or not 0 <= self.cursor_row < len(self.rows_shown):
            return None
        return self.rows_shown[self.cursor_row]

    def show_rows(self, rows: Sequence[GroupRow | ParamRow]) -> None:
        """Show *rows*; when only values changed, only the value cells are redrawn."""
        rows = list(rows)
        if [row.key for row in rows] == [row.key for row in self.rows_shown]:
            widths = [len(_value_cell(row)) for row in rows]
            if max(widths, default=0) <= self.columns["value"].width:  # type: ignore[index]
                for old, new in zip(self.rows_shown, rows):
                    if old != new:
                        self.update_cell(new.key, "value", _value_cell(new))
                self.rows_shown = rows
                return
        keep = self.highlighted_row.key if self.highlighted_row is not None else None
        self.clear(columns=True)
        self._add_columns(rows)
        self.rows_shown = rows
        for row in rows:
            self.add_row(_name_cell(row), _value_cell(row), key=row.key)
        keys = [row.key for row in rows]
        if keep in keys:
            self.move_cursor(row=keys.index(keep), animate=False)
        else:
            first = next((i for i, row in enumerate(rows) if isinstance(row, ParamRow)), None)
            if first is not None:
                self.move_cursor(row=first, animate=False)

    def clear_rows(self) -> None:
        """Show no parameters."""
        self.clear()
        self.rows_shown = []


def detail_text(row: GroupRow | ParamRow | None) -> str:
    """One line about the row under the cursor: type, range or constants, default and description (a group's
    kind)."""
    if row is None:
        return ""
    if isinstance(row, GroupRow):
        return f"group {row.name}" + (f" ({row.kind})" if row.kind else "") + ("" if row.state else ", closed")
    facts = [row.type]
    if row.range_text():
        facts.append(row.range_text())
    if row.default is not None:
        facts.append(f"default {ParamRow(row.name, row.type, row.default, choices=row.choices).value_text()}")
    described = f": {row.description}" if row.description else ""
    return f"{row.name} ({', '.join(facts)}){described}"


class EditScreen(ModalScreen[Any]):
    """Edit one parameter's value: an enum's constants to choose from, or a field for any other value.

    Enter sends the value (the screen is dismissed with it); Escape leaves it unchanged (dismissed with None).
    A typed value that is not of the parameter's type is said under the field.
    """

    DEFAULT_CSS = """
    EditScreen {
        align: center middle;
    }
    EditScreen > #edit {
        width: 70%;
        max-width: 70;
        height: auto;
        border: round $accent;
        border-title-color: $accent;
        padding: 0 1;
        background: $surface;
    }
    EditScreen #edit-error {
        color: $error;
        text-style: bold;
        height: auto;
    }
    EditScreen #choices {
        height: auto;
        max-height: 12;
    }
    """

    BINDINGS: ClassVar[list[BindingType]] = [Binding("escape", "cancel", "cancel")]

    def __init__(self, row: ParamRow) -> None:
        super().__init__()
        self.row = row

    def compose(self) -> ComposeResult:
        """The choices or the field, and a line for errors."""
        with Vertical(id="edit"):
            yield Static(Text(self.row.description or self.row.name), id="edit-about")
            if self.row.choices:
                options = [Option(Text(f"{c.name} ({c.value})" + (f": {c.description}" if c.description else "")),
                                  id=str(index)) for index, c in enumerate(self.row.choices)]
                yield OptionList(*options, id="choices")
            else:
                yield LineInput(value="" if self.row.value is None else self.row.value_text(), id="field")
            yield Static("", id="edit-error")

    def on_mount(self) -> None:
        """Title; the cursor on the current choice."""
        self.query_one("#edit").border_title = f"{self.row.name} ({self.row.type}) · Enter sends · Esc cancels"
        if self.row.choices:
            choices = self.query_one("#choices", OptionList)
            values = [c.value for c in self.row.choices]
            if self.row.value in values:
                choices.highlighted = values.index(self.row.value)
            focus_now(choices)
        else:
            focus_now(self.query_one("#field", Input))

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        """A constant chosen: send its value."""
        event.stop()
        self.dismiss(self.row.choices[int(event.option.id or 0)].value)

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """A value typed: send it when it is of the parameter's type, else say why."""
        event.stop()
        try:
            value = self.row.parse(event.value.strip())
        except ParameterValueError as exc:
            self.query_one("#edit-error", Static).update(Text(str(exc)))
            return
        self.dismiss(value)

    def action_cancel(self) -> None:
        """Leave the value as it is."""
        self.dismiss(None)
