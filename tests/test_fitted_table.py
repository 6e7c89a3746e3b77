"""A self-sizing column narrows on screen when its widest cell becomes shorter (FittedTable)."""

from __future__ import annotations

import asyncio

from textual.app import App, ComposeResult
from textual.widgets import DataTable

from rostui.apps.widgets.fitted_table import FittedTable


class OneRow(App[None]):
    """A table of one row: a state and a number."""

    def __init__(self, table: DataTable[str]) -> None:
        super().__init__()
        self.table = table

    def compose(self) -> ComposeResult:
        yield self.table

    def on_mount(self) -> None:
        self.table.add_column("State", key="state")
        self.table.add_column("Pid", key="pid")
        self.table.add_row("starting", "4242", key="node")


def shown_row(app: OneRow) -> str:
    """The table's first data row as the screen shows it."""
    return "".join(segment.text for segment in app.table.render_line(1)).rstrip()


def after_a_shorter_state(table: DataTable[str]) -> str:
    async def scenario() -> str:
        app = OneRow(table)
        async with app.run_test(size=(40, 5)) as pilot:
            await pilot.pause()
            assert shown_row(app) == " starting  4242"
            table.update_cell("node", "state", "running", update_width=True)
            shown_row(app)  # drawn before the column is measured again (a busy machine's screen update)
            for _ in range(5):
                await pilot.pause(0.02)
            return shown_row(app)
    return asyncio.run(scenario())


def test_the_column_narrows_on_screen() -> None:
    assert after_a_shorter_state(FittedTable()) == " running  4242"
