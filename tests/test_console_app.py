"""The console app driven with Textual's pilot: every key and what the user then sees.

Offline tests open the sample rosout.log (console_helpers) the way
`rostui console PATH` does; live tests run against `rostui core` with a node
in the test that logs, so messages take the real path /rosout -> rosout ->
/rosout_agg -> the app's subscriber -> its batch timer.
"""

from __future__ import annotations

import asyncio
import time
from pathlib import Path
from typing import Any, Awaitable, Callable

import pytest
from conftest import until
from console_helpers import log_until_seen, write_sample_log
from textual import events
from textual.pilot import Pilot

from rostui.apps.console.app import ConsoleApp
from rostui.core.log import Level
from rostui.core.log.rosout_read import RosoutEntry, read_rosout_log
from rostui.core.node.node import AsyncNode
from rostui.models.console.model import ConsoleOptions

Scenario = Callable[[Pilot, ConsoleApp], Awaitable[None]]



@pytest.fixture(autouse=True)
def utc(monkeypatch: pytest.MonkeyPatch) -> None:
    """Stamps shown in UTC."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()


@pytest.fixture
def sample(tmp_path: Path) -> Path:
    """The sample rosout.log."""
    return write_sample_log(tmp_path / "rosout.log")


def run(app: ConsoleApp, scenario: Scenario, size: tuple[int, int] = (140, 30)) -> None:
    """Run ``app`` headless and play ``scenario``."""
    async def main() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            await scenario(pilot, app)

    asyncio.run(main())


def offline(path: Path, **options: Any) -> ConsoleApp:
    """The app on a log file, as `rostui console PATH` opens it."""
    return ConsoleApp(ConsoleOptions(**options), read_rosout_log(path), log_name="rosout.log")


def messages(app: ConsoleApp) -> list[str]:
    """The message column of every visible row, as drawn (header and blank lines left out)."""
    lines = app.table.visible_texts()[1:]
    layout = app.table.column_layout
    start = layout.columns[0].width + 1
    width = layout.columns[1].width
    return [line[start:start + width].rstrip() for line in lines if line.strip()]


def status(app: ConsoleApp) -> str:
    """The status line's text."""
    return app.query_one("#status").plain  # type: ignore[attr-defined]


def filters(app: ConsoleApp) -> str:
    """The filter bar's text."""
    return app.query_one("#filters").plain  # type: ignore[attr-defined]


def cursor_message(app: ConsoleApp) -> str:
    """The message of the selected row."""
    assert app.table.cursor_seq is not None
    return app.model.entry(app.table.cursor_seq).message


KEY_NAMES = {" ": "space", "\\": "backslash", "(": "left_parenthesis", "^": "circumflex_accent"}


async def type_text(pilot: Pilot, text: str) -> None:
    """Type ``text`` key by key."""
    for char in text:
        await pilot.press(KEY_NAMES.get(char, char))


# ---------------------------------------------------------------------------------------------- offline


def test_opens_a_log_file_newest_at_the_bottom_following(sample: Path) -> None:
    """All 37 messages; the last row on screen is the newest, selected, in follow mode."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert len(app.model) == 37
        shown = messages(app)
        assert shown[-1] == "20 is divisible by 20."
        assert cursor_message(app) == "20 is divisible by 20."
        assert status(app).startswith(" FOLLOW  │ 37 shown / 37 kept │ file rosout.log")
        assert filters(app).startswith("1 DEBUG 20  2 INFO 8  3 WARN 5  4 ERROR 3  5 FATAL 1")
        header = app.table.visible_texts()[0]
        assert header.split() == ["#", "Message", "Sev", "Node", "Stamp", "Topics", "Location"]
        last = app.table.visible_texts()[-1]
        assert "FATAL /count_and_log" in last and "22:13:25.069" in last and "count.cpp:main:25" in last

    run(offline(sample), scenario)


def test_level_keys_hide_and_show_levels(sample: Path) -> None:
    """1 hides DEBUG, 2 hides INFO; pressing again shows them; the filter bar strikes them out."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("1")
        assert not any(m.startswith("Counted to") for m in messages(app))
        assert len(app.model) == 17
        await pilot.press("2")
        assert {app.model.entry(seq).level for seq, _ in app.model.shown()} == {4, 8, 16}
        assert messages(app)[0] == "5 is divisible by 5."
        await pilot.press("1", "2")
        assert len(app.model) == 37

    run(offline(sample), scenario)


