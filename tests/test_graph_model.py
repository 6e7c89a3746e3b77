"""The graph's views, filters, layout, live marks, search and DOT on the book's graphs (no master needed).

The graphs are the registrations the book's figures show: turtlesim with
teleop (Figures 2.2-2.4, chapter 2), doublesim.launch (Figure 6.1) and the
reverse_cmd_vel mistake and its remap fix (Figures 6.2, 6.3).
"""

from __future__ import annotations

import random
import re

import pytest

from rostui.apps.graph.canvas import draw, layout_view
from rostui.models.graph.dot import to_dot
from rostui.models.graph.layout import layered_layout
from rostui.models.graph.live import LiveGraph, Mark
from rostui.models.graph.model import RosGraph
from rostui.models.graph.search import fuzzy_rank
from rostui.models.graph.view import (
    FilterError, GraphOptions, Kind, ViewMode, book_setup, build_view, focus_view, is_debug_node,
)

ROSOUT = "/rosout"


def turtlesim_graph(*extra_nodes: str) -> RosGraph:
    """turtlesim and teleop_turtle as the book runs them, with rosout and a rqt-like tool node."""
    nodes = ["/turtlesim", "/teleop_turtle", *extra_nodes]
    return RosGraph.build(
        publishers={"/turtle1/command_velocity": ["/teleop_turtle"], "/turtle1/pose": ["/turtlesim"],
                    "/turtle1/color_sensor": ["/turtlesim"], ROSOUT: nodes, "/rosout_agg": [ROSOUT]},
        subscribers={"/turtle1/command_velocity": ["/turtlesim"], ROSOUT: [ROSOUT]},
        services={"/turtlesim/get_loggers": ["/turtlesim"], "/clear": ["/turtlesim"]},
        topic_types={"/turtle1/command_velocity": "turtlesim/Velocity", "/turtle1/pose": "turtlesim/Pose",
                     "/turtle1/color_sensor": "turtlesim/Color", ROSOUT: "rosgraph_msgs/Log"},
    )


def reverse_graph(remapped: bool) -> RosGraph:
    """Figure 6.2 (turtlesim listens to the wrong topic) or Figure 6.3 (reverse.launch's remap)."""
    sim_topic = "/turtle1/command_velocity_reversed" if remapped else "/turtle1/command_velocity"
    return RosGraph.build(
        publishers={"/turtle1/command_velocity": ["/teleop_key"],
                    "/turtle1/command_velocity_reversed": ["/reverse_velocity"],
                    "/turtle1/pose": ["/turtlesim"], "/turtle1/color_sensor": ["/turtlesim"]},
        subscribers={"/turtle1/command_velocity": ["/reverse_velocity"] + ([] if remapped else ["/turtlesim"]),
                     sim_topic: ["/turtlesim"]} if not remapped else
                    {"/turtle1/command_velocity": ["/reverse_velocity"], sim_topic: ["/turtlesim"]},
    )


def doublesim_graph() -> RosGraph:
    """Figure 6.1: two turtlesims in /sim1 and /sim2, one driven by teleop_key, one by pubvel."""
    pubs, subs = {}, {}
    for ns, driver in (("/sim1", "teleop_key"), ("/sim2", "velocity_publisher")):
        pubs[f"{ns}/turtle1/command_velocity"] = [f"{ns}/{driver}"]
        subs[f"{ns}/turtle1/command_velocity"] = [f"{ns}/turtlesim_node"]
        pubs[f"{ns}/turtle1/pose"] = [f"{ns}/turtlesim_node"]
        pubs[f"{ns}/turtle1/color_sensor"] = [f"{ns}/turtlesim_node"]
    return RosGraph.build(pubs, subs)


def names(view) -> set[str]:
    """The graph names of a view's vertices."""
    return {v.name for v in view.vertices.values()}


def edges(view) -> set[tuple[str, str]]:
    """A view's edges as (name, name)."""
    return {(view.vertices[a].name, view.vertices[b].name) for a, b in view.edges}


# ----------------------------------------------------------------------------- views and filters
def test_nodes_only_view_is_figure_2_2_and_hides_debug_by_default() -> None:
    """Default options: /teleop_turtle -> /turtlesim only; rosout and the tool node are hidden."""
    view = build_view(turtlesim_graph("/rqt_gui_py_node_22924", "/rostopic_4711_1700000000000"), GraphOptions())
    assert names(view) == {"/teleop_turtle", "/turtlesim"}
    assert edges(view) == {("/teleop_turtle", "/turtlesim")}
    assert view.edge_topics[("n:/teleop_turtle", "n:/turtlesim")] == ("/turtle1/command_velocity",)


