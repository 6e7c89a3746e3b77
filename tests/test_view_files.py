"""View files and rviz files for `rostui view`: a view saved on quit opens the same picture; an rviz file from a
public robot repository (tests/rviz_corpus, sources and licences in its SOURCES.md) gives its enabled displays,
fixed frame, tool topics and view; bad files are one line with FILE:LINE and exit 1. Also the robot's footprint
(costmap_2d's forms) and PolygonStamped."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cli_helpers import rostui
from conftest import REPO
from rostui.models.sensors.footprint import FootprintError, footprint_outline
from rostui.models.sensors.view_file import ViewFileError, ViewSpec, read_view_file, spec_from_rviz, write_view_file

CORPUS = REPO / "tests" / "rviz_corpus"


def test_a_view_file_round_trips(tmp_path: Path) -> None:
    spec = ViewSpec(["/map", "/scan"], "map", 12.5, (1.5, -0.75), "/goal", "/initialpose", "/cmd_vel",
                    "[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]", "base_footprint", True)
    path = tmp_path / "nav.yaml"
    write_view_file(spec, path)
    assert path.read_text().startswith("# rostui view: `rostui view nav.yaml` opens it\ntopics: [/map, /scan]\n")
    assert read_view_file(path) == spec


@pytest.mark.parametrize(("text", "said"), [
    ("topics: [/map]\nzoom: 3\n", ":2: unknown key 'zoom'"),
    ("topics: []\n", ":1: topics: a list of 1 to 64 topic names"),
    ("topics: [/map, 'bad topic']\n", ":1: topics: "),
    ("topics: [/map]\nspan: -2\n", ":2: span: -2 metres is not between 0.001 and 1e+07"),
    ("topics: [/map]\nspan: 1.0e-320\n", ":2: span: "),
    ("topics: [/map]\nspan: " + "9" * 400 + "\n", ":2: span: '999"),
    ("topics: [/map]\nspan: !!float abc\n", ":2: not a value: "),
    ("topics: [/map]\nframe: !foo x\n", ":2: not a value: "),
    ("topics: [/map]\ncentre: [1]\n", ":2: centre: [x, y] in metres"),
    ("topics: [/map]\nfollow: 'yes'\n", ":2: follow: true or false"),
    ("frame: map\n", ":1: a view file needs `topics: [TOPIC, ...]`"),
    ("- /map\n", ":1: a view file is a mapping"),
    ("topics: &a [/map]\nframe: *a\n", ":2: YAML aliases are not allowed in a view file"),
    ("topics: [/map\n", ": YAML error"),
])
def test_a_bad_view_file_is_one_line_with_its_place(tmp_path: Path, text: str, said: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    with pytest.raises(ViewFileError) as caught:
        read_view_file(path)
    assert str(caught.value).startswith(str(path)) and said in str(caught.value) and "\n" not in str(caught.value)


def test_turtlebot3_navigation_rviz() -> None:
    spec, skipped = spec_from_rviz(CORPUS / "turtlebot3-turtlebot3_navigation.rviz")
    assert spec.topics == ["/scan", "/map", "/move_base/NavfnROS/plan", "/move_base/global_costmap/costmap",
                           "/move_base/DWAPlannerROS/global_plan", "/move_base/local_costmap/footprint",
                           "/move_base/local_costmap/costmap", "/move_base/DWAPlannerROS/local_plan",
                           "/particlecloud", "/move_base_simple/goal"]  # the Image display is disabled
    assert (spec.frame, spec.goal_topic, spec.pose_topic, spec.centre) == (
        "map", "/move_base_simple/goal", "/initialpose", (0.0, 0.0))
    assert spec.span is not None and math.isclose(spec.span, 1279 / 100)  # window width over TopDownOrtho's scale
    assert skipped == ["RobotModel (rviz/RobotModel)"]


def test_tiago_navigation_rviz_relative_topics_and_nested_groups() -> None:
    spec, skipped = spec_from_rviz(CORPUS / "tiago_navigation-navigation.rviz")
    assert spec.frame == "map" and spec.goal_topic == "/move_base_simple/goal" and spec.pose_topic == "/initialpose"
    assert {"/scan", "/move_base/local_costmap/footprint", "/move_base/TebLocalPlannerROS/teb_markers",
            "/move_base/local_planner/vfh_angle_candidates", "/vo_map"} <= set(spec.topics)
    assert "/xtion/depth/points" not in spec.topics  # disabled in the file
    assert "Sonar (rviz/Range)" in skipped
    assert spec.centre == (1.5263429880142212, -0.7649117112159729)


def test_husky_robot_rviz_orbit_view() -> None:
    spec, _ = spec_from_rviz(CORPUS / "husky-robot.rviz")
    assert spec.frame == "odom" and spec.topics[:3] == ["/odometry/filtered", "/front/scan", "/camera/depth/points"]
    assert spec.span == 17.1298 and spec.centre == (1.62908, -0.0834703)


def test_every_corpus_file_opens() -> None:
    files = sorted(CORPUS.glob("*.rviz"))
    assert len(files) == 4
    for path in files:
        spec, _ = spec_from_rviz(path)
        assert spec.topics and spec.frame


@pytest.mark.parametrize(("text", "said"), [
    ("a: 1\n", ":1: not an rviz configuration"),
    ("Visualization Manager:\n  Displays:\n    - Class: rviz/RobotModel\n      Enabled: true\n",
     ":1: no enabled display of a type rostui view draws"),
])
def test_a_bad_rviz_file_is_one_line(tmp_path: Path, text: str, said: str) -> None:
    path = tmp_path / "bad.rviz"
    path.write_text(text)
    with pytest.raises(ViewFileError, match=said):
        spec_from_rviz(path)


@pytest.mark.parametrize("value", ["[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]",
                                   [[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]])
def test_a_footprint_as_costmap_2d_reads_it(value: object) -> None:
    outline = footprint_outline(value)
    assert outline.tolist() == [[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2], [0.3, 0.2]]


def test_a_radius_is_a_circle() -> None:
    outline = footprint_outline(0.25)
    assert np.allclose(np.hypot(outline[:, 0], outline[:, 1]), 0.25) and np.allclose(outline[0], outline[-1])


@pytest.mark.parametrize(("value", "said"), [
    ("[[0, 0], [1, 0]]", "at least three"), ("[[0, 0], [1, 0], [1]]", "point 3"), ("[[0, 0], [1, 0], [1, x]]", "'x' is not a number"),
    ("[[0, 0], [1, 0], [nan, 1]]", "not a number"), (-1, "not positive"), ("{oops", "not a list"),
    ("[[0, 0], [1, 0], [1, 1.0e+999]]", "not a finite number"), ([[0, 0], [1, 0], [10 ** 400, 1]], "not a finite"),
    ("[" * 100 + "]" * 100, "at least three"), ("x" * 70000, "longer than 65536"),
])
def test_a_bad_footprint_is_one_line(value: object, said: str) -> None:
    with pytest.raises(FootprintError, match=said):
        footprint_outline(value)


def test_cli_errors_are_one_line(tmp_path: Path, ros_env: dict[str, str]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("topics: [/map]\nzoom: 3\n")
    for args, said in ((["view", str(bad)], f"ERROR: {bad}:2: unknown key 'zoom'"),
                       (["view", "--from-rviz", str(tmp_path / "none.rviz")], "No such file or directory"),
                       (["view"], "ERROR: no topic to show"),
                       (["view", "/map", "--footprint", "[[0, 0]]"], "ERROR: --footprint: a footprint needs at least"),
                       (["view", "/map", "--goal-topic", "bad topic"], "ERROR: ")):
        result = rostui(args, ros_env, timeout=30)
        assert result.returncode == 1 and result.stderr.count("\n") == 1 and said in result.stderr, (args, result)
