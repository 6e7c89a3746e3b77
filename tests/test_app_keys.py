"""The keys every app shares (issue 21): ``?``/F1 help, Ctrl-C quits cleanly, ctrl+p palette, the key line.

Each app runs for real against a `rostui core` master (the launch monitor
runs a one-node launch, bag view a small bag); the tests press keys with the
pilot.  Ctrl-C must leave with exit status 0 after the same release as ``q``:
every node the app registered is gone from the master afterwards.
"""

from __future__ import annotations

import asyncio
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

import pytest
from textual.app import App
from textual.message import Message
from textual.widgets import Static
from textual.command import CommandPalette
from textual.pilot import Pilot

from bag_view_helpers import write_counts
from conftest import until
from launch_tui_helpers import monitor, pids_of_launch, still_alive, tui_env, write_launch  # noqa: F401
from loggers_helpers import DEADLINE, listed_nodes

from rostui.apps.bagview.app import BagViewApp
from rostui.apps.bagview.record_app import BagRecordApp
from rostui.apps.console.app import ConsoleApp
from rostui.apps.graph.app import GraphApp
from rostui.apps.launchmon.app import LaunchMonitorApp
from rostui.apps.loggers.app import LoggersApp
from rostui.apps.loggers.panels import LevelList, LoggerTable, NodeList
from rostui.apps.monitor.app import MonitorApp
from rostui.apps.diagnostics.app import DiagnosticsApp
from rostui.apps.reconfigure.app import ReconfigureApp
from rostui.apps.top.app import TopApp
from rostui.apps.action.app import ActionApp
from rostui.apps.form.app import FormApp
from rostui.apps.widgets.app_keys import KeysApp
from rostui.apps.widgets.help import HelpScreen
from rostui.apps.widgets.keys import ESSENTIAL_KEYS
from rostui.tools.bag.recorder import RecordOptions
from rostui.core.xmlrpc import call_sync, ros_result
from rostui.models.graph.view import GraphOptions
from rostui.turtlesim.app import TurtlesimApp

SIZE = (80, 24)


@dataclass(frozen=True)
class Case:
    """How to start one app, when it is ready, and one of its hidden keys as the help lists it."""

    make: Callable[[Path], App[int]]
    hidden: str
    ready: Callable[[Any], bool] = lambda app: True


def _launch(tmp: Path) -> LaunchMonitorApp:
    return monitor(write_launch(tmp / "one.launch", '<node pkg="tuitest" type="quiet" name="worker"/>'))


CASES: dict[str, Case] = {
    "graph": Case(lambda tmp: GraphApp(GraphOptions(), period=0.2), "1  nodes only", lambda app: app.polls >= 1),
    "console": Case(lambda tmp: ConsoleApp(), "1  DEBUG on/off",
                    lambda app: app.source is not None and app.source.state.status.name == "CONNECTED"),
    "loggers": Case(lambda tmp: LoggersApp(node_period=0.3, ping_period=0.5, timeout=2.0), "d  DEBUG",
                    lambda app: app.started.is_set()),
    "monitor": Case(lambda tmp: MonitorApp(period=0.3), "x  collapse topic",
                    lambda app: app.source.state.status.name == "CONNECTED"),
    "bag view": Case(lambda tmp: BagViewApp([str(write_counts(tmp / "counts.mcap", 20))], publish_all=True),
                     "0  go to 0%",
                     lambda app: app.node is not None),
    "bag record": Case(lambda tmp: BagRecordApp(RecordOptions(topics=["/counts"],
                                                              output_name=str(tmp / "rec.mcap"))),
                       "n  split", lambda app: app.session.recording),
    "launch": Case(_launch, "tab  log/table", lambda app: bool(app.rows) and
                   all(row.state == "running" for row in app.rows.values())),
    "turtlesim": Case(lambda tmp: TurtlesimApp(), "↑ / ↓  drive forward / backward",
                      lambda app: app.started.is_set()),
    "reconfigure": Case(lambda tmp: ReconfigureApp(server_period=0.3), "shift+→  a number ten steps up",
                        lambda app: app.source.servers_read),
    "diagnostics": Case(lambda tmp: DiagnosticsApp(), "↑/↓ PgUp/PgDn  move between statuses",
                        lambda app: app.source.state.status.name == "CONNECTED"),
    "top": Case(lambda tmp: TopApp(interval=0.3), "↑/↓ PgUp/PgDn  move between nodes", lambda app: app.polls >= 1),
    "action": Case(lambda tmp: ActionApp(period=0.3), "^x  cancel the goal running", lambda app: app.polls >= 1),
    "publish": Case(lambda tmp: FormApp("publish", name="/keys_words", type_name="std_msgs/String"),
                    "shift+→  slider up ×10", lambda app: app.ready.is_set()),
    "call": Case(lambda tmp: FormApp("call", name="/rosout/get_loggers"), "^o  load a form from YAML",
                 lambda app: app.form is not None),
}


