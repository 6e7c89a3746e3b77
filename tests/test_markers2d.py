"""The marker model of the top-down view (rostui.models.sensors.markers2d and Scene2D's marker topics): each
marker type's ground-plane shape, ADD/MODIFY/DELETE/DELETEALL by namespace and id, lifetime, frame_locked, a
colour per point, alpha 0, and bounds against a flood of markers or hostile text."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from rostui.core.rostime import Duration
from rostui.models.sensors.canvas2d import Viewport
from rostui.models.sensors.markers2d import MarkerStore, marker_shape
from rostui.models.sensors.pose2d import Pose2D
from rostui.models.sensors.scene2d import Scene2D
from topdown_helpers import ColorRGBA, Marker, MarkerArray, marker

def close(a: Any, b: Any) -> bool:
    return bool(np.allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), atol=1e-9))


def test_an_arrow_runs_scale_x_along_its_heading_or_between_its_two_points() -> None:
    shape = marker_shape(marker(Marker.ARROW, 1.0, 2.0, yaw=math.pi / 2, scale=(2.0, 0.1)))
    assert close(shape.starts[0], [1.0, 2.0]) and close(shape.ends[0], [1.0, 4.0])
    assert len(shape.starts) == 3  # the shaft and two barbs, from the tip
    shape = marker_shape(marker(Marker.ARROW, 1.0, 0.0, points=((0, 0), (0, 3))))
    assert close(shape.starts[0], [1.0, 0.0]) and close(shape.ends[0], [1.0, 3.0])


@pytest.mark.parametrize("kind", [Marker.CUBE, Marker.MESH_RESOURCE])
def test_a_cube_or_mesh_is_the_outline_of_its_scale_turned_by_its_pose(kind: int) -> None:
    shape = marker_shape(marker(kind, 5.0, 0.0, yaw=math.pi / 2, scale=(2.0, 1.0)))
    corners = {tuple(np.round(p, 9)) for p in shape.starts}
    assert corners == {(5.5, -1.0), (5.5, 1.0), (4.5, 1.0), (4.5, -1.0)}
    assert close(shape.ends, np.roll(shape.starts, -1, axis=0))


@pytest.mark.parametrize("kind", [Marker.SPHERE, Marker.CYLINDER])
def test_a_sphere_or_cylinder_is_an_ellipse_of_its_diameters(kind: int) -> None:
    shape = marker_shape(marker(kind, 1.0, 1.0, scale=(2.0, 1.0)))
    rel = shape.starts - [1.0, 1.0]
    assert close((rel[:, 0] / 1.0) ** 2 + (rel[:, 1] / 0.5) ** 2, np.ones(len(rel)))


def test_lines_and_triangles() -> None:
    strip = marker_shape(marker(Marker.LINE_STRIP, 1.0, 0.0, points=((0, 0), (1, 0), (1, 1))))
    assert close(strip.starts, [[1, 0], [2, 0]]) and close(strip.ends, [[2, 0], [2, 1]])
    pairs = marker_shape(marker(Marker.LINE_LIST, points=((0, 0), (1, 0), (0, 1), (1, 1), (9, 9))))
    assert close(pairs.starts, [[0, 0], [0, 1]]) and close(pairs.ends, [[1, 0], [1, 1]])  # an odd point is left
    tri = marker_shape(marker(Marker.TRIANGLE_LIST, points=((0, 0), (1, 0), (0, 1))))
    assert close(tri.starts, [[0, 0], [1, 0], [0, 1]]) and close(tri.ends, [[1, 0], [0, 1], [0, 0]])


@pytest.mark.parametrize("kind", [Marker.POINTS, Marker.CUBE_LIST, Marker.SPHERE_LIST])
def test_point_lists_are_a_dot_each_with_a_colour_per_point_when_given(kind: int) -> None:
    m = marker(kind, 1.0, 1.0, points=((0, 0), (1, 0), (2, 0)))
    assert close(marker_shape(m).dots, [[1, 1], [2, 1], [3, 1]])
    shape = marker_shape(m)
    assert [shape.palette[i] for i in shape.dot_colors] == [(240, 16, 16)] * 3  # colours grouped, 8 levels
    m.colors = [ColorRGBA(0, 0, 1, 1), ColorRGBA(0, 1, 0, 1), ColorRGBA(1, 1, 1, 0)]  # the third hidden (alpha 0)
    shape = marker_shape(m)
    assert [shape.palette[i] for i in shape.dot_colors] == [(16, 16, 240), (16, 240, 16)]
    assert close(shape.dots, [[1, 1], [2, 1]])


def test_text_is_one_line_of_single_cells_at_its_position() -> None:
    shape = marker_shape(marker(Marker.TEXT_VIEW_FACING, 2.0, 3.0, text="goal\n\x1b[31mA\u0301 \u6771" + "x" * 100))
    assert shape.label_at == (2.0, 3.0)
    assert "\n" not in shape.label and "\x1b" not in shape.label and "\u0301" not in shape.label
    assert shape.label.startswith("goal [31mA ?") and len(shape.label) == 60 and shape.label.endswith("…")


def test_an_unknown_type_is_refused_in_one_line() -> None:
    store = MarkerStore()
    store.offer(marker(42), 0.0)
    assert len(store) == 0 and store.refused == 1 and store.problem == "marker type 42 is not one rviz draws"


def test_add_modify_delete_and_deleteall_by_namespace_and_id() -> None:
    store = MarkerStore()
    store.offer(MarkerArray(markers=[marker(Marker.CUBE, ident=1), marker(Marker.CUBE, ident=2),
                                     marker(Marker.CUBE, ident=1, ns="other")]), 0.0)
    assert sorted(key for key, _, _ in store.held()) == [("n", 1), ("n", 2), ("other", 1)]
    store.offer(marker(Marker.SPHERE, 7.0, ident=1), 0.0)  # ADD of a held key replaces it
    assert len(store) == 3 and close(dict((k, s) for k, s, _ in store.held())[("n", 1)].starts[:, 0].max(), 7.5)
    gone = marker(Marker.CUBE, ident=2)
    gone.action = Marker.DELETE
    store.offer(gone, 0.0)
    assert sorted(key for key, _, _ in store.held()) == [("n", 1), ("other", 1)]
    everything = Marker(action=Marker.DELETEALL)
    store.offer(MarkerArray(markers=[everything, marker(Marker.CUBE, ident=9)]), 0.0)  # in order: cleared, then 9
    assert [key for key, _, _ in store.held()] == [("n", 9)]
    odd = marker(Marker.CUBE, ident=3)
    odd.action = 7
    store.offer(odd, 0.0)
    assert store.refused == 1 and "action 7" in store.problem


def test_lifetime_counts_from_arrival_and_zero_is_forever() -> None:
    store = MarkerStore()
    store.offer(MarkerArray(markers=[marker(Marker.CUBE, ident=1, lifetime=Duration(1, 500_000_000)),
                                     marker(Marker.CUBE, ident=2)]), 10.0)
    assert store.next_expiry() == 11.5
    assert not store.expire(11.4) and len(store) == 2
    assert store.expire(11.5) and [key for key, _, _ in store.held()] == [("n", 2)] and store.expired == 1
    assert store.next_expiry() is None and not store.expire(1e9)


def test_alpha_zero_is_not_drawn_and_removes_what_it_replaces() -> None:
    store = MarkerStore()
    store.offer(marker(Marker.CUBE), 0.0)
    store.offer(marker(Marker.CUBE, alpha=0.0), 0.0)
    assert len(store) == 0 and store.refused == 0


def test_a_flood_of_markers_is_bounded_and_said() -> None:
    store = MarkerStore(most=100)
    store.offer(MarkerArray(markers=[marker(Marker.CUBE, ident=i) for i in range(150)]), 0.0)
    assert len(store) == 100 and store.refused == 50 and store.problem == "more than 100 markers"
    scene = Scene2D(["/m"])
    scene.offer("/m", MarkerArray(markers=[marker(Marker.CUBE, ident=1, frame="")]), 0.0)
    assert scene.note("/m") == "0 markers; 1 not drawn: marker n/1 has no frame_id"


def test_a_point_list_of_a_million_points_is_strided() -> None:
    shape = marker_shape(marker(Marker.POINTS, points=tuple((i * 1e-3, 0.0) for i in range(300_000))), most=1000)
    assert len(shape.dots) <= 1000


def moving_lookup(state: dict[str, Pose2D]) -> Any:
    def lookup(target: str, source: str) -> Pose2D | None:
        return state.get(source) if target == "map" else None
    return lookup


def test_frame_locked_markers_follow_tf_and_others_stay_where_they_were_put() -> None:
    state = {"base": Pose2D(1.0, 0.0, 0.0)}
    scene = Scene2D(["/m"], "map", moving_lookup(state))
    scene.offer("/m", MarkerArray(markers=[marker(Marker.TEXT_VIEW_FACING, frame="base", ident=1, text="A"),
                                           marker(Marker.TEXT_VIEW_FACING, frame="base", ident=2, text="B",
                                                  frame_locked=True)]), 0.0)
    view = Viewport(40, 10, 0.0, 0.0, 0.1)

    def label_cols() -> dict[str, int]:
        scene.render(view)
        return {label.text: label.col for label in scene.labels}

    first = label_cols()
    assert first["A"] == first["B"]
    state["base"] = Pose2D(2.0, 0.0, 0.0)  # the robot drove 1 m: 5 cells at 0.1 m a dot, 2 dots a cell
    after = label_cols()
    assert after["A"] == first["A"] and after["B"] == first["B"] + 5
    scene.set_fixed_frame("map")  # a new fixed frame places every marker again
    assert label_cols()["A"] == after["B"]


def test_markers_without_a_transform_are_named_in_the_note() -> None:
    scene = Scene2D(["/m"], "map", moving_lookup({}))
    scene.offer("/m", marker(Marker.CUBE, frame="camera"), 0.0)
    assert scene.note("/m") == "1 marker; no transform from camera to map"


def test_colours_are_layers_of_their_own_bounded() -> None:
    scene = Scene2D(["/scan", "/m"], "map")
    scene.offer("/m", MarkerArray(markers=[marker(Marker.CUBE, ident=i, rgb=(i / 40, 1 - i / 40, 0.5))
                                           for i in range(40)]), 0.0)
    canvas = scene.render(Viewport(40, 10, 0.0, 0.0, 0.1))
    assert 1 < len(scene.layer_colors) <= 24 and len(canvas.bits) == 3 + len(scene.layer_colors)
    assert {topic for topic, _ in scene.layer_colors} == {"/m"}


MESHES = Path(__file__).parent / "mesh_corpus"


@pytest.mark.parametrize("name", ["turtlebot3-lds.stl", "turtlebot3-r200.dae"])
def test_a_mesh_marker_is_the_outline_of_its_real_mesh_as_trimesh_reads_it(name: str) -> None:
    """Real robot meshes (tests/mesh_corpus/SOURCES.md): the outline spans the mesh's x and y extent times the
    marker's scale, as trimesh (and pycollada's unit, which rviz applies to COLLADA files) measures it."""
    import collada
    import trimesh

    path = MESHES / name
    bounds = trimesh.load(str(path), force="mesh").bounds
    unit = collada.Collada(str(path)).assetInfo.unitmeter if name.endswith(".dae") else 1.0
    scale = (0.001, 0.002) if name.endswith(".stl") else (1.0, 1.0)
    m = marker(Marker.MESH_RESOURCE, 1.0, 2.0, scale=scale, mesh_resource=f"file://{path}")
    shape = marker_shape(m)
    assert not shape.note
    xs, ys = shape.starts[:, 0] - 1.0, shape.starts[:, 1] - 2.0
    assert math.isclose(xs.min(), bounds[0][0] * unit * scale[0], abs_tol=1e-9)
    assert math.isclose(xs.max(), bounds[1][0] * unit * scale[0], abs_tol=1e-9)
    assert math.isclose(ys.min(), bounds[0][1] * unit * scale[1], abs_tol=1e-9)
    assert math.isclose(ys.max(), bounds[1][1] * unit * scale[1], abs_tol=1e-9)


def test_a_mesh_of_a_package_is_found_as_rospack_finds_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    package = tmp_path / "robot_description"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>robot_description</name></package>")
    (package / "meshes" / "lds.stl").write_bytes((MESHES / "turtlebot3-lds.stl").read_bytes())
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    shape = marker_shape(marker(Marker.MESH_RESOURCE, scale=(0.001, 0.001),
                                mesh_resource="package://robot_description/meshes/lds.stl"))
    assert not shape.note and math.isclose(shape.starts[:, 0].max(), 0.06084831619262695, rel_tol=1e-6)


@pytest.mark.parametrize(("resource", "said"), [
    ("package://no_such_package/meshes/base.dae", "package 'no_such_package' of package://no_such_package"),
    ("http://example.com/base.stl", "is not a package:// or file:// resource"),
    ("file:///no/such/base.stl", "No such file or directory"),
])
def test_a_mesh_that_cannot_be_read_is_a_box_of_its_scale_and_the_legend_says_why(resource: str, said: str) -> None:
    scene = Scene2D(["/m"], "map")
    scene.offer("/m", marker(Marker.MESH_RESOURCE, scale=(2.0, 1.0), mesh_resource=resource), 0.0)
    store = scene.markers("/m")
    assert store is not None
    [(_, shape, _)] = store.held()
    assert {tuple(np.round(p, 9)) for p in shape.starts} == {(-1.0, -0.5), (1.0, -0.5), (1.0, 0.5), (-1.0, 0.5)}
    assert said in scene.note("/m") and "a mesh drawn as a box of its scale" in scene.note("/m")


def test_a_hostile_mesh_is_refused_in_one_line(tmp_path: Path) -> None:
    bomb = tmp_path / "bomb.dae"
    bomb.write_text('<?xml version="1.0"?><!DOCTYPE c [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;">]>'
                    '<COLLADA><library_geometries>&b;</library_geometries></COLLADA>')
    shape = marker_shape(marker(Marker.MESH_RESOURCE, mesh_resource=f"file://{bomb}"))
    assert "no vertex positions" in shape.note or "not XML" in shape.note
    text = tmp_path / "text.stl"
    text.write_text("solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 nan 0\nvertex a b c\nendloop\n")
    assert "not a number" in marker_shape(marker(Marker.MESH_RESOURCE, mesh_resource=f"file://{text}")).note


def test_a_mesh_path_to_a_device_or_a_fifo_is_refused_without_reading_it(tmp_path: Path) -> None:
    import os

    fifo = tmp_path / "mesh.stl"
    os.mkfifo(fifo)
    for resource, said in ((f"file://{fifo}", "not a regular file"), ("file:///dev/zero", "is not read"),
                           ("file:///dev/null.stl", "No such file")):
        assert said in marker_shape(marker(Marker.MESH_RESOURCE, mesh_resource=resource)).note


def test_nan_markers_neither_crash_the_picture_nor_the_fit() -> None:
    """A text marker at NaN, a points marker with a NaN point, an arrow of infinite length: drawn where they can
    be, the rest left out; fitting the view ignores them."""
    scene = Scene2D(["/m"], "map")
    nan = float("nan")
    scene.offer("/m", MarkerArray(markers=[  # offered as the store offers: NaN and inf are no warnings
        marker(Marker.TEXT_VIEW_FACING, nan, 1.0, ident=1, text="lost"),
        marker(Marker.POINTS, ident=2, points=((0.0, 0.0), (nan, 1.0), (1.0, 1.0))),
        marker(Marker.ARROW, ident=3, scale=(float("inf"), 1.0)),
    ]), 0.0)
    view = Viewport(40, 10, 0.0, 0.0, 0.1)
    with np.errstate(all="raise"):  # nothing left to warn of in drawing or fitting
        scene.render(view)
        assert scene.labels == []
        fitted = view.fitting(scene.world_points())
    assert all(math.isfinite(v) for v in (fitted.cx, fitted.cy, fitted.scale))


def test_large_line_lists_and_triangle_lists_keep_whole_pairs_and_triangles() -> None:
    """Past the point budget, a LINE_LIST keeps whole pairs (every k-th pair) and a TRIANGLE_LIST whole
    triangles: no segment joins the end of one pair to the start of another."""
    pairs = tuple(p for i in range(3000) for p in ((float(i), 0.0), (float(i), 1.0)))
    shape = marker_shape(marker(Marker.LINE_LIST, points=pairs), most=1000)
    assert 0 < len(shape.starts) <= 500
    assert close(shape.starts[:, 0], shape.ends[:, 0]) and close(shape.starts[:, 1], 0) and close(shape.ends[:, 1], 1)
    triangles = tuple(p for i in range(3000) for p in ((float(i), 0.0), (i + 0.5, 0.0), (float(i), 0.5)))
    shape = marker_shape(marker(Marker.TRIANGLE_LIST, points=triangles), most=999)
    assert 0 < len(shape.starts) <= 999 and len(shape.starts) % 3 == 0
    assert (np.floor(shape.starts[:, 0]) == np.floor(shape.ends[:, 0])).all()


def test_the_points_and_lines_of_all_markers_are_bounded_together() -> None:
    store = MarkerStore(most_elements=2500)
    strip = tuple((float(i), 0.0) for i in range(1001))
    store.offer(MarkerArray(markers=[marker(Marker.LINE_STRIP, ident=i, points=strip) for i in range(3)]), 0.0)
    assert len(store) == 2 and store.elements == 2000 and store.refused == 1
    assert store.problem == "more than 2500 points and lines in all markers"
    store.offer(marker(Marker.LINE_STRIP, ident=0, points=strip[:11]), 0.0)  # a replacement frees its old share
    store.offer(marker(Marker.LINE_STRIP, ident=2, points=strip), 0.0)
    assert len(store) == 3 and store.elements == 2010


def test_marker_messages_wait_in_order_within_a_count_and_a_byte_bound() -> None:
    """The feed of a marker topic keeps every message in order for the screen, up to its count and 64 MB; the
    oldest are dropped past that and counted, and the legend says so (what they added or deleted is missing)."""
    from types import SimpleNamespace

    from rostui.apps.view import feed as feed_module
    from rostui.apps.view.feed import TopicFeed

    feed = TopicFeed("/m", lambda: None, clock=lambda: 1.0)
    feed.keep_every = 3
    for i in range(5):
        feed._on_message(SimpleNamespace(_buff=bytes(10), i=i))
    assert [feed.take()[0].i for _ in range(3)] == [2, 3, 4] and feed.take() is None and feed.dropped == 2  # type: ignore[index]
    feed.keep_every = 1000
    big = feed_module.KEEP_BYTES // 3 + 1
    for i in range(4):
        feed._on_message(SimpleNamespace(_buff=bytes(big), i=i))
    assert feed._queue_bytes <= feed_module.KEEP_BYTES and len(feed._queue) == 2 and feed.dropped == 4
    scene = Scene2D(["/m"], "map")
    scene.offer("/m", marker(Marker.CUBE), 0.0)
    store = scene.markers("/m")
    assert store is not None
    store.dropped = 4
    assert scene.note("/m") == "1 marker; 4 messages dropped: the screen fell behind"


def test_the_fixed_frame_comes_from_the_first_marker_that_names_one() -> None:
    """A MarkerArray that starts with a DELETEALL (no frame, a common pattern) takes its frame from the next."""
    scene = Scene2D(["/m"])
    scene.offer("/m", MarkerArray(markers=[Marker(action=Marker.DELETEALL), marker(Marker.CUBE, frame="odom")]), 0.0)
    assert scene.fixed_frame == "odom" and scene.note("/m") == "1 marker"