def test_unchecking_hide_debug_shows_figure_2_3() -> None:
    """Every node publishes /rosout, which the /rosout node subscribes to; rqt's own node appears."""
    view = build_view(turtlesim_graph("/rqt_gui_py_node_22924"), GraphOptions(hide_debug=False))
    assert names(view) == {"/teleop_turtle", "/turtlesim", ROSOUT, "/rqt_gui_py_node_22924"}
    assert {("/turtlesim", ROSOUT), ("/teleop_turtle", ROSOUT), ("/rqt_gui_py_node_22924", ROSOUT)} <= edges(view)


def test_book_setup_is_figure_2_4() -> None:
    """Nodes/Topics (all) with only Hide debug: topics in boxes, turtlesim's pose and colour sensor shown."""
    view = build_view(turtlesim_graph(), book_setup())
    assert names(view) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity", "/turtle1/pose",
                           "/turtle1/color_sensor"}
    assert edges(view) == {("/teleop_turtle", "/turtle1/command_velocity"),
                           ("/turtle1/command_velocity", "/turtlesim"), ("/turtlesim", "/turtle1/pose"),
                           ("/turtlesim", "/turtle1/color_sensor")}
    kinds = {v.name: v.kind for v in view.vertices.values()}
    assert kinds["/turtle1/pose"] is Kind.TOPIC and kinds["/turtlesim"] is Kind.NODE


def test_active_view_keeps_topics_with_publisher_and_subscriber() -> None:
    """Nodes/Topics (active): only /turtle1/command_velocity connects two nodes."""
    view = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ACTIVE))
    assert names(view) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity"}


def test_debug_names() -> None:
    """rosout and anonymous tool nodes are debug; a user's anonymous node and rosbag's recorder are not."""
    for name in ("/rosout", "/rostopic_12_1700000000000", "/rosnode_1_2", "/rostui_graph_3_4",
                 "/rostui_console_5_6", "/rqt_gui_py_node_22924", "/rosservice_9_9"):
        assert is_debug_node(name), name
    for name in ("/rospy_talker_12_1700000000000", "/record_1234_5678", "/turtlesim", "/rosout_helper",
                 "/rostui_listener"):
        assert not is_debug_node(name), name


def test_dead_sinks_and_leaf_topics() -> None:
    """Dead sinks: topics nobody subscribes to; leaf topics: topics used by one node only."""
    graph = reverse_graph(remapped=True)
    all_topics = build_view(graph, GraphOptions(view=ViewMode.ALL))
    assert "/turtle1/pose" in names(all_topics)
    no_sinks = build_view(graph, GraphOptions(view=ViewMode.ALL, hide_dead_sinks=True))
    assert names(no_sinks) & {"/turtle1/pose", "/turtle1/color_sensor"} == set()
    assert "/turtle1/command_velocity_reversed" in names(no_sinks)
    lone = RosGraph.build({"/a": ["/n1"], "/b": ["/n1"]}, {"/b": ["/n2"], "/c": ["/n2"]})
    no_leaves = build_view(lone, GraphOptions(view=ViewMode.ALL, hide_leaf_topics=True))
    assert names(no_leaves) == {"/n1", "/n2", "/b"}


def test_figures_6_2_and_6_3_remap_moves_the_edge() -> None:
    """Without the remap turtlesim reads teleop's topic directly; with it, only through reverse_velocity."""
    wrong = build_view(reverse_graph(remapped=False), GraphOptions())
    assert ("/teleop_key", "/turtlesim") in edges(wrong)
    fixed = build_view(reverse_graph(remapped=True), GraphOptions())
    assert edges(fixed) == {("/teleop_key", "/reverse_velocity"), ("/reverse_velocity", "/turtlesim")}


def test_include_shows_matches_and_what_they_connect_to() -> None:
    """--include /turtlesim: the node with its topics; --include pose: the topic with its publisher."""
    view = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ALL, include="^/turtlesim$"))
    assert names(view) == {"/turtlesim", "/turtle1/command_velocity", "/turtle1/pose", "/turtle1/color_sensor"}
    view = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ALL, include="pose"))
    assert names(view) == {"/turtle1/pose", "/turtlesim"}


def test_exclude_hides_matches_always() -> None:
    """--exclude wins over everything: excluded nodes take their edges along."""
    view = build_view(turtlesim_graph(), GraphOptions(view=ViewMode.ALL, exclude="color|pose"))
    assert names(view) == {"/teleop_turtle", "/turtlesim", "/turtle1/command_velocity"}
    view = build_view(turtlesim_graph(), GraphOptions(exclude="teleop"))
    assert names(view) == {"/turtlesim"} and not view.edges