@pytest.fixture
def master(rostui_core: Any, tui_env: dict[str, str]) -> dict[str, str]:
    """A `rostui core` and an environment with the launch tests' package (for the launch monitor)."""
    return tui_env


def master_nodes(env: dict[str, str]) -> set[str]:
    """Every node the master lists (publishers, subscribers, services)."""
    state = ros_result(call_sync(env["ROS_MASTER_URI"], "getSystemState", "/keys_test", timeout=5.0))
    return {node for kind in state for _name, nodes in kind for node in nodes}


def run(name: str, tmp: Path, scenario: Callable[[Pilot, Any], Any]) -> App[int]:
    """Run app ``name`` at 80x24 until it is ready, play ``scenario``, and return the app once it has ended."""
    case = CASES[name]
    app = case.make(tmp)

    async def main() -> None:
        async with app.run_test(size=SIZE) as pilot:
            await until(lambda: case.ready(app), f"{name} ready", timeout=DEADLINE)
            await pilot.pause()
            await scenario(pilot, app)
            if app.is_running:
                await app.action_quit()  # type: ignore[attr-defined]

    asyncio.run(main())
    return app


def key_line(app: App[int]) -> str:
    """The key line as shown (the loggers' Footer: its keys and descriptions)."""
    if isinstance(app, LoggersApp):
        from textual.widgets._footer import FooterKey

        return "  ".join(f"{key.key_display} {key.description}" for key in app.query(FooterKey))
    widget = app.query_one("#status" if isinstance(app, TurtlesimApp) else "#keys")
    return getattr(widget, "plain", None) or str(widget.render())


@pytest.mark.parametrize("name", list(CASES))
@pytest.mark.parametrize("key", ["question_mark", "f1"])
def test_help_lists_every_key(master: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                              name: str, key: str) -> None:
    """? and F1 open the help panel listing help, quit and a hidden key; Escape, ? and q close it."""
    monkeypatch.chdir(tmp_path)
    shown: list[str] = []

    async def scenario(pilot: Pilot, app: Any) -> None:
        for close in ("escape", "question_mark", "q"):
            await pilot.press(key)
            await until(lambda: isinstance(app.screen, HelpScreen), "the help panel")
            shown.append(app.screen.text)
            await pilot.press(close)
            await until(lambda: not isinstance(app.screen, HelpScreen), f"{close} to close the help")
            assert app.is_running, f"{close} in the help panel closed the app"

    run(name, tmp_path, scenario)
    text = shown[0]
    assert "? / f1  help" in text
    if name == "turtlesim":  # q asks first while other nodes use the master it started; Ctrl-C never asks
        assert "^c / ^q  quit" in text and "q  quit (twice while other nodes use the master it started)" in text
    else:
        assert "q / ^c / ^q  quit" in text
    assert CASES[name].hidden in text, text


