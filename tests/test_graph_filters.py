"""The graph's issue-21 rules without a master: which nodes "hide debug" hides, why a view is empty, edge labels.

* Only anonymous tool nodes are debug: ``/rostopic_<pid>_<ms>`` (rospy's
  anonymous form, which `rostopic` and `rostui topic` use), roscpp's
  ``_<ns>`` form, rqt's ``_<pid>``, and rostui's own apps; a user's
  ``/rostui_listener`` is not, nor a user's anonymous ``/talker_<pid>_<ms>``
  (rospy's tutorial listener is anonymous and part of the user's system).
* An empty view names what each filter hides and the key that shows it.
* The nodes-only view writes topic names on its edges: in full, abbreviated
  with a legend, or as numbered keys with a legend, whichever fits.
"""

from __future__ import annotations

import re

import pytest
from test_graph_model import turtlesim_graph

from rostui.apps.graph.app import lay_out
from rostui.apps.graph.canvas import LEGEND_TITLE, draw, layout_view
from rostui.models.console.source import NODE_NAME as CONSOLE_NODE
from rostui.models.graph.hidden import START_HINT, explain_empty
from rostui.models.graph.labels import LabelStyle, abbreviations, edge_labels
from rostui.models.graph.model import RosGraph
from rostui.models.graph.source import NODE_NAME as GRAPH_NODE
from rostui.models.graph.view import TOOL_NODES, GraphOptions, ViewMode, build_view, is_debug_node, is_tool_node
from rostui.models.monitor.source import NODE_NAME as MONITOR_NODE

TOOL = "/rostopic_4711_1700000000000"


def names(view) -> set[str]:
    """The graph names of a view's vertices."""
    return {v.name for v in view.vertices.values()}


# ----------------------------------------------------------------------------- anonymous tool nodes
@pytest.mark.parametrize("name", [
    "/rostopic_1234_1700000000000",          # rostopic echo/pub, rostui topic echo/pub (rospy's anonymous form)
    "/rosservice_9_1700000000001",
    "/rostui_graph_3_1700000000002",          # rostui graph's rate probe
    "/rostui_console_5_1700000000003",
    "/rostui_monitor_5_1700000000004",
    "/rostui_loggers_5_1700000000005",
    "/rqt_gui_py_node_22924",                 # rqt names its host node with its pid
    "/rqt_gui_cpp_node_1700000000000123456",  # roscpp's anonymous form: one nanosecond number
    "/robot1/rostopic_1234_1700000000000",    # ROS_NAMESPACE=/robot1 rostopic echo ...
])
def test_anonymous_tool_nodes_are_debug(name: str) -> None:
    """The tools' anonymous nodes are hidden by hide debug, in any namespace."""
    assert is_tool_node(name) and is_debug_node(name)


@pytest.mark.parametrize("name", [
    "/rostui_listener",                       # a user's node whose name starts with rostui_
    "/rostui_listener_1234_1700000000000",    # ... even started anonymous: not a tool
    "/talker_1234_1700000000000",             # a user's anonymous rospy node (the ROS tutorials' listener)
    "/record_1234_1700000000000",             # rosbag record: a data sink the user started on purpose
    "/play_1234_1700000000000",               # rosbag play: the source of the edges it drives
    "/bag_view_1234_1700000000000",           # rostui bag view publishing a bag
    "/rostopic",                              # not anonymous
    "/rostopic_listener_1_2",                 # a user's node named after a tool
    "/turtlesim",
])
def test_user_nodes_are_not_debug(name: str) -> None:
    """A user's node is shown, whatever it is called and whether or not it is anonymous."""
    assert not is_tool_node(name) and not is_debug_node(name)


def test_rostui_tools_use_names_hide_debug_knows() -> None:
    """rostui's own apps register under base names in TOOL_NODES (the list and the apps stay in step)."""
    for base in (GRAPH_NODE, CONSOLE_NODE, MONITOR_NODE, "rostopic", "rosservice"):
        assert base in TOOL_NODES


def test_user_rostui_listener_shows_with_its_edges() -> None:
    """/rostui_listener with its /chatter edge from /talker stays; rostopic echo's node on /chatter goes."""
    graph = RosGraph.build({"/chatter": ["/talker"], "/rosout": ["/talker", "/rostui_listener", TOOL]},
                           {"/chatter": ["/rostui_listener", TOOL], "/rosout": ["/rosout"]})
    view = build_view(graph, GraphOptions())
    assert names(view) == {"/talker", "/rostui_listener"}
    assert view.edge_topics[("n:/talker", "n:/rostui_listener")] == ("/chatter",)
    everything = build_view(graph, GraphOptions(hide_debug=False))
    assert {TOOL, "/rosout"} <= names(everything)


# ----------------------------------------------------------------------------- why a view is empty
def pub_only_graph() -> RosGraph:
    """A bare master with rosout and `rostopic pub /greeting` only."""
    return RosGraph.build({"/greeting": [TOOL], "/rosout": [TOOL], "/rosout_agg": ["/rosout"]},
                          {"/rosout": ["/rosout"]})