def test_min_level_keeps_only_warnings_up_and_a_lower_level_key_starts_keeping_it(sample: Path) -> None:
    """--min-level WARN: DEBUG and INFO are not kept; pressing 2 keeps INFO from then on."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert len(app.model) == 37 - 20 - 8
        assert "1 DEBUG  2 INFO  3 WARN 5" in filters(app)
        await pilot.press("2")
        assert app.model.min_level == Level.INFO
        assert "keeping INFO messages from now on" in status(app)
        app.ingest([RosoutEntry(1_800_000_000 * 10**9, 2, "/late", "late info", "", 0, "", ())])
        await pilot.pause()
        assert messages(app)[-1] == "late info"

    path = sample
    app = ConsoleApp(ConsoleOptions(min_level=Level.WARN), read_rosout_log(path, min_level=Level.WARN),
                     log_name="rosout.log")
    run(app, scenario)


def test_node_include_exclude_and_reset(sample: Path) -> None:
    """n on a turtlesim row shows only /turtlesim; x hides it; N shows every node again."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("home")
        assert cursor_message(app) == "Starting turtlesim with node name /turtlesim"
        await pilot.press("n")
        assert {e.node for _, e in app.model.shown()} == {"/turtlesim"}
        assert len(messages(app)) == 3
        assert "nodes +/turtlesim" in filters(app)
        await pilot.press("x")
        assert "/turtlesim" not in {e.node for _, e in app.model.shown()}
        assert len(app.model) == 34
        assert "nodes −/turtlesim" in filters(app)
        await pilot.press("N")
        assert len(app.model) == 37 and "nodes" not in filters(app)

    run(offline(sample), scenario)


def test_text_search_filters_as_you_type_and_escape_cancels(sample: Path) -> None:
    """/ opens the prompt; typing filters (any case); Enter keeps it; Escape on the table drops it."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("slash")
        await type_text(pilot, "DIVISIBLE BY 10")
        await until(lambda: len(app.model) == 2, "the search to apply")
        await pilot.press("enter")
        assert not app.query_one("#prompt").display
        assert messages(app) == ["10 is divisible by 10.", "20 is divisible by 10."]
        assert "text DIVISIBLE BY 10" in filters(app)
        await pilot.press("escape")
        assert len(app.model) == 37

    run(offline(sample), scenario)


def test_search_cancelled_with_escape_goes_back_to_the_previous_search(sample: Path) -> None:
    """Escape in the prompt restores the search that was active before it opened."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("slash")
        await type_text(pilot, "wall")
        await pilot.press("enter")
        wall = "Oh no! I hit the wall! (Clamping from [x=11.112, y=5.544])"
        assert [e.message for _, e in app.model.shown()] == [wall]
        await pilot.press("slash", "backspace", "backspace", "backspace", "backspace")
        await until(lambda: len(app.model) == 37, "the emptied search to apply")
        await pilot.press("escape")
        assert len(app.model) == 1 and not app.query_one("#prompt").display

    run(offline(sample), scenario)