@pytest.mark.parametrize("field", ["include", "exclude"])
def test_bad_regex_is_one_clear_error(field: str) -> None:
    """A malformed pattern names the filter, the pattern and what is wrong with it."""
    with pytest.raises(FilterError, match=rf"bad {field} regex '\(turtle': missing \)"):
        build_view(turtlesim_graph(), GraphOptions(**{field: "(turtle"}))


def test_group_namespaces_collapses_and_expands() -> None:
    """doublesim: /sim1 and /sim2 fold into one box each; expanding /sim1 brings its members back."""
    graph = doublesim_graph()
    grouped = build_view(graph, GraphOptions(view=ViewMode.ALL, group_namespaces=True))
    assert {v.kind for v in grouped.vertices.values()} == {Kind.GROUP}
    assert names(grouped) == {"/sim1", "/sim2"}
    assert len(grouped.vertices["g:/sim1"].members) == 5
    opened = build_view(graph, GraphOptions(view=ViewMode.ALL, group_namespaces=True,
                                            expanded=frozenset({"/sim1"})))
    assert "/sim2" in names(opened) and "/sim1/turtlesim_node" in names(opened)
    assert "/sim1" not in names(opened)


def test_focus_view_counts_hops() -> None:
    """Focus on /teleop_turtle: 1 hop is its topic, 2 hops reach turtlesim, 3 hops its topics."""
    view = build_view(turtlesim_graph(), book_setup())
    assert names(focus_view(view, "n:/teleop_turtle", 1)) == {"/teleop_turtle", "/turtle1/command_velocity"}
    assert names(focus_view(view, "n:/teleop_turtle", 2)) == {"/teleop_turtle", "/turtle1/command_velocity",
                                                              "/turtlesim"}
    assert names(focus_view(view, "n:/teleop_turtle", 3)) == names(view)


# ----------------------------------------------------------------------------- layout and drawing
def test_book_graph_draws_left_to_right_with_boxes_and_arrows() -> None:
    """teleop, its topic and turtlesim on one row, left to right; nodes rounded, topics square."""
    view = build_view(turtlesim_graph(), book_setup())
    text = draw(view, layout_view(view)).text()
    row = next(line for line in text.splitlines() if "/teleop_turtle" in line)
    assert re.search(r"│ /teleop_turtle │─*▶│ /turtle1/command_velocity │", row)
    assert "╭" in text and "┌" in text and text.count("▶") == 4


def test_layout_has_no_overlapping_boxes_and_every_edge_an_arrow() -> None:
    """A random 60-node graph: disjoint boxes, one arrow head per edge, edges leave left to right."""
    rng = random.Random(7)
    nodes = [f"/n{i}" for i in range(60)]
    pubs = {f"/t{i}": [rng.choice(nodes)] for i in range(90)}
    subs = {f"/t{i}": rng.sample(nodes, rng.randint(0, 3)) for i in range(90)}
    view = build_view(RosGraph.build(pubs, subs), GraphOptions(view=ViewMode.ALL))
    layout = layout_view(view)
    cells: set[tuple[int, int]] = set()
    for box in layout.boxes.values():
        area = {(x, y) for x in range(box.x, box.x + box.w) for y in range(box.y, box.y + box.h)}
        assert not area & cells, f"{box.id} overlaps another box"
        cells |= area
    assert len(layout.arrows) == len(layout.edges)
    for arrow in layout.arrows:
        assert (arrow.x, arrow.y) not in cells


def test_unchanged_graph_draws_identically() -> None:
    """Laying out the same view twice, or again from the first layout's hint, gives the same picture."""
    view = build_view(doublesim_graph(), GraphOptions(view=ViewMode.ALL))
    first = layout_view(view)
    assert draw(view, layout_view(view)).text() == draw(view, first).text()
    assert draw(view, layout_view(view, first.hint())).text() == draw(view, first).text()