def test_only_a_tool_node_running_is_explained_with_its_key() -> None:
    """Only `topic pub` running: the tool node, /rosout and the topics are hidden by hide debug; press d."""
    explanation = explain_empty(pub_only_graph(), GraphOptions())
    assert build_view(pub_only_graph(), GraphOptions()).vertices == {}
    lines = explanation.lines()
    assert lines[0] == "Nothing drawn, but the master has 2 nodes and 3 topics:"
    assert lines[1] == (f"• 1 tool node ({TOOL}), /rosout and 3 topics (/greeting, /rosout, /rosout_agg) are "
                        "hidden: hide debug is on. Press d to show them.")
    assert START_HINT in lines[2]


def test_include_matching_nothing_is_explained() -> None:
    """An include pattern that matches nothing names itself, what it hides, and how to clear it."""
    lines = explain_empty(turtlesim_graph(), GraphOptions(include="^/nope$")).lines()
    assert lines[1].startswith("• 2 nodes (/teleop_turtle, /turtlesim) and 3 topics (")
    assert lines[1].endswith("hidden: the include filter /^/nope$/ matches none of them. "
                             "Press i, clear the pattern and press Enter to show them.")
    assert len(lines) == 2


def test_filters_hiding_together_are_named_with_their_keys() -> None:
    """Neither filter alone brings anything back: both are named, each with its key."""
    lines = explain_empty(pub_only_graph(), GraphOptions(include="^/nope$")).lines()
    assert lines[1] == "• hidden by hide debug (d) and include /^/nope$/ (i) together: turn them off one by one."


def test_exclude_and_no_nodes_at_all() -> None:
    """An exclude that matches every name says so; an empty master says how to start a node."""
    lines = explain_empty(turtlesim_graph(), GraphOptions(exclude="."))
    assert "the exclude filter /./ matches them. Press x" in lines.lines()[1]
    assert explain_empty(RosGraph(), GraphOptions()).lines() == [
        "The master has no nodes yet.", f"Start one (for example `{START_HINT}`) and it appears here."]


def test_leaf_topic_filter_is_named_when_it_hides_the_rest() -> None:
    """Nodes/Topics with leaf topics hidden and the only node excluded: both filters are accounted for."""
    graph = RosGraph.build({"/a": ["/lonely"]})
    options = GraphOptions(view=ViewMode.ALL, hide_leaf_topics=True, exclude="lonely")
    lines = explain_empty(graph, options).lines()
    assert "1 node (/lonely) is hidden: the exclude filter /lonely/ matches them" in lines[1]
    assert "1 topic (/a) is hidden: hide leaf topics is on. Press l to show them." == lines[2][2:]


# ----------------------------------------------------------------------------- edge labels
def chain_graph() -> RosGraph:
    """Figure 6.3 with a pose logger: teleop_key -> reverse_velocity -> turtlesim -> pose_logger."""
    return RosGraph.build({"/turtle1/command_velocity": ["/teleop_key"],
                           "/turtle1/command_velocity_reversed": ["/reverse_velocity"],
                           "/turtle1/pose": ["/turtlesim"]},
                          {"/turtle1/command_velocity": ["/reverse_velocity"],
                           "/turtle1/command_velocity_reversed": ["/turtlesim"],
                           "/turtle1/pose": ["/pose_logger"]})


def test_nodes_only_edge_carries_its_topic_on_its_line() -> None:
    """rqt_graph's Figure 2.2 label: the topic name sits on the line from teleop to turtlesim."""
    view = build_view(turtlesim_graph(), GraphOptions())
    text = lay_out(view, None, 200)[1].text()
    assert re.search(r"│ /teleop_turtle │─+ /turtle1/command_velocity ─+▶│ /turtlesim │", text)
    assert text.count("▶") == 1 and LEGEND_TITLE not in text


def test_labels_shrink_to_fit_the_width_with_a_legend() -> None:
    """Too wide in full: abbreviations (…/pose) when they fit, else numbered keys; each with a legend."""
    view = build_view(chain_graph(), GraphOptions())
    widths = {style: layout_view(view, None, edge_labels(view, style).lines).width for style in LabelStyle}
    assert widths[LabelStyle.FULL] > widths[LabelStyle.SHORT] > widths[LabelStyle.KEYS]
    full = lay_out(view, None, widths[LabelStyle.FULL])[1]
    assert "── /turtle1/command_velocity_reversed ──▶│ /turtlesim │" in full.text()
    assert LEGEND_TITLE not in full.text()
    short = lay_out(view, None, widths[LabelStyle.FULL] - 1)[1]
    assert "── …/pose ──▶│ /pose_logger │" in short.text()
    assert "  …/pose" + " " * 23 + "/turtle1/pose" in short.text().splitlines()  # under …/command_velocity_reversed
    keys = lay_out(view, None, widths[LabelStyle.SHORT] - 1)[1]
    assert keys.width == widths[LabelStyle.KEYS]
    assert re.search(r"│ /teleop_key │─+ \[1\] ─+▶│ /reverse_velocity │", keys.text())
    legend = keys.text().split(LEGEND_TITLE)[1].splitlines()
    assert legend[1:] == ["  [1]  /turtle1/command_velocity", "  [2]  /turtle1/command_velocity_reversed",
                          "  [3]  /turtle1/pose"]
    assert lay_out(view, None, 20)[1].text() == keys.text()