@pytest.mark.parametrize("name", list(CASES))
def test_ctrl_c_quits_cleanly(master: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                              name: str) -> None:
    """Ctrl-C leaves at once with status 0, no notice, and every node of the app gone from the master."""
    monkeypatch.chdir(tmp_path)
    before = master_nodes(master)
    during: set[str] = set()
    pids: set[int] = set()

    async def scenario(pilot: Pilot, app: Any) -> None:
        during.update(master_nodes(master))
        if isinstance(app, LaunchMonitorApp):
            pids.update(pids_of_launch(app))
        await pilot.press("ctrl+c")
        await until(lambda: not app.is_running, "the app to end after ctrl+c")

    app = run(name, tmp_path, scenario)
    assert app.return_code == 0
    assert not app._notifications, "ctrl+c showed a notice instead of quitting"
    if isinstance(app, (GraphApp, ConsoleApp, LoggersApp, MonitorApp, BagViewApp, BagRecordApp, TurtlesimApp)):
        assert app.released
    if name in ("console", "monitor", "bag view", "bag record"):
        assert during - before, f"{name} registered no node, so the test checks nothing"
    if name == "launch":
        assert pids, "the launch ran no process, so the test checks nothing"
        assert not still_alive(pids), "the launch's nodes outlived ctrl+c"
    if name != "turtlesim":  # turtlesim uses the test's master; its own nodes must be gone from it
        assert master_nodes(master) <= before, f"left registered: {master_nodes(master) - before}"
    else:
        assert not {"/turtlesim", "/teleop_turtle"} & master_nodes(master)


