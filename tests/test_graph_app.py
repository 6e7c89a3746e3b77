"""`rostui graph` driven with Textual's pilot against a `rostui core` master and real node processes.

Every test runs the real :class:`GraphApp` (its own master polls, node info
and rate measurement) while the book's turtlesim system (headless turtlesim
and a teleop_turtle publishing at 2 Hz) runs as separate processes.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator

import pytest
from conftest import master_port, start_rostui_core, stop_process, until
from graph_helpers import (
    banner, book_system, details, empty_screen, has_edges, master_graph, run_graph, screen_text, settled, shown_names,
    status, stop_programs,
)
from live_helpers import Program, wait_until
from textual.pilot import Pilot

from rostui.apps.graph.app import GraphApp
from rostui.models.graph.live import Mark
from rostui.models.graph.model import RosGraph
from rostui.models.graph.view import GraphOptions, ViewMode, book_setup

FIGURE_2_4 = {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity", "/turtle1/cmd_vel", "/turtle1/pose",
              "/turtle1/color_sensor"}


@pytest.fixture
def book(rostui_core: Any, ros_env: dict[str, str], tmp_path: Path) -> Iterator[list[Program]]:
    """The book's turtlesim system on a `rostui core` master."""
    programs = book_system(ros_env, tmp_path)
    yield programs
    stop_programs(programs)


async def type_text(pilot: Pilot, text: str) -> None:
    """Press one key per character (what a user typing does)."""
    keys = {"/": "slash", "(": "left_parenthesis", ")": "right_parenthesis", "^": "circumflex_accent",
            "$": "dollar_sign", "|": "vertical_line", " ": "space", "_": "underscore", ".": "full_stop"}
    for ch in text:
        await pilot.press(keys.get(ch, ch))


def test_views_switch_with_v_and_number_keys(book: list[Program]) -> None:
    """Nodes only (Figure 2.2) -> v -> Nodes/Topics (active) -> v -> (all) (Figure 2.4) -> 1 -> nodes only."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim"}
        assert re.search(r"│ /teleop_turtle │─+ /turtle1/command_velocity ─+▶│ /turtlesim │", screen_text(app))
        assert "Nodes only · hide debug" in status(app)
        await pilot.press("v")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity"}
        assert "Nodes/Topics (active)" in status(app)
        await pilot.press("v")
        await settled(app)
        assert shown_names(app) == FIGURE_2_4
        assert "┌──" in screen_text(app) and "/turtle1/color_sensor" in screen_text(app)
        await pilot.press("1")
        await settled(app)
        assert app.options.view is ViewMode.NODES and shown_names(app) == {"/teleop_turtle", "/turtlesim"}
        await pilot.press("q")

    app = GraphApp(period=0.5)
    run_graph(app, scenario)
    assert app.return_code == 0


def test_hide_debug_toggle_shows_rosout_like_figure_2_3(book: list[Program]) -> None:
    """d: the /rosout node appears with every node's edge to it; d again hides it."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert "/rosout" not in shown_names(app)
        await pilot.press("d")
        await settled(app)
        assert {"/rosout", "/teleop_turtle", "/turtlesim"} <= shown_names(app)
        edges = {(app.shown.vertices[a].name, app.shown.vertices[b].name) for a, b in app.shown.edges}
        assert {("/teleop_turtle", "/rosout"), ("/turtlesim", "/rosout")} <= edges
        assert "hide debug" not in status(app)
        await pilot.press("d")
        await settled(app)
        assert "/rosout" not in shown_names(app) and "hide debug" in status(app)

    run_graph(GraphApp(period=0.5), scenario)