def test_abbreviations_keep_topics_apart() -> None:
    """The shortest tail that no other topic shares; /ns/…/name when only the namespace tells them apart."""
    got = abbreviations(["/turtle1/cmd_vel", "/turtle1/pose", "/turtle2/pose", "/chatter",
                         "/sim1/turtle1/command_velocity", "/sim2/turtle1/command_velocity"])
    assert got["/turtle1/cmd_vel"] == "…/cmd_vel"
    assert got["/turtle1/pose"] == "/turtle1/pose" and got["/turtle2/pose"] == "/turtle2/pose"
    assert got["/chatter"] == "/chatter"
    assert got["/sim1/turtle1/command_velocity"] == "/sim1/…/command_velocity"
    assert len(set(got.values())) == len(got)


def test_many_topics_on_one_edge_are_counted() -> None:
    """Up to three topics a label, one a row; past that the rest are counted."""
    topics = [f"/t{i}" for i in range(5)]
    graph = RosGraph.build({t: ["/a"] for t in topics}, {t: ["/b"] for t in topics})
    view = build_view(graph, GraphOptions())
    labels = edge_labels(view, LabelStyle.FULL)
    assert labels.lines[("n:/a", "n:/b")] == ("/t0", "/t1", "+3 more")
    text = draw(view, layout_view(view, None, labels.lines), labels).text()
    assert "/t0" in text and "+3 more" in text and text.count("▶") == 1


def test_edge_label_cells_belong_to_their_edge() -> None:
    """Clicking or colouring a label treats it as part of its edge (label cells owned by the edge)."""
    view = build_view(turtlesim_graph(), GraphOptions())
    canvas = lay_out(view, None, 200)[1]
    row = next(y for y in range(canvas.height) if "/turtle1/command_velocity" in canvas.line(y))
    x = canvas.line(row).index("/turtle1/command_velocity")
    assert canvas.edge_at(x, row) == ("n:/teleop_turtle", "n:/turtlesim")
    assert canvas.edge_of(canvas.row(row)[1][x]) == (0, True)
    assert canvas.edge_of(canvas.row(row)[1][x - 3]) == (0, False)
    assert set(canvas.boxes) == set(view.vertices)


def test_topic_views_have_no_edge_labels() -> None:
    """Nodes/Topics views draw topics as boxes: nothing is written on their edges, grouped or not."""
    view = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ALL))
    assert view.edge_topics == {}
    assert lay_out(view, None, 80)[1].text() == draw(view, layout_view(view)).text()
    grouped = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ALL, group_namespaces=True))
    text = lay_out(grouped, None, 80, labelled=False)[1].text()
    assert text == draw(grouped, layout_view(grouped)).text() and "/turtle1/pose" not in text


def test_a_new_topic_between_the_same_nodes_changes_the_signature() -> None:
    """The drawing is redone when an edge gains a topic (its label changes though its ends do not)."""
    one = build_view(RosGraph.build({"/a": ["/n1"]}, {"/a": ["/n2"]}), GraphOptions())
    two = build_view(RosGraph.build({"/a": ["/n1"], "/b": ["/n1"]}, {"/a": ["/n2"], "/b": ["/n2"]}), GraphOptions())
    assert one.signature() != two.signature()


def test_a_cycle_keeps_each_label_between_its_nodes() -> None:
    """/a -> /ping -> /b and /b -> /pong -> /a: /pong is drawn backwards with ◀ on its label and at /a."""
    graph = RosGraph.build({"/ping": ["/a"], "/pong": ["/b"]}, {"/ping": ["/b"], "/pong": ["/a"]})
    view = build_view(graph, GraphOptions())
    canvas = lay_out(view, None, 200)[1]
    a, b = canvas.boxes["n:/a"], canvas.boxes["n:/b"]
    for topic in ("/ping", "/pong"):
        row = next(y for y in range(canvas.height) if topic in canvas.line(y))
        assert a.x + a.w < canvas.line(row).index(topic) < b.x, f"{topic} is not between /a and /b"
    assert "◀ /pong" in canvas.text() and "◀ /ping" not in canvas.text()
    assert canvas.line(a.center_row)[a.x + a.w] == "◀"
    assert canvas.line(b.center_row)[b.x - 1] == "▶"
    assert canvas.text().count("◀") == 2 and canvas.text().count("▶") == 1
