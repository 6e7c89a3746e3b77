"""`rostui monitor` driven with Textual's pilot against `rostui core` and publisher processes.

Publishers are real processes (`rostui topic pub -r`, or one process with
many topics), so messages reach the app over TCPROS; what the monitor
subscribes to is read back from the master with getSystemState, as any ROS
tool would see it.
"""

from __future__ import annotations

import asyncio
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from cli_helpers import rostui
from conftest import rostui_cmd, start_rostui_core, stop_process, until
from live_helpers import Watcher
from pilot_helpers import press_in_one_burst
from monitor_helpers import (ManyTopics, Publisher, master_subscriptions, run_monitor as run,
                             start_publishers, stop_all)
from textual.pilot import Pilot
from textual.widgets import Input, Static, TextArea

from rostui.apps.monitor.app import MonitorApp
from rostui.apps.monitor.editor import PublishEditor
from rostui.apps.monitor.plot import FieldChooser
from rostui.models.monitor.rows import Column, Liveness, TopicRow

DEADLINE = 30.0




def row(app: MonitorApp, topic: str) -> TopicRow | None:
    """The row the table shows for ``topic``."""
    return next((r for r in app.shown if r.name == topic), None)


async def live(app: MonitorApp, *topics: str) -> None:
    """Wait until every topic's row is live with a rate."""
    def ready() -> bool:
        rows = [row(app, t) for t in topics]
        return all(r is not None and r.liveness is Liveness.LIVE and r.rate for r in rows)
    await until(ready, f"{', '.join(topics)} live with a rate", DEADLINE)


def screen_text(app: MonitorApp, widget_id: str) -> str:
    """The plain text a Static shows."""
    return str(app.query_one(widget_id, Static).render())


def test_table_sort_and_filter(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """Two publishers: type, counts, rates and bandwidth in the table; s cycles the sort; / filters."""
    pubs = start_publishers(ros_env, tmp_path, [
        ("/fast", "geometry_msgs/Twist", "{linear: {x: 1.5}}", 20),
        ("/slow", "std_msgs/String", "data: hello", 2),
    ])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await live(app, "/fast", "/slow")
        fast, slow = row(app, "/fast"), row(app, "/slow")
        assert fast.type == "geometry_msgs/Twist" and len(fast.publishers) == 1 and fast.subscribers == ()
        assert fast.rate == pytest.approx(20, rel=0.2) and slow.rate == pytest.approx(2, rel=0.2)
        assert fast.cells()[5].endswith("B/s") and fast.bandwidth == pytest.approx(20 * 48, rel=0.25)
        while app.sort_column is not Column.RATE:
            await pilot.press("s")
        assert app.table.names.index("/fast") < app.table.names.index("/slow")
        assert "sort rate ↓" in screen_text(app, "#status")
        await pilot.press("S")
        assert app.table.names.index("/fast") > app.table.names.index("/slow")
        await pilot.press("slash", *"slo")
        assert app.table.names == ["/slow"]
        assert "1 shown" in screen_text(app, "#status")
        await pilot.press("escape")
        assert "/fast" in app.table.names and app.focused is app.table
        await pilot.press("slash", *"zzz", "enter")
        assert app.table.names == [] and "no topic matches 'zzz'" in screen_text(app, "#banner")
        await pilot.press("slash", *["backspace"] * 3, "enter")
        press_in_one_burst(app, "slash", *"/fas", "enter")
        await until(lambda: app.filter_text == "/fas", lambda: f"the keys typed with / (a / among them) to reach the filter, not {app.filter_text!r}", 10)
        await until(lambda: app.focused is app.table, "Enter to give the keyboard back to the table", 10)
        assert app.table.names == ["/fast"]

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        stop_all(pubs)


def test_subscribes_only_to_visible_rows(any_master: str, ros_env: dict[str, str], tmp_path: Path) -> None:
    """40 topics, about 10 rows on screen: the master lists the monitor on exactly the rows shown, as they change.

    Run against `rostui core` and a real roscore.
    """
    many = ManyTopics(ros_env, tmp_path, "/many", 40, 5)

    async def subscribed_on_master_are_shown(app: MonitorApp, what: str) -> set[str]:
        seen: list[set[str]] = []

        def same() -> bool:
            seen[:] = [master_subscriptions(ros_env)]
            return seen[0] == set(app.table.visible_topics()) and bool(seen[0])
        await until(same, what, DEADLINE)
        return seen[0]

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: len([n for n in app.table.names if n.startswith("/many/")]) == 40, "40 topics", DEADLINE)
        await pilot.press("home")
        first = await subscribed_on_master_are_shown(app, "subscriptions = rows on screen")
        assert "/many/t000" in first and "/many/t039" not in first and 3 < len(first) < 20
        assert app.source.subscribed == first
        await pilot.press("end")
        last = await subscribed_on_master_are_shown(app, "subscriptions follow the scroll")
        assert "/many/t039" in last and "/many/t000" not in last
        await pilot.press("slash", *"t01", "enter")
        assert await subscribed_on_master_are_shown(app, "subscriptions follow the filter") == \
            {f"/many/t01{i}" for i in range(10)}
        await live(app, "/many/t015")

    try:
        run(MonitorApp(period=0.3), scenario, size=(100, 16))
    finally:
        many.stop()
    assert master_subscriptions(ros_env) == set(), "the monitor left subscriptions behind"


