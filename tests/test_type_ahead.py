"""Keys typed in one burst after a key that opens a line editor land in that editor (type-ahead over SSH).

A terminal hands the app every key of a burst at once (a paste, a fast typist on a slow link, tmux's
send-keys).  Each test posts ``/`` (or ``h``, ``i``) and the letters after it to the app in one go, as
Textual's driver does, and checks that the letters reached the editor, not the keys of the table behind
it: in the console ``warning`` once ran w, a, r (regex on), n (only this node), i, n, g instead (CI, stop
46).  A text field that has the keyboard keeps these keys: ``/`` typed in the search is a ``/``.

Editing keys in a burst act in turn too: Textual's Input inserts letters at once but runs ctrl+u, backspace,
arrows and Enter as bindings once the key has travelled up to the app, so ctrl+u then ``True`` then Enter
once gave an empty line (the form's expression, CI at stop 45 and again under load): rostui's LineInput runs
them in order.
"""

from __future__ import annotations

import asyncio
from pathlib import Path

from textual import events
from textual.app import App, ComposeResult
from textual.widgets import Input

from rostui.apps.console.app import ConsoleApp
from rostui.apps.diagnostics.app import DiagnosticsApp
from rostui.apps.graph.app import GraphApp
from rostui.apps.widgets.line_input import LineInput
from rostui.core.log.rosout_read import read_rosout_log
from rostui.models.console.model import ConsoleOptions

from conftest import free_port
from console_helpers import write_sample_log
from test_diagnostics_snapshots import robot_picture

KEY_NAMES = {"/": "slash", " ": "space", ".": "full_stop", "*": "asterisk"}
EDITING_KEYS = {"\x15": "ctrl+u", "\x7f": "backspace", "\x02": "left", "\r": "enter"}
"""Stand-ins for editing keys in a burst's text: ctrl+u, backspace, ← and Enter."""


def burst(app: App[object], text: str) -> None:
    """Post every character of ``text`` to ``app`` as key events at once, as the terminal driver does."""
    for char in text:
        if char in EDITING_KEYS:
            app.post_message(events.Key(EDITING_KEYS[char], None))
        else:
            app.post_message(events.Key(KEY_NAMES.get(char, char), char))


async def typed(app: App[object], text: str, field: str) -> str:
    """Send ``text`` in one burst and return what the editor ``field`` (a CSS selector) then holds."""
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        burst(app, text)
        for _ in range(50):
            await pilot.pause()
            editor = app.query_one(field, Input)
            if editor.has_focus and editor.value and len(editor.value) >= len(text) - 1:
                break
        editor = app.query_one(field, Input)
        assert editor.has_focus, f"{field} does not have the keyboard"
        return editor.value


def test_console_search_gets_every_key_of_the_burst(tmp_path: Path) -> None:
    log = write_sample_log(tmp_path / "rosout.log")
    app = ConsoleApp(ConsoleOptions(), read_rosout_log(log), log_name="rosout.log")
    assert asyncio.run(typed(app, "/warning/x", "#prompt")) == "warning/x"
    assert not app.spec.regex and not app.spec.include_nodes, "the table's keys ran (r: regex, n: only this node)"


def test_console_highlight_gets_every_key_of_the_burst(tmp_path: Path) -> None:
    log = write_sample_log(tmp_path / "rosout.log")
    app = ConsoleApp(ConsoleOptions(), read_rosout_log(log), log_name="rosout.log")
    assert asyncio.run(typed(app, "hdivisible", "#prompt")) == "divisible"


def test_diagnostics_filter_gets_every_key_of_the_burst() -> None:
    app = DiagnosticsApp(store=robot_picture(), clock=lambda: 1_700_000_001.4)
    assert asyncio.run(typed(app, "/motor.*l", "#filter")) == "motor.*l"
    assert app.only.level == 0, "l (the level key) ran behind the filter"


def test_graph_search_gets_every_key_of_the_burst() -> None:
    app = GraphApp(master_uri=f"http://127.0.0.1:{free_port()}", period=0.5)
    assert asyncio.run(typed(app, "/talker", "#prompt")) == "talker"


class OneLine(App[str]):
    """A LineInput alone, as the form's expression editor holds one; Enter ends the app with its line."""

    def compose(self) -> ComposeResult:
        yield LineInput("old text", id="line")

    def on_input_submitted(self, event: Input.Submitted) -> None:
        self.exit(event.value)


def test_editing_keys_in_a_burst_act_in_the_order_typed() -> None:
    """ctrl+u, True, ← X, backspace... then Enter: the line is what a slow typist would have made."""
    async def main() -> str | None:
        app = OneLine()
        async with app.run_test() as pilot:
            await pilot.pause()
            burst(app, "\x15True\x02X\x02\x02\x7fZ\r")
            for _ in range(50):
                if app.return_value is not None:
                    break
                await pilot.pause()
        return app.return_value
    assert asyncio.run(main()) == "TZuXe"


def test_console_search_edits_in_a_burst_act_in_order(tmp_path: Path) -> None:
    log = write_sample_log(tmp_path / "rosout.log")
    app = ConsoleApp(ConsoleOptions(), read_rosout_log(log), log_name="rosout.log")
    assert asyncio.run(typed(app, "/warm\x7fn", "#prompt")) == "warn"