def test_book_setup_is_one_key_away(book: list[Program]) -> None:
    """b from a cluttered setup (debug shown, leaves hidden, grouped, filtered): Figure 2.4 exactly."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert "/rosout" in shown_names(app) and "/turtle1/pose" not in shown_names(app)
        await pilot.press("b")
        await settled(app)
        assert app.options == book_setup()
        assert shown_names(app) == FIGURE_2_4
        assert "Nodes/Topics (all) · hide debug" in status(app)

    cluttered = GraphOptions(view=ViewMode.ACTIVE, hide_debug=False, hide_leaf_topics=True, group_namespaces=True,
                             exclude="color")
    run_graph(GraphApp(cluttered, period=0.5), scenario)


def test_toggles_for_dead_sinks_and_leaf_topics(book: list[Program]) -> None:
    """s hides the topics nobody subscribes to; l hides the topics only one node uses."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        await pilot.press("s")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity", "/turtle1/cmd_vel"}
        await pilot.press("s", "l")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity"}
        assert "hide leaf topics" in status(app)

    run_graph(GraphApp(book_setup(), period=0.5), scenario)


def test_include_and_exclude_filters_apply_per_keystroke(book: list[Program]) -> None:
    """i pose: the pose topic and its publisher; Esc undoes it; x (color) hides the sensor; Enter keeps it."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        await pilot.press("i")
        await type_text(pilot, "pos")
        await settled(app)
        assert shown_names(app) == {"/turtle1/pose", "/turtlesim"}
        await type_text(pilot, "e")
        await settled(app)
        assert app.options.include == "pose" and "include /pose/" in status(app)
        await pilot.press("escape")
        await settled(app)
        assert app.options.include == "" and shown_names(app) == FIGURE_2_4
        await pilot.press("x")
        await type_text(pilot, "(color")
        await pilot.pause()
        assert "bad exclude regex '(color'" in banner(app)
        assert shown_names(app) == FIGURE_2_4, "a bad pattern must leave the last good view"
        await type_text(pilot, ")")
        await settled(app)
        assert banner(app) == "" and shown_names(app) == FIGURE_2_4 - {"/turtle1/color_sensor"}
        await pilot.press("enter")
        await pilot.pause()
        assert not app.query_one("#prompt").display and app.options.exclude == "(color)"
        await pilot.press("v")  # keys reach the graph again
        await settled(app)
        assert app.options.view is ViewMode.NODES

    run_graph(GraphApp(book_setup(), period=0.5), scenario)


def test_group_by_namespace_collapses_and_expands(book: list[Program]) -> None:
    """g folds the four /turtle1 topics into one box; Enter on it expands; space on a member folds it again."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        await pilot.press("g")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim", "/turtle1"}
        assert "▸ /turtle1 (4)" in screen_text(app) and "╔" in screen_text(app)
        await pilot.press("slash")
        await type_text(pilot, "turtle1")
        await pilot.press("enter")
        assert app.selected == "g:/turtle1"
        assert "Namespace /turtle1" in details(app) and " * /turtle1/pose" in details(app)
        await pilot.press("enter")
        await settled(app)
        assert shown_names(app) == FIGURE_2_4
        await pilot.press("slash")
        await type_text(pilot, "pose")
        await pilot.press("enter", "space")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim", "/turtle1"}
        assert app.selected == "g:/turtle1"

    run_graph(GraphApp(book_setup(), period=0.5), scenario)