def test_small_change_keeps_the_others_in_place() -> None:
    """A new node subscribing to one topic leaves every other vertex's layer and order as it was."""
    graph = doublesim_graph()
    before = layout_view(build_view(graph, GraphOptions(view=ViewMode.ALL)))
    subs = dict(graph.subscribers)
    subs["/sim2/turtle1/pose"] = ("/sim2/pose_logger",)
    after_view = build_view(RosGraph.build(graph.publishers, subs), GraphOptions(view=ViewMode.ALL))
    after = layout_view(after_view, before.hint())

    def order(layout) -> list[tuple[int, str]]:
        return sorted((layout.ranks[v], v) for v in before.boxes)

    assert order(after) == order(before)
    for rank in set(before.ranks.values()):
        column = [v for v in sorted(before.boxes, key=lambda v: before.boxes[v].y) if before.ranks[v] == rank]
        assert sorted(column, key=lambda v: after.boxes[v].y) == column


def test_cycles_point_back_with_a_left_arrow() -> None:
    """n1 -> /a -> n2 -> /b -> n1: one edge is drawn backwards, its head on n1's side."""
    graph = RosGraph.build({"/a": ["/n1"], "/b": ["/n2"]}, {"/a": ["/n2"], "/b": ["/n1"]})
    layout = layout_view(build_view(graph, GraphOptions(view=ViewMode.ALL)))
    assert sum(a.left for a in layout.arrows) == 1 and len(layout.arrows) == 4


def test_layout_is_deterministic_for_any_input_order() -> None:
    """Vertex and edge order of the input do not change the result."""
    sizes = {f"v{i}": (6, 3) for i in range(30)}
    rng = random.Random(3)
    edge_list = [(f"v{rng.randrange(30)}", f"v{rng.randrange(30)}") for _ in range(50)]
    a = layered_layout(sizes, edge_list)
    shuffled = dict(sorted(sizes.items(), reverse=True))
    b = layered_layout(shuffled, sorted(edge_list, reverse=True))
    assert {k: (v.x, v.y) for k, v in a.boxes.items()} == {k: (v.x, v.y) for k, v in b.boxes.items()}


# ----------------------------------------------------------------------------- live marks and search
def test_live_marks_new_and_gone_for_a_few_refreshes() -> None:
    """First snapshot: no marks; a node appears: new for 3 refreshes; it leaves: a ghost for 3 refreshes."""
    live = LiveGraph(keep=3)
    live.update(turtlesim_graph())
    assert live.marks() == {}
    with_logger = RosGraph.build(dict(turtlesim_graph().publishers),
                                 {**turtlesim_graph().subscribers, "/turtle1/pose": ["/pose_logger"]})
    live.update(with_logger)
    assert live.marks() == {"n:/pose_logger": Mark.NEW}
    live.update(with_logger)
    live.update(with_logger)
    assert live.marks() == {"n:/pose_logger": Mark.NEW}
    live.update(with_logger)
    assert live.marks() == {}
    live.update(turtlesim_graph())
    assert live.marks() == {"n:/pose_logger": Mark.GONE}
    assert "/pose_logger" in live.graph.nodes() and "/pose_logger" not in live.current.nodes()
    assert live.graph.subscribers["/turtle1/pose"] == ("/pose_logger",)
    live.update(turtlesim_graph())
    live.update(turtlesim_graph())
    assert live.marks() == {"n:/pose_logger": Mark.GONE}
    live.update(turtlesim_graph())
    assert live.marks() == {} and "/pose_logger" not in live.graph.nodes()


def test_fuzzy_search_ranks_substrings_then_subsequences() -> None:
    """`pose` finds /turtle1/pose first; `tcv` finds /turtle1/command_velocity; nonsense finds nothing."""
    candidates = ["/turtle1/pose", "/turtle1/color_sensor", "/turtlesim", "/turtle1/command_velocity"]
    assert fuzzy_rank("pose", candidates)[0] == "/turtle1/pose"
    assert fuzzy_rank("tcv", candidates)[0] == "/turtle1/command_velocity"
    assert fuzzy_rank("sim", candidates)[0] == "/turtlesim"
    assert fuzzy_rank("zzz", candidates) == []


def test_dot_output() -> None:
    """Nodes are ellipses, topics boxes; nodes-only edges carry their topics as labels."""
    dot = to_dot(build_view(turtlesim_graph(), book_setup()))
    assert dot.startswith('digraph "rosgraph" {\n  rankdir=LR;\n')
    assert '"n:/turtlesim" [label="/turtlesim", shape=ellipse];' in dot
    assert '"t:/turtle1/pose" [label="/turtle1/pose", shape=box];' in dot
    assert '"n:/teleop_turtle" -> "t:/turtle1/command_velocity";' in dot
    nodes_dot = to_dot(build_view(turtlesim_graph(), GraphOptions()), label_edges=True)
    assert '"n:/teleop_turtle" -> "n:/turtlesim" [label="/turtle1/command_velocity"];' in nodes_dot