def test_rate_matches_rostui_topic_hz(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """On a steady 25 Hz publisher the monitor's rate is within 2 % of what `rostui topic hz` prints."""
    pubs = start_publishers(ros_env, tmp_path, [("/steady", "std_msgs/String", "data: tick", 25)])
    hz_out = (tmp_path / "hz.txt").open("w")
    # the monitor's rate is over the last 10 s of arrivals: topic hz gets the same window (250 messages at 25 Hz),
    # so a publisher slowed for a moment on a busy machine moves both alike (and a stalled screen does not lift
    # the monitor's: tests/test_monitor_core.py)
    hz = subprocess.Popen(rostui_cmd("topic", "hz", "-w", "250", "/steady"), env=ros_env, stdout=hz_out,
                          stderr=subprocess.STDOUT, text=True)
    rates: dict[str, float] = {}

    def hz_rates() -> list[float]:
        return [float(x) for x in re.findall(r"average rate: ([\d.]+)", (tmp_path / "hz.txt").read_text())]

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await live(app, "/steady")
        await until(lambda: len(hz_rates()) >= 12, "twelve rostui topic hz reports (a full window)", DEADLINE)
        reports = len(hz_rates())
        await until(lambda: len(hz_rates()) > reports, "the next report, read with the monitor's row", DEADLINE)
        rates["monitor"] = row(app, "/steady").rate
        rates["hz"] = hz_rates()[-1]

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        stop_process(hz)
        hz_out.close()
        stop_all(pubs)
    assert rates["monitor"] == pytest.approx(rates["hz"], rel=0.02), rates
    assert rates["hz"] == pytest.approx(25, rel=0.1)


def test_dead_publisher_marks_topic_stale(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """A publisher killed (it cannot unregister): its row turns stale, and so does its expanded tree."""
    pub = Publisher(ros_env, tmp_path, "/dying", "std_msgs/String", "data: alive", 10)

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await live(app, "/dying")
        await until(lambda: "alive" in str(app.message_trees.topic_node("/dying").children[0].label),
                    "the message tree", DEADLINE)
        pub.kill()
        await until(lambda: row(app, "/dying").liveness is Liveness.STALE, "the row marked stale", DEADLINE)
        assert row(app, "/dying").cells()[-1] == "✖ stale" and row(app, "/dying").rate is None
        assert len(row(app, "/dying").publishers) == 1, "the master still lists the dead publisher"
        await until(lambda: "stale" in str(app.message_trees.topic_node("/dying").label), "the tree marked stale",
                    DEADLINE)

    try:
        run(MonitorApp(["/dying"], period=0.3), scenario)
    finally:
        if pub.proc.poll() is None:
            pub.stop()


def test_expand_tree_constants_and_plot(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """Enter expands a Log topic: level 2 shows as INFO, 12 topics show 8 and a count; f plots a number.

    f on the table's row opens the chooser of its numeric fields (nothing chosen: nothing plotted).
    """
    pubs = start_publishers(ros_env, tmp_path, [
        ("/log", "rosgraph_msgs/Log", "{level: 2, msg: ready, line: 42, topics: [a,b,c,d,e,f,g,h,i,j,k,l]}", 5),
    ])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await live(app, "/log")
        assert app.table.select_topic("/log")
        await pilot.press("enter")
        assert app.expanded == ["/log"]
        tree = app.message_trees

        def labels() -> list[str]:
            node = tree.topic_node("/log")
            return [str(c.label) for c in node.children] if node else []
        await until(lambda: "level: 2 (INFO)" in labels(), "level shown as INFO", DEADLINE)
        assert "msg: 'ready'" in labels() and "topics: string[12]" in labels()
        topics = next(c for c in tree.topic_node("/log").children if str(c.label).startswith("topics"))
        assert [str(c.label) for c in topics.children][-1] == "… 4 more"
        await pilot.press("f")
        await until(lambda: isinstance(app.screen, FieldChooser), "the chooser of /log's numeric fields", DEADLINE)
        await pilot.press("escape")
        await pilot.press("tab")
        assert app.focused is tree
        line = next(c for c in tree.topic_node("/log").children if str(c.label).startswith("line"))
        tree.move_cursor(line)
        await pilot.press("f")
        assert [s.name for s in app.source.plot.series] == ["/log/line"] and app.query_one("#plot").display
        await until(lambda: "range 42 … 42" in screen_text(app, "#plot-heading"), "the plotted value", DEADLINE)
        assert "/log" in str(app.query_one("#chart-title", Static).render())
        await pilot.press("shift+tab", "enter")
        assert app.expanded == [] and not app.query_one("#detail").display

    try:
        run(MonitorApp(period=0.3), scenario, size=(120, 40))
    finally:
        stop_all(pubs)


def test_publish_once_and_at_rate(rostui_core: Any, ros_env: dict[str, str]) -> None:
    """p opens the editor: a type fills the template, ctrl+s sends the edited message, ctrl+r repeats and stops."""
    watcher = Watcher()
    heard = watcher.record("/chatter", "std_msgs/String")

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: app.source.state.status == "connected", "the master", DEADLINE)
        await pilot.press("p")
        editor = app.screen
        assert isinstance(editor, PublishEditor)
        editor.query_one("#pub-topic", Input).value = "/chatter"
        editor.query_one("#pub-type", Input).value = ""
        editor.query_one("#pub-type", Input).focus()
        await pilot.pause()
        await pilot.press(*"std_msgs/Strin", "enter")
        assert "invalid message type: std_msgs/Strin" in str(editor.query_one("#pub-status", Static).render())
        await pilot.press("g", "enter")
        await pilot.pause()
        area = editor.query_one("#pub-yaml", TextArea)
        assert area.text == "data: ''\n" and app.focused is area
        area.load_text("data: [unclosed")
        await pilot.press("ctrl+s")
        assert "YAML error: message:1:" in str(editor.query_one("#pub-status", Static).render())
        area.load_text("data: hello from the monitor")
        await pilot.press("ctrl+s")
        await until(lambda: any(m.data == "hello from the monitor" for m in heard.messages), "the message sent",
                    DEADLINE)
        assert len(heard.messages) == 1
        editor.query_one("#pub-rate", Input).value = "20"
        await pilot.press("ctrl+r")
        await until(lambda: len(heard.messages) >= 11, "ten more messages at 20 Hz", DEADLINE)
        assert "publishing /chatter 20 Hz" in screen_text(app, "#status")
        await live(app, "/chatter")
        # The rate window (10 s) still holds the message sent once before the repeater started, so the
        # measured rate climbs to 20 Hz as repeated messages outnumber that gap.
        await until(lambda: row(app, "/chatter").rate == pytest.approx(20, rel=0.25),
                    "the monitor measuring its own publisher at 20 Hz", DEADLINE)
        await pilot.press("ctrl+r")
        assert "stopped publishing /chatter" in str(editor.query_one("#pub-status", Static).render())
        count = len(heard.messages)
        await asyncio.sleep(0.5)
        assert len(heard.messages) <= count + 1
        await pilot.press("escape")
        assert app.screen is not editor

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        watcher.close()


def test_no_master_says_so_and_waits(ros_env: dict[str, str]) -> None:
    """Without a master the app opens, says so in red and keeps trying (as `rostui graph` does)."""
    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: "waiting for master" in screen_text(app, "#banner"), "the banner", DEADLINE)
        assert "rostui core" in screen_text(app, "#banner") and app.table.names == []

    run(MonitorApp(period=0.3), scenario)


def test_bad_command_line_is_one_line(ros_env: dict[str, str]) -> None:
    """A bad topic name or period: one line on stderr, exit status 1, no screen."""
    for args, words in ((["monitor", "bad name"], "invalid ROS topic 'bad name'"),
                        (["monitor", "--period", "0"], "--period must be a positive number")):
        result = rostui(args, ros_env)
        assert result.returncode == 1 and words in result.stderr and result.stderr.count("\n") == 1, result


def test_master_restart(ros_env: dict[str, str], tmp_path: Path) -> None:
    """The master goes away: a red line says so and the last rows stay; a new master is found and polled."""
    core = start_rostui_core(ros_env)

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        nonlocal core
        await until(lambda: "/rosout" in app.table.names, "the first master's topics", DEADLINE)
        stop_process(core)
        await until(lambda: "gone: waiting for it to come back" in screen_text(app, "#banner"), "the lost master",
                    DEADLINE)
        assert "/rosout" in app.table.names and "✖ master" in screen_text(app, "#status")
        core = start_rostui_core(ros_env)
        watcher = Watcher("after_restart")
        try:
            watcher.publisher("/after", "std_msgs/String")
            await until(lambda: "/after" in app.table.names and app.source.state.status == "connected",
                        "the new master's topics", DEADLINE)
            assert not app.query_one("#banner").display
        finally:
            watcher.close()

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        stop_process(core)


def test_command_line_does_not_import_textual(ros_env: dict[str, str]) -> None:
    """Registering `rostui monitor` keeps `rostui topic list` and friends free of Textual."""
    code = ("import sys, rostui.cli.main; "
            "print(sorted({m.split('.')[0] for m in sys.modules} & {'textual'}), "
            "'rostui.models.monitor' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], env=ros_env, capture_output=True, text=True, timeout=60)
    assert result.stdout.strip() == "[] False", result