def test_regex_search_and_a_bad_regex(sample: Path) -> None:
    """r switches to regular expressions; a bad one is named in the filter bar and changes nothing."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("r")
        assert "regex mode" in filters(app)
        await pilot.press("slash")
        await type_text(pilot, r"^1\d is")
        await until(lambda: len(app.model) == 6, "the regex to apply")
        assert messages(app)[0] == "10 is divisible by 5."
        await type_text(pilot, "(")
        await until(lambda: "bad regular expression" in filters(app), "the bad regex to be reported")
        assert "missing ), unterminated subpattern" in filters(app)
        assert app.query_one("#prompt").has_class("-invalid")
        assert len(app.model) == 6
        await pilot.press("enter")
        assert app.query_one("#prompt").display, "Enter on a bad regex keeps the prompt open"
        await pilot.press("backspace", "enter")
        assert "bad regular expression" not in filters(app) and len(app.model) == 6

    run(offline(sample), scenario)


def test_regex_key_keeps_plain_text_when_the_search_is_no_regex(sample: Path) -> None:
    """A plain search '(Clamping' stays plain text when r is pressed; the status line says why."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("slash", *"(clamping", "enter")
        assert len(app.model) == 1
        await pilot.press("r")
        assert "'(clamping' is not a regular expression: still searching plain text" in status(app)
        assert "text (clamping" in filters(app) and len(app.model) == 1 and not app.spec.regex

    run(offline(sample), scenario)


def test_resizing_keeps_following_and_fits_the_columns(sample: Path) -> None:
    """From 140 to 80 columns: location and topics give way, the newest row stays at the bottom."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert "Location" in app.table.visible_texts()[0]
        await pilot.resize_terminal(80, 20)
        await pilot.pause()
        header = app.table.visible_texts()[0]
        assert "Location" not in header and "Topics" not in header and "Stamp" in header
        assert messages(app)[-1] == "20 is divisible by 20." and len(messages(app)) == app.table.page_rows

    run(offline(sample), scenario)


def test_highlight_rules_colour_matching_rows(sample: Path) -> None:
    """h adds a rule: matching rows get a background; H removes all rules."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        def backgrounds() -> dict[str, Any]:
            found = {}
            for y in range(1, app.table.page_rows + 1):
                strip = app.table.render_line(y)
                text = strip.text
                if text.strip():
                    found[text] = list(strip)[0].style.bgcolor
            return found

        await pilot.press("up")  # cursor off the rows compared below
        plain = backgrounds()
        await pilot.press("h")
        await type_text(pilot, "by 5.")
        await pilot.press("enter")
        assert " by 5. " in filters(app)
        marked = backgrounds()
        changed = {text for text in marked if marked[text] != plain.get(text)}
        assert changed and all("divisible by 5." in text for text in changed)
        assert {t for t in marked if "divisible by 5." in t and "FATAL" not in t and "20 is" not in t} <= changed
        await pilot.press("H")
        assert backgrounds() == plain

    run(offline(sample), scenario)


def test_detail_pane_shows_every_field_of_the_selected_message(sample: Path) -> None:
    """Enter opens the detail pane; moving the cursor updates it; Enter closes it."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("slash")
        await type_text(pilot, "lost")
        await pilot.press("enter", "enter")
        detail = app.query_one("#detail-text")
        text = str(detail.render())
        assert "#23  ERROR  /listener" in text
        assert "1700000003.151000000  (2023-11-14 22:13:23.151)" in text
        assert "listener.py:callback:9" in text
        assert "/chatter, /rosout" in text
        assert "rosout.log:26" in text
        assert "lost the talker\nlast heard 3.2 s ago" in text
        await pilot.press("escape", "up")
        assert "#36  ERROR  /count_and_log" in str(detail.render()), "follow mode took the cursor to the newest row"
        await pilot.press("enter")
        assert not app.query_one("#detail").display

    run(offline(sample), scenario)


def test_save_writes_the_shown_messages_as_rosout_log(sample: Path, tmp_path: Path) -> None:
    """s saves the filtered rows in rosout.log format (readable again); a bad path is reported."""
    target = tmp_path / "saved.log"

    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("1", "2", "s")
        prompt = app.query_one("#prompt")
        assert prompt.value.startswith("rostui_console_")  # type: ignore[attr-defined]
        prompt.value = str(tmp_path / "no" / "such" / "dir.log")  # type: ignore[attr-defined]
        await pilot.press("enter")
        assert "save failed:" in status(app) and "No such file or directory" in status(app)
        assert prompt.display
        prompt.value = str(target)  # type: ignore[attr-defined]
        await pilot.press("enter")
        assert f"saved 9 messages to {target}" in status(app)
        assert not prompt.display

    run(offline(sample), scenario)
    saved = read_rosout_log(target)
    assert [e.level for e in saved.entries] == [4, 4, 4, 8, 8, 4, 4, 8, 16]
    original = {e.message: e for e in read_rosout_log(sample).entries}
    assert all(e[:8] == original[e.message][:8] for e in saved.entries)


def test_follow_mode_scrolling_up_leaves_it_and_end_or_F_comes_back(sample: Path) -> None:
    """New rows follow at the bottom; after Up the view stays put while rows arrive; F and End follow again."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        def more(start: int, count: int) -> None:
            app.ingest([RosoutEntry((1_800_000_000 + n) * 10**9, 2, "/more", f"more {n}", "", 0, "", ())
                        for n in range(start, start + count)])

        more(0, 100)
        await pilot.pause()
        assert messages(app)[-1] == "more 99" and app.table.follow
        await pilot.press("up")
        assert " SCROLL " in status(app) and not app.table.follow
        before = messages(app)
        assert cursor_message(app) == "more 98"
        more(100, 50)
        await pilot.pause()
        assert messages(app) == before and cursor_message(app) == "more 98"
        await pilot.press("F")
        assert " FOLLOW " in status(app) and messages(app)[-1] == "more 149"
        await pilot.press("pageup")
        assert not app.table.follow
        await pilot.press("end")
        assert app.table.follow and cursor_message(app) == "more 149"
        await pilot._post_mouse_events([events.MouseScrollUp], "#table", offset=(10, 5))
        assert not app.table.follow, "the mouse wheel up leaves follow mode"
        top = messages(app)[0]
        await pilot.press("f")
        assert app.table.follow
        await pilot.click("#table", offset=(10, 3))
        assert not app.table.follow and cursor_message(app) == messages(app)[2], "a click selects the row"
        assert top != messages(app)[0]
        await pilot.press("f")
        more(150, 1)
        await pilot.pause()
        assert messages(app)[-1] == "more 150"

    run(offline(sample), scenario, size=(100, 24))


def test_max_drops_the_oldest_and_counts_them_on_screen(sample: Path) -> None:
    """--max 10: only the newest ten stay; the status line counts the dropped ones; # goes on."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert (len(app.model), app.model.dropped) == (10, 27)
        assert "27 dropped (max 10)" in status(app)
        app.ingest([RosoutEntry(1_800_000_000 * 10**9, 8, "/x", "one more", "", 0, "", ())])
        await pilot.pause()
        assert "28 dropped (max 10)" in status(app)
        assert app.table.visible_texts()[-1 - (app.table.page_rows - 10)].startswith("38 ")

    run(offline(sample, max_messages=10), scenario)


def test_clear_empties_the_table_and_numbering_goes_on(sample: Path) -> None:
    """c clears; the next message is #38."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await pilot.press("c")
        assert messages(app) == [] and "0 shown / 0 kept" in status(app) and "cleared" in status(app)
        app.ingest([RosoutEntry(1_800_000_000 * 10**9, 2, "/x", "after clear", "", 0, "", ())])
        await pilot.pause()
        assert app.table.visible_texts()[1].startswith("38  after clear")

    run(offline(sample), scenario)


def test_malformed_lines_are_counted_and_named_on_screen(tmp_path: Path) -> None:
    """A log with two bad lines opens; the status line counts them and names the first as file:line."""
    path = write_sample_log(tmp_path / "rosout.log", count=3)
    with path.open("a") as handle:
        handle.write("1700000100.000000000 INFO /x [no location\nstray text\n")
        handle.write("1700000101.000000000 INFO /x [x.py:1(f)] [topics: ] after the damage\n")

    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert messages(app)[-1] == "after the damage"
        assert f"⚠ 2 malformed lines (first: {path}:" in status(app)
        assert any(n.title == "malformed lines" for n in app._notifications)

    run(ConsoleApp(ConsoleOptions(), read_rosout_log(path), log_name=str(path)), scenario, size=(200, 24))


def test_command_line_filters_apply_from_the_start(sample: Path) -> None:
    """--node, --exclude-node and --search --regex (as ConsoleOptions) filter the first screen."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert {e.node for _, e in app.model.shown()} == {"/count_and_log"}
        assert messages(app) == ["10 is divisible by 5.", "10 is divisible by 10."]
        assert "nodes +/count_and_log −/turtlesim" in filters(app) and "regex ^10 is" in filters(app)

    run(offline(sample, include_nodes=("/count_and_log",), exclude_nodes=("/turtlesim",), search="^10 is",
                regex=True), scenario)


def test_a_bad_regex_on_the_command_line_is_reported_and_nothing_is_searched(sample: Path) -> None:
    """--search '(' --regex: the filter bar names the error; every message is shown; r and / still work."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        assert "bad regular expression '('" in filters(app)
        assert len(app.model) == 37
        await pilot.press("slash", *"wall", "enter")
        assert len(app.model) == 1 and "bad regular expression" not in filters(app)

    run(offline(sample, search="(", regex=True), scenario)


def test_control_characters_and_markup_in_messages_are_shown_as_text(tmp_path: Path) -> None:
    """Escape codes never reach the terminal; '[b]' in a message is text, also in the detail pane."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        app.ingest([RosoutEntry(1_800_000_000 * 10**9, 2, "/x", "\x1b[31mred[/] [b]bold\ttab", "", 0, "", ())])
        await pilot.pause()
        assert messages(app)[-1] == "␛[31mred[/] [b]bold tab"
        await pilot.press("enter")
        assert "␛[31mred[/] [b]bold tab" in str(app.query_one("#detail-text").render())

    run(ConsoleApp(ConsoleOptions(), read_rosout_log(write_sample_log(tmp_path / "r.log", 1))), scenario)


# ---------------------------------------------------------------------------------------------- live


async def logging_node(name: str) -> AsyncNode:
    """A node in the test that logs to /rosout (console output off)."""
    node = AsyncNode(name)
    node.log.console = None
    await node.start()
    return node


async def connected(app: ConsoleApp) -> None:
    """Wait until the app listens to /rosout_agg."""
    await until(lambda: app.source_state is not None and app.source_state.status == "connected",
                "the console to subscribe to /rosout_agg")


def test_live_messages_arrive_with_their_fields(rostui_core: Any) -> None:
    """A node logs; the console shows its messages with level, node, location and topics."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await connected(app)
        assert "master http://127.0.0.1:" in status(app)
        node = await logging_node("live_talker")
        try:
            await log_until_seen(app, node, "warm up")
            node.log.warn("careful: %d", 42)
            node.log.error("broken")
            await until(lambda: "broken" in messages(app), "the error to be drawn")
            shown = [e for _, e in app.model.shown() if e.message == "careful: 42"]
            assert shown and shown[0].level == 4 and shown[0].node == "/live_talker"
            assert shown[0].file == "test_console_app.py" and shown[0].function.endswith("scenario")
            assert "/rosout" in shown[0].topics
        finally:
            await node.shutdown()

    run(ConsoleApp(ConsoleOptions()), scenario)


def test_pause_keeps_buffering_and_shows_the_count_then_resume_shows_them(rostui_core: Any) -> None:
    """p freezes the table; arriving messages are counted as new; p again shows them in order."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await connected(app)
        node = await logging_node("pause_talker")
        try:
            await log_until_seen(app, node, "before pause")
            await pilot.press("p")
            frozen = messages(app)
            assert " PAUSED  0 new" in status(app)
            for n in range(5):
                node.log.info("during pause %d", n)
            await until(lambda: "5 new" in status(app), "the status line to count 5 new messages")
            assert messages(app) == frozen
            await pilot.press("p")
            assert messages(app)[-5:] == [f"during pause {n}" for n in range(5)]
            assert "resumed: 5 new messages" in status(app)
        finally:
            await node.shutdown()

    run(ConsoleApp(ConsoleOptions()), scenario)


def test_no_master_is_said_on_screen_until_one_comes(ros_env: dict[str, str]) -> None:
    """Without a master the status line says it waits; no crash, q quits."""
    async def scenario(pilot: Pilot, app: ConsoleApp) -> None:
        await until(lambda: "waiting for master http://127.0.0.1:" in status(app), "the waiting message")
        assert "(no answer)" in status(app)
        await pilot.press("q")

    run(ConsoleApp(ConsoleOptions()), scenario)