@pytest.mark.parametrize("name", list(CASES))
def test_key_line_starts_with_help_and_quit(master: dict[str, str], tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    """At 80x24 the key line starts with ``? help`` and ``q quit`` (turtlesim: its status line holds them)."""
    monkeypatch.chdir(tmp_path)
    lines: list[str] = []

    async def scenario(pilot: Pilot, app: Any) -> None:
        await pilot.pause()
        lines.append(key_line(app))

    run(name, tmp_path, scenario)
    line = lines[0]
    if name == "turtlesim":
        assert f"│ {ESSENTIAL_KEYS}  " in line.splitlines()[0]
    elif name == "loggers":
        assert line.startswith("? help  q quit"), line
    else:
        assert line.startswith(ESSENTIAL_KEYS), line


@pytest.mark.parametrize("name", list(CASES))
def test_palette_runs_an_action(master: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                name: str) -> None:
    """ctrl+p opens the palette with the app's actions; choosing "help" runs it (the help panel opens)."""
    monkeypatch.chdir(tmp_path)

    async def scenario(pilot: Pilot, app: Any) -> None:
        await pilot.press("ctrl+p")
        await until(lambda: isinstance(app.screen, CommandPalette), "the command palette")
        await pilot.press(*"help")
        await pilot.pause(0.3)
        await pilot.press("enter")
        await until(lambda: isinstance(app.screen, HelpScreen), "the help panel run from the palette")
        await pilot.press("escape")

    run(name, tmp_path, scenario)


@pytest.mark.parametrize("name,query,effect", [
    ("console", "pause", lambda app: app.model.paused),
    ("graph", "hide leaf", lambda app: app.options.hide_leaf_topics),
    ("bag view", "loop", lambda app: app.transport.loop),
])
def test_palette_runs_the_apps_own_action(master: dict[str, str], tmp_path: Path, name: str, query: str,
                                          effect: Callable[[Any], bool]) -> None:
    """A command found by its description does what its key does."""
    async def scenario(pilot: Pilot, app: Any) -> None:
        assert not effect(app)
        await pilot.press("ctrl+p")
        await until(lambda: isinstance(app.screen, CommandPalette), "the command palette")
        await pilot.press(*query)
        await pilot.pause(0.3)
        await pilot.press("enter")
        await until(lambda: effect(app), f"{query!r} run from the palette")

    run(name, tmp_path, scenario)


def test_loggers_enter_works_without_an_arrow_key(master: dict[str, str], tmp_path: Path) -> None:
    """The first node is selected at start: Enter goes to its loggers, Enter again to the levels."""
    async def scenario(pilot: Pilot, app: Any) -> None:
        await until(lambda: bool(listed_nodes(app)), "nodes listed")
        first = listed_nodes(app)[0]
        await until(lambda: app.node == first and bool(app.loggers), f"{first} selected with its loggers")
        assert isinstance(app.focused, NodeList)
        await pilot.press("enter")
        assert isinstance(app.focused, LoggerTable)
        await until(lambda: bool(app.logger), "a logger selected")
        await pilot.press("enter")
        assert isinstance(app.focused, LevelList)

    run("loggers", tmp_path, scenario)


def test_help_and_ctrl_c_over_the_publish_editor(master: dict[str, str], tmp_path: Path) -> None:
    """Over the monitor's publish editor: F1 lists the editor's keys, Escape closes only the help, Ctrl-C quits."""
    from rostui.apps.monitor.editor import PublishEditor

    async def scenario(pilot: Pilot, app: Any) -> None:
        await pilot.press("p")
        await until(lambda: isinstance(app.screen, PublishEditor), "the publish editor")
        await pilot.press("f1")
        await until(lambda: isinstance(app.screen, HelpScreen), "the help over the editor")
        text = app.screen.text
        quit_line = next(line for line in text.splitlines() if line.endswith("  quit"))
        assert "^s  send once" in text and "^c" in quit_line.split("  ")[0], text
        await pilot.press("escape")
        await until(lambda: isinstance(app.screen, PublishEditor), "Escape to close only the help")
        await pilot.press("ctrl+c")
        await until(lambda: not app.is_running, "the app to end after ctrl+c in the editor")

    app = run("monitor", tmp_path, scenario)
    assert app.return_code == 0 and app.released


class LateWidget(Static):
    """A widget that, as it is removed at shutdown, sends the app a message (as a table sends a row highlight)."""

    class Late(Message):
        """Handled by the app after the widgets are gone."""

    def on_unmount(self) -> None:
        """Queue the message for the app while Textual is taking the screen down."""
        self.app.post_message(self.Late())


class LateMessageApp(KeysApp):
    """An app whose handler needs its widget, as loggers' row highlight handler does."""

    def __init__(self) -> None:
        super().__init__()
        self.late_handled = 0

    def compose(self) -> Any:
        """One widget."""
        yield LateWidget("late", id="late")

    def on_late_widget_late(self) -> None:
        """Read the widget (NoMatches once it is gone)."""
        self.query_one("#late", LateWidget)
        self.late_handled += 1


def test_messages_left_for_the_app_after_its_widgets_are_gone_are_not_handled() -> None:
    """A loaded fresh-ci run: the loggers app handled a row highlight after quitting had removed its panels
    and crashed with NoMatches. Once shutdown has begun, the app's handlers get no more widget messages."""
    app = LateMessageApp()

    async def main() -> None:
        async with app.run_test() as pilot:
            await pilot.pause()
            app.post_message(LateWidget.Late())  # while running: handled
            await until(lambda: app.late_handled == 1, "the message handled while the app runs")

    asyncio.run(main())
    assert app.return_code in (None, 0) and app.late_handled == 1


def test_status_parts_wrap_between_parts_never_inside_one() -> None:
    """A status line too long for its width breaks before the part that would cross it."""
    from rostui.apps.widgets.bar_text import join_parts

    parts = ["Nodes/Topics (all) · hide debug", "2 nodes · 4 topics", "● master", "arrows scroll"]
    assert join_parts(parts, 100) == " │ ".join(parts)
    assert join_parts(parts, 70) == " │ ".join(parts[:3]) + "\narrows scroll"
    assert join_parts(parts, 10) == "\n".join(parts)
    assert join_parts(parts, 0) == " │ ".join(parts)
