"""The monitor's plot panel driven with Textual's pilot: its keys, the field chooser and rqt_plot-style arguments.

A real `rostui core` master and real `rostui topic pub -r` processes (a
turtlesim/Pose and a rosgraph_msgs/Log); what is plotted is read from the
app's PlotModel and from the panel's heading line.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from cli_helpers import rostui
from conftest import until
from monitor_helpers import Scenario, run_monitor, start_publishers, stop_all
from textual.pilot import Pilot
from textual.widgets import SelectionList, Static

from rostui.apps.monitor.app import MonitorApp
from rostui.apps.monitor.plot import FieldChooser, PlotPanel

DEADLINE = 30.0
POSE = ("/turtle1/pose", "turtlesim/Pose", "{x: 5.5, y: 2.5, theta: 0.5, linear_velocity: 1.0}", 20)
LOG = ("/log", "rosgraph_msgs/Log", "{level: 2, msg: ready, line: 42}", 5)


def run(app: MonitorApp, scenario: Scenario, size: tuple[int, int] = (120, 40)) -> None:
    """Run ``app`` headless at 120x40 (room for the plot), play ``scenario``, quit with q."""
    run_monitor(app, scenario, size)


def text_of(app: MonitorApp, selector: str) -> str:
    """The plain text a Static shows."""
    return str(app.query_one(selector, Static).render())


def plotted(app: MonitorApp) -> list[str]:
    """The plotted fields, as rqt_plot names them."""
    return [s.name for s in app.source.plot.series]


async def live(app: MonitorApp, topic: str) -> None:
    """Wait until ``topic`` has a row with a decoded message."""
    def ready() -> bool:
        try:
            return app.source.latest(topic) is not None
        except Exception:
            return False
    await until(ready, f"a message on {topic}", DEADLINE)


async def choose(pilot: Pilot, app: MonitorApp, *toggles: int) -> FieldChooser:
    """In the open chooser, check or uncheck the items at ``toggles`` (indexes) with the keyboard; returns it."""
    await until(lambda: isinstance(app.screen, FieldChooser), "the field chooser", DEADLINE)
    chooser = app.screen
    assert isinstance(chooser, FieldChooser)
    options = chooser.query_one(SelectionList)
    for index in toggles:
        options.highlighted = index
        await pilot.press("space")
    return chooser


def test_plot_keys(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """f on a topic opens its numeric fields; add and remove fields; v hides and shows; + and - the window;
    space pauses (points keep counting, the picture stands) and resumes."""
    pubs = start_publishers(ros_env, tmp_path, [POSE, LOG])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        panel = app.query_one("#plot", PlotPanel)
        assert not panel.display, "no plot before a field is chosen"
        await until(lambda: app.table.select_topic("/turtle1/pose"), "the pose row", DEADLINE)
        await live(app, "/turtle1/pose")
        await pilot.press("f")
        chooser = await choose(pilot, app, 0, 1)
        assert [path for path, _ in chooser.fields] == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
        assert chooser.fields[0] == ("x", "5.5")
        await pilot.press("v", "plus")  # letters in the chooser are not the app's keys
        assert app.source.plot.window == 10.0 and not panel.display
        await pilot.press("enter")
        assert plotted(app) == ["/turtle1/pose/x", "/turtle1/pose/y"] and panel.display
        await until(lambda: text_of(app, "#plot-heading").startswith("2 fields  │  last 10 s  │  range 2.5 … 5.5"),
                    "the heading with the value range", DEADLINE)
        assert all(v.last in (5.5, 2.5) for v in app.source.plot.view(app.clock()))

        await pilot.press("plus")
        assert app.source.plot.window == 20.0 and "last 20 s" in text_of(app, "#plot-heading")
        await pilot.press("minus", "minus")
        assert app.source.plot.window == 5.0 and "plot window 5 s" in text_of(app, "#status")

        await pilot.press("space")
        plot = app.source.plot
        assert plot.paused
        frozen = plot.view(app.clock())
        await until(lambda: plot.since_pause >= 6, "points counted while paused", DEADLINE)
        assert plot.view(app.clock()) == frozen
        await until(lambda: "paused (" in text_of(app, "#plot-heading") and
                    "new points)" in text_of(app, "#plot-heading"), "the pause in the heading", DEADLINE)
        await pilot.press("space")
        assert not plot.paused and "▶ live" in text_of(app, "#plot-heading")

        await pilot.press("v")
        assert not panel.display
        await pilot.press("v")
        assert panel.display

        await pilot.press("f")
        await choose(pilot, app, 1, 2)  # uncheck y, check theta
        await pilot.press("escape")
        assert plotted(app) == ["/turtle1/pose/x", "/turtle1/pose/theta"]

        # a number in the tree: f plots it, f again stops; a string is refused with a clear line
        assert app.table.select_topic("/log")
        await live(app, "/log")
        await pilot.press("enter", "tab")
        tree = app.message_trees
        await until(lambda: any(str(c.label).startswith("line") for c in tree.topic_node("/log").children),
                    "the Log tree", DEADLINE)
        line = next(c for c in tree.topic_node("/log").children if str(c.label).startswith("line"))
        tree.move_cursor(line)
        await pilot.press("f")
        assert plotted(app)[-1] == "/log/line" and "plotting /log/line" in text_of(app, "#status")
        await pilot.press("f")
        assert "/log/line" not in plotted(app) and "stopped plotting /log/line" in text_of(app, "#status")
        msg = next(c for c in tree.topic_node("/log").children if str(c.label).startswith("msg"))
        tree.move_cursor(msg)
        await pilot.press("f")
        assert "/log/msg is a string, not a number: only numeric fields can be plotted" in text_of(app, "#status")
        assert "/log/msg" not in plotted(app)

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        stop_all(pubs)


def test_fields_on_the_command_line(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """`rostui monitor /turtle1/pose/x:theta /log /turtle1/pose/name`: pose fields plotted, /log expanded,
    a field the message lacks said in the panel."""
    pubs = start_publishers(ros_env, tmp_path, [POSE, LOG])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: not app.pending, "the names told apart", DEADLINE)
        assert plotted(app) == ["/turtle1/pose/x", "/turtle1/pose/theta", "/turtle1/pose/name"]
        assert app.expanded == ["/log"]
        await until(lambda: "✖ /turtle1/pose/name: no field 'name' in turtlesim/Pose" in text_of(app, "#plot-notes"),
                    "the missing field said", DEADLINE)
        await until(lambda: text_of(app, "#plot-heading").startswith("3 fields  │  last 10 s  │  range 0.5 … 5.5"),
                    "x and theta plotted", DEADLINE)

    try:
        app = MonitorApp(["/turtle1/pose/x:theta", "/log", "/turtle1/pose/name"], period=0.3)
        # Before the master is asked, a name without a colon may be a topic: it starts expanded.
        assert app.expanded == ["/log", "/turtle1/pose/name"] and app.plot_open
        run(app, scenario)
    finally:
        stop_all(pubs)


def test_nothing_to_choose(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> None:
    """f on a topic without a message yet, and on a message without numbers, says why instead of opening."""
    pubs = start_publishers(ros_env, tmp_path, [("/words", "std_msgs/String", "data: hi", 10)])

    async def scenario(pilot: Pilot, app: MonitorApp) -> None:
        await until(lambda: app.table.select_topic("/words"), "the /words row", DEADLINE)
        await live(app, "/words")
        await pilot.press("f")
        assert not isinstance(app.screen, FieldChooser)
        assert "/words (std_msgs/String) has no numeric fields to plot" in text_of(app, "#status")
        assert app.table.select_topic("/rosout")
        await pilot.press("f")
        assert "no message on /rosout yet" in text_of(app, "#status")

    try:
        run(MonitorApp(period=0.3), scenario)
    finally:
        stop_all(pubs)


def test_bad_field_arguments_are_one_line(ros_env: dict[str, str]) -> None:
    """A bad field after rqt_plot's ':' or a bad topic part: one line on stderr, exit status 1."""
    for arg, words in (("/turtle1/pose/x:9", "'9' after ':' is not a field name"),
                       ("/turtle1/po se/x:y", "invalid ROS topic"),
                       (":x", "is not a topic name")):
        result = rostui(["monitor", arg], ros_env)
        assert result.returncode == 1 and words in result.stderr and result.stderr.count("\n") == 1, result