def test_search_jumps_to_an_element_off_screen(book: list[Program]) -> None:
    """In a 50x12 terminal: / pose selects /turtle1/pose and scrolls it into view."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        graph = app.graph_view
        box = graph.canvas.boxes["t:/turtle1/pose"]
        assert box.x + box.w > graph.scrollable_content_region.width, "the test needs pose off screen"
        await pilot.press("slash")
        await type_text(pilot, "pose")
        assert app.selected == "t:/turtle1/pose"
        await pilot.press("enter")
        await until(lambda: graph.scroll_offset.x > 0, "the view to scroll right")
        region = graph.scrollable_content_region
        x, y = graph.scroll_offset
        assert x <= box.x and box.x + box.w <= x + region.width + 44  # the details pane may cover the end
        assert y <= box.y + 1 < y + region.height
        await pilot.press("slash")
        await type_text(pilot, "zzz")
        assert "no match for 'zzz'" in status(app)
        assert app.selected == "t:/turtle1/pose"

    run_graph(GraphApp(book_setup(), period=0.5), scenario, size=(50, 12))


def test_arrows_scroll_a_wide_graph_several_cells_a_press(book: list[Program]) -> None:
    """In a 50x8 terminal the book's graph is larger than the screen: → moves 8 columns, ↓ 3 lines (one cell a
    press took a tutorial reader 45 presses to reach the recorder's box), ← and ↑ come back."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        graph = app.graph_view
        graph.focus()
        await until(lambda: graph.max_scroll_x > 16 and graph.max_scroll_y >= 3,
                    lambda: f"a graph larger than the screen: {graph.max_scroll_x} {graph.max_scroll_y} "
                            f"{graph.scrollable_content_region}")
        await pilot.press("right", "right")
        assert graph.scroll_offset.x == 16
        await pilot.press("down")
        assert graph.scroll_offset.y == 3
        await pilot.press("up", "left")
        assert (graph.scroll_offset.x, graph.scroll_offset.y) == (8, 0)

    run_graph(GraphApp(book_setup(), period=0.5), scenario, size=(50, 8))


def test_focus_mode_shows_neighbours_n_hops_out(book: list[Program]) -> None:
    """f on /teleop_turtle: it and its topic; + reaches turtlesim, + its topics; - back; f shows all again."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        await pilot.press("f")
        assert "select a node or topic first" in status(app)
        await pilot.press("slash")
        await type_text(pilot, "teleop")
        await pilot.press("enter", "f")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtle1/command_velocity"}
        assert "focus /teleop_turtle ±1" in status(app)
        await pilot.press("plus")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtle1/command_velocity", "/turtlesim"}
        await pilot.press("plus")
        await settled(app)
        assert shown_names(app) == FIGURE_2_4
        await pilot.press("minus", "minus")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtle1/command_velocity"}
        await pilot.press("f")
        await settled(app)
        assert shown_names(app) == FIGURE_2_4 and "focus" not in status(app)

    run_graph(GraphApp(book_setup(), period=0.5), scenario)


def test_selecting_shows_node_info_and_topic_rate(book: list[Program]) -> None:
    """A node: publications, subscriptions, services, URI and pid; a topic: type, ends and rate on demand."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        await pilot.press("tab")
        assert app.selected == "n:/teleop_turtle"
        await pilot.press("tab")
        assert app.selected == "t:/turtle1/command_velocity"
        await pilot.press("tab", "tab")  # reading order: column by column, top to bottom
        assert app.selected == "n:/turtlesim"
        await until(lambda: "Pid:" in details(app), "turtlesim's pid in the details")
        text = details(app)
        assert "Node /turtlesim" in text
        assert " * /turtle1/pose [turtlesim/Pose]" in text
        assert " * /turtle1/command_velocity [turtlesim/Velocity]" in text
        assert re.search(r"Services:\n(?: \* .*\n)* \* /turtlesim/set_logger_level", text)
        assert re.search(r"URI: http://127\.0\.0\.1:\d+/", text) and re.search(r"Pid: \d+", text)
        await pilot.press("slash")
        await type_text(pilot, "command_velocity")
        await pilot.press("enter")
        text = details(app)
        assert "Topic /turtle1/command_velocity" in text and "Type: turtlesim/Velocity" in text
        assert "Publishers:\n * /teleop_turtle" in text and "Subscribers:\n * /turtlesim" in text
        assert "Rate: press r to measure" in text
        await pilot.press("r")
        await until(lambda: "measuring" in details(app), "the measurement to start")
        await until(lambda: "average rate" in details(app), "the measured rate", timeout=30)
        rate = float(re.search(r"average rate: ([\d.]+) Hz", details(app)).group(1))
        assert 1.5 < rate < 2.5, "pubvel publishes at 2 Hz"
        await pilot.press("escape")
        assert app.selected is None and details(app) == ""

    run_graph(GraphApp(book_setup(), period=0.5, rate_seconds=3.0), scenario)


