"""Keys typed in one burst after a key that opens a line editor land in that editor (type-ahead over SSH).

A terminal hands the app every key of a burst at once (a paste, a fast typist on a slow link, tmux's
send-keys).  Each test posts ``/`` (or ``h``, ``i``) and the letters after it to the app in one go, as
Textual's driver does, and checks that the letters reached the editor, not the keys of the table behind
it: in the console ``warning`` once ran w, a, r (regex on), n (only this node), i, n, g instead (CI, stop
46).  A text field that has the keyboard keeps these keys: ``/`` typed in the search is a ``/``.
"""

from __future__ import annotations

import asyncio
from pathlib import Path

from textual import events
from textual.app import App
from textual.widgets import Input

from rostui.apps.console.app import ConsoleApp
from rostui.apps.diagnostics.app import DiagnosticsApp
from rostui.apps.graph.app import GraphApp
from rostui.core.log.rosout_read import read_rosout_log
from rostui.models.console.model import ConsoleOptions

from conftest import free_port
from console_helpers import write_sample_log
from test_diagnostics_snapshots import robot_picture

KEY_NAMES = {"/": "slash", " ": "space", ".": "full_stop", "*": "asterisk"}


def burst(app: App[object], text: str) -> None:
    """Post every character of ``text`` to ``app`` as key events at once, as the terminal driver does."""
    for char in text:
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