def test_live_marks_for_appearing_and_vanishing_nodes(book: list[Program], ros_env: dict[str, str],
                                                      tmp_path: Path) -> None:
    """agitr's subpose starts: its node is marked new (+); it stops: marked gone (×), then removed."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert app.graph_view.marks == {}
        sub = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
        try:
            await until(lambda: app.graph_view.marks.get("n:/subscribe_to_pose") is Mark.NEW,
                        "subscribe_to_pose marked new")
            await settled(app)
            canvas = app.graph_view.canvas
            box = canvas.boxes["n:/subscribe_to_pose"]
            line = app.graph_view.render_line(box.y - app.graph_view.scroll_offset.y)
            assert "╭+" in line.text
        finally:
            sub.stop()
        await until(lambda: app.graph_view.marks.get("n:/subscribe_to_pose") is Mark.GONE,
                    "subscribe_to_pose marked gone")
        assert "/subscribe_to_pose" in shown_names(app), "a vanished node stays a few refreshes"
        await until(lambda: "/subscribe_to_pose" not in shown_names(app), "subscribe_to_pose removed")

    run_graph(GraphApp(book_setup(), period=0.3, mark_refreshes=6), scenario)


def test_node_dying_while_selected(book: list[Program], ros_env: dict[str, str], tmp_path: Path) -> None:
    """Killed hard: Enter says the node does not answer; stopped cleanly: says it is gone; no crash."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        hard = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
        soft = Program(ros_env, tmp_path, "agitr", "count", label="count")
        try:
            await until(lambda: {"/subscribe_to_pose", "/count_and_log"} <= set(app.live.current.nodes()),
                        "both nodes in the graph")
            await settled(app)
            app.select("n:/subscribe_to_pose")
            await until(lambda: "Pid:" in details(app), "the node's pid")
            hard.proc.kill()
            hard.proc.wait()
            await pilot.press("enter")
            await until(lambda: "Communication with node" in details(app), "the unreachable node reported")
            assert app.is_running
            app.select("n:/count_and_log")
            await until(lambda: "Pid:" in details(app), "count_and_log's pid")
            soft.stop()
            await until(lambda: "/count_and_log is gone" in details(app), "the vanished node reported")
            await until(lambda: app.selected not in (app.shown.vertices if app.shown else {}),
                        "the ghost to leave the drawing")
            assert "/count_and_log is gone" in details(app)
        finally:
            hard.stop()
            soft.stop()

    run_graph(GraphApp(GraphOptions(view=ViewMode.ALL), period=0.3), scenario)


def test_master_going_away_and_coming_back(ros_env: dict[str, str], tmp_path: Path) -> None:
    """The master stops: a red line says so and the last graph stays; it restarts: the graph comes back."""
    port = master_port(ros_env)

    core = start_rostui_core(ros_env)
    programs = book_system(ros_env, tmp_path)
    restarted: list[subprocess.Popen] = []

    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert "● master" in status(app)
        stop_process(core)
        await until(lambda: app.master_ok is False, "the app to notice the master is gone")
        assert f"master unreachable at http://127.0.0.1:{port}" in banner(app)
        assert "retrying" in banner(app) and "✖ master" in status(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim"}, "the last graph stays on screen"
        restarted.append(start_rostui_core(ros_env))
        await until(lambda: app.master_ok is True, "the app to reach the restarted master")
        await until(lambda: banner(app) == "" and "master is back" in status(app), "the all-clear")
        sub = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
        try:
            await until(lambda: "/subscribe_to_pose" in shown_names(app), "a node registered after the restart")
        finally:
            sub.stop()

    try:
        run_graph(GraphApp(period=0.3), scenario)
    finally:
        stop_programs(programs)
        for proc in [core, *restarted]:
            stop_process(proc)


def test_empty_filter_result_says_so(book: list[Program]) -> None:
    """An include pattern nothing matches: the screen names what it hides and how to clear it; i clears it."""
    async def scenario(pilot: Pilot, app: GraphApp) -> None:
        assert shown_names(app) == set()
        assert banner(app) == ""
        text = empty_screen(app)
        assert "Nothing drawn, but the master has" in text
        assert "(/teleop_turtle, /turtlesim) and" in text
        assert "the include filter /^/no_such_node$/ matches none of them. Press i, clear the pattern" in text
        assert not app.graph_view.display
        await pilot.press("i")
        await pilot.press(*["backspace"] * len("^/no_such_node$"))
        await pilot.press("enter")
        await settled(app)
        assert shown_names(app) == {"/teleop_turtle", "/turtlesim"} and empty_screen(app) == ""
        assert app.graph_view.display and app.focused is app.graph_view

    run_graph(GraphApp(GraphOptions(include="^/no_such_node$"), period=0.5), scenario)


def test_only_tool_nodes_running_explains_hide_debug(rostui_core: Any, ros_env: dict[str, str],
                                                    tmp_path: Path) -> None:
    """Only `rostui topic pub` runs: the first screen names its tool node and topic, hidden by hide debug; d shows them."""
    pub = subprocess.Popen([sys.executable, "-m", "rostui", "topic", "pub", "/greeting", "std_msgs/String",
                            "data: hello", "-r", "1"], env=ros_env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: (master_graph(ros_env) or RosGraph()).publishers.get("/greeting"),
                   "rostui topic pub to register")
        tool = master_graph(ros_env).publishers["/greeting"][0]

        async def scenario(pilot: Pilot, app: GraphApp) -> None:
            assert shown_names(app) == set()
            text = empty_screen(app)
            assert f"1 tool node ({tool})" in text and "/greeting" in text
            assert "hidden: hide debug is on. Press d to show them." in text
            assert "start one of yours" in text
            await pilot.press("d")
            await settled(app)
            assert {tool, "/rosout"} <= shown_names(app) and empty_screen(app) == ""

        run_graph(GraphApp(period=0.5), scenario)
    finally:
        stop_process(pub)


def test_real_rospy_node_with_its_topics(real_roscore: Any, rospy_available: None, ros_env: dict[str, str],
                                         tmp_path: Path) -> None:
    """Against a real roscore: rospy talker -> /chatter -> rospy listener, with the talker's pid and rate."""
    from conftest import REPO, SYSTEM_PYTHON

    talker = subprocess.Popen([SYSTEM_PYTHON, str(REPO / "tests/peers/rospy_talker.py"), "/chatter", "1000", "5",
                               "__name:=talker"], env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    listener = subprocess.Popen([SYSTEM_PYTHON, str(REPO / "tests/peers/rospy_listener.py"), "/chatter", "100000",
                                 "__name:=listener"], env=ros_env, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
    try:
        wait_until(lambda: has_edges(ros_env, (("/talker", "/chatter", "/listener"),)),
                   "the rospy talker and listener to register")

        async def scenario(pilot: Pilot, app: GraphApp) -> None:
            assert {"/talker", "/chatter", "/listener"} <= shown_names(app)
            assert "/rosout" not in shown_names(app)
            edges = {(app.shown.vertices[a].name, app.shown.vertices[b].name) for a, b in app.shown.edges}
            assert {("/talker", "/chatter"), ("/chatter", "/listener")} <= edges
            app.select("n:/talker")
            await until(lambda: "Pid:" in details(app), "the rospy node's pid")
            assert f"Pid: {talker.pid}" in details(app)
            assert " * /chatter [std_msgs/String]" in details(app)
            app.select("t:/chatter")
            await pilot.press("r")
            await until(lambda: "average rate" in details(app), "the talker's rate", timeout=30)

        run_graph(GraphApp(book_setup(), period=0.5, rate_seconds=2.0), scenario)
    finally:
        stop_process(listener)
        stop_process(talker)


def test_user_rostui_listener_shown_with_its_edges(real_roscore: Any, rospy_available: None,
                                                   ros_env: dict[str, str]) -> None:
    """Real roscore: a rospy node the user named rostui_listener is drawn with its /chatter edge, labelled;
    the anonymous nodes of the real `rostopic echo` and of `rostui topic echo` on the same topic are hidden."""
    from conftest import REPO, SYSTEM_PYTHON

    quiet = {"env": ros_env, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    procs = [
        subprocess.Popen([SYSTEM_PYTHON, str(REPO / "tests/peers/rospy_talker.py"), "/chatter", "1000", "5",
                          "__name:=talker"], **quiet),
        subprocess.Popen([SYSTEM_PYTHON, str(REPO / "tests/peers/rospy_listener.py"), "/chatter", "100000",
                          "__name:=rostui_listener"], **quiet),
        subprocess.Popen(["rostopic", "echo", "/chatter"], **quiet),
        subprocess.Popen([sys.executable, "-m", "rostui", "topic", "echo", "/chatter"], **quiet),
    ]

    def tools() -> list[str]:
        graph = master_graph(ros_env) or RosGraph()
        return [n for n in graph.subscribers.get("/chatter", ()) if n.startswith("/rostopic_")]

    try:
        wait_until(lambda: has_edges(ros_env, (("/talker", "/chatter", "/rostui_listener"),)) and len(tools()) == 2,
                   "the talker, /rostui_listener and both echo tools on /chatter")

        async def scenario(pilot: Pilot, app: GraphApp) -> None:
            assert shown_names(app) == {"/talker", "/rostui_listener"}
            assert app.shown.edge_topics[("n:/talker", "n:/rostui_listener")] == ("/chatter",)
            assert re.search(r"│ /talker │─+ /chatter ─+▶│ /rostui_listener │", screen_text(app))
            await pilot.press("d")
            await settled(app)
            assert set(tools()) | {"/talker", "/rostui_listener", "/rosout"} <= shown_names(app)

        run_graph(GraphApp(period=0.5), scenario)
    finally:
        for proc in reversed(procs):
            stop_process(proc)


def test_edge_labels_fit_the_terminal_as_it_is_resized(book: list[Program], ros_env: dict[str, str],
                                                       tmp_path: Path) -> None:
    """teleop -> turtlesim -> subscribe_to_pose: full topic names at 120 columns, abbreviations at 100,
    numbered keys with a legend at 80 (the drawing always fits the screen)."""
    sub = Program(ros_env, tmp_path, "agitr", "subpose", label="subpose")
    try:
        wait_until(lambda: has_edges(ros_env, (("/turtlesim", "/turtle1/pose", "/subscribe_to_pose"),)),
                   "subpose to register")

        async def scenario(pilot: Pilot, app: GraphApp) -> None:
            await until(lambda: "/subscribe_to_pose" in shown_names(app), "subpose on screen")
            await settled(app)
            text = screen_text(app)
            assert "─ /turtle1/command_velocity ─" in text and "─ /turtle1/pose ─" in text
            await pilot.resize_terminal(100, 32)
            await until(lambda: "─ …/pose ─" in screen_text(app), "abbreviated labels at 100 columns")
            assert "  …/command_velocity  /turtle1/command_velocity" in screen_text(app).splitlines()
            assert app.graph_view.canvas.width <= 99
            await pilot.resize_terminal(80, 24)
            await until(lambda: "─ [1] ─" in screen_text(app), "numbered labels at 80 columns")
            assert "  [2]  /turtle1/pose" in screen_text(app).splitlines()
            assert app.graph_view.canvas.width <= 79

        run_graph(GraphApp(period=0.5), scenario, size=(120, 32))
    finally:
        sub.stop()
