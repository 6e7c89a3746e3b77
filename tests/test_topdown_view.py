"""The top-down view under Textual's pilot: a known scan lands in the right cells; zoom, pan, fit, notes, frames."""

from __future__ import annotations

import math
import re

from rostui.apps.view.topdown_view import TopDownView
from rostui.models.sensors.pose2d import Pose2D
from topdown_helpers import ViewTestApp, odometry, occupancy, path, pose_array, sync, wall_scan


def scan_cells(view: TopDownView, topic: str = "/scan") -> set[tuple[int, int]]:
    """Canvas cells (column, row) drawn in ``topic``'s colour."""
    vp = view.viewport
    assert vp is not None
    return {(c, r) for r in range(vp.rows) for c in range(vp.cols) if view.cell_topic(c, r) == topic}


@sync
async def test_a_wall_2_05_m_ahead_fills_one_column_of_cells() -> None:
    """80x24: 10 m across 160 dots; x = 2.05 m is dot 112.8 -> column 56; y = ±2.05 m -> rows 2..19."""
    app = ViewTestApp(["/scan"])
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05))
        await pilot.pause(0.15)
        assert view.viewport is not None and (view.viewport.cols, view.viewport.rows) == (80, 22)
        assert scan_cells(view) == {(56, r) for r in range(2, 20)}
        wall = [view.row_text(view.canvas_top + r)[56] for r in range(2, 20)]
        assert all("⠀" < ch <= "⣿" for ch in wall)
        assert view.row_text(0).startswith("■ /scan")
        assert view.row_text(23).startswith("├──────┤ 1 m   frame laser")


@sync
async def test_zoom_pan_origin_and_fit_move_the_wall() -> None:
    app = ViewTestApp(["/scan"])
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05))
        await pilot.pause(0.15)
        await pilot.press("plus")  # 1.5x: 2.05 m is 49.2 dots right of the centre -> column 64
        assert {c for c, _ in scan_cells(view)} == {64}
        await pilot.press("minus")
        assert {c for c, _ in scan_cells(view)} == {56}
        await pilot.press("right")  # an eighth of 80 columns: the world moves 10 columns left
        assert {c for c, _ in scan_cells(view)} == {46}
        await pilot.press("up", "up")  # 2 x 2 rows: the wall moves 4 rows down
        assert {r for _, r in scan_cells(view)} == set(range(6, 22))
        await pilot.press("0")
        assert scan_cells(view) == {(56, r) for r in range(2, 20)}
        await pilot.press("c")  # fit: the whole wall, top to bottom of the canvas (10 % margins), centred
        rows = {r for _, r in scan_cells(view)}
        assert min(rows) <= 3 and max(rows) >= 18 and {c for c, _ in scan_cells(view)} <= {39, 40}
        assert "frame laser" in view.row_text(23)


@sync
async def test_a_view_not_moved_yet_keeps_the_starting_zoom_when_it_grows() -> None:
    """First laid out 12 columns wide (as beside seven other panels, before they join it), then 80: still 10 m
    across, so the wall lands where it would have at 80 columns; once zoomed, a resize keeps the zoom."""
    app = ViewTestApp(["/scan"])
    async with app.run_test(size=(12, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05))
        await pilot.pause(0.15)
        assert view.viewport is not None and view.viewport.cols == 12
        await pilot.resize_terminal(80, 24)
        await pilot.pause(0.15)
        assert scan_cells(view) == {(56, r) for r in range(2, 20)}
        await pilot.press("plus")
        zoomed = view.viewport
        assert zoomed is not None
        await pilot.resize_terminal(100, 24)
        await pilot.pause(0.15)
        assert view.viewport is not None and view.viewport.scale == zoomed.scale


@sync
async def test_scale_bar_follows_the_zoom() -> None:
    app = ViewTestApp(["/scan"])
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05))
        await pilot.pause(0.15)
        for _ in range(4):
            await pilot.press("minus")  # 1.5^4 = 5.06x further: 50.6 m across, 16 dots are 5.06 m: 10 m lines
        assert view.row_text(23).startswith("├" + "─" * 14 + "┤ 10 m")
        for _ in range(8):
            await pilot.press("plus")  # 1.98 m across
        assert "20 cm" in view.row_text(23)


@sync
async def test_other_frames_are_left_out_with_a_note_and_drawn_with_a_transform() -> None:
    app = ViewTestApp(["/scan", "/odom"])
    async with app.run_test(size=(100, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05, frame="laser"))
        view.show_topic_message("/odom", odometry(0.5, 0.5, 0.0, frame="odom"))
        await pilot.pause(0.15)
        assert "■ /odom (no transform from odom to laser)" in view.row_text(0)
        assert scan_cells(view, "/odom") == set()
    poses = {("laser", "odom"): Pose2D(-1.0, 0.0, 0.0)}
    app = ViewTestApp(["/scan", "/odom"], lookup=lambda target, source: poses.get((target, source)))
    async with app.run_test(size=(100, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05, frame="laser"))
        view.show_topic_message("/odom", odometry(0.5, 0.53, 0.0, frame="odom"))
        await pilot.pause(0.15)
        assert "no transform" not in view.row_text(0)
        vp = view.viewport
        assert vp is not None
        tail = vp.cell_of(-0.5 + 0.05, 0.53)  # the arrow starts at odom (0.5, 0.53) -> laser (-0.5, 0.53)
        assert tail is not None and view.cell_topic(*tail) == "/odom"


@sync
async def test_fixed_frame_option_and_grid_path_pose_layers() -> None:
    app = ViewTestApp(["/map", "/path", "/poses"], frame="map")
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/map", occupancy())
        view.show_topic_message("/path", path([(-3.0, -2.0), (-1.0, -2.0)], frame="map"))
        view.show_topic_message("/poses", pose_array([(2.03, 2.03, 0.0), (3.03, 2.03, math.pi)], frame="map"))
        await pilot.pause(0.15)
        vp = view.viewport
        assert vp is not None
        for x, y, topic in [(-0.2, 0.2, "/map"), (0.8, 0.8, "/map"), (-0.7, 0.2, None), (-2.0, -2.02, "/path"),
                            (2.3, 2.03, "/poses"), (2.73, 2.03, "/poses")]:
            cell = vp.cell_of(x, y)
            assert cell is not None
            owner = view.cell_topic(*cell)
            assert owner == topic or (topic is None and owner in (None, "")), (x, y, owner)
        assert "frame map" in view.row_text(23)


@sync
async def test_messages_are_dropped_not_queued_and_frames_are_bounded() -> None:
    """A burst of 200 scans between two frames is one frame showing the newest scan."""
    app = ViewTestApp(["/scan"])
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(2.05))
        await pilot.pause(0.15)
        before = view.frames
        for i in range(200):
            view.show_topic_message("/scan", wall_scan(2.05 - 0.005 * i))
        assert view.frames == before  # nothing drawn on arrival
        await pilot.pause(0.2)
        assert view.frames - before <= 1 + math.ceil(0.2 * TopDownView.FRAME_RATE) + 2
        assert view.scene.received("/scan") == 201
        assert re.search(r"   \d+\.\d msg/s \(\d+\.\d drawn\)$", view.row_text(23)), view.row_text(23)
        assert {c for c, _ in scan_cells(view)} == {vp_col(view, 2.05 - 0.005 * 199)}


def vp_col(view: TopDownView, x: float) -> int:
    """The canvas column showing x (at y = 0)."""
    assert view.viewport is not None
    cell = view.viewport.cell_of(x, 0.0)
    assert cell is not None
    return cell[0]


@sync
async def test_an_unreadable_message_is_a_note_not_a_crash() -> None:
    app = ViewTestApp(["/x"])
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        msg = occupancy()
        msg.data = [1, 2, 3]
        view.show_topic_message("/x", msg)
        await pilot.pause(0.15)
        assert "■ /x (cannot draw: 3 cells of data for a 4 x 2 grid)" in view.row_text(0)


@sync
async def test_f_steps_the_fixed_frame_through_the_frames_named() -> None:
    """laser sits at x = 1 in odom: with f the fixed frame becomes odom and the wall moves 1 m right."""
    poses = {("odom", "laser"): Pose2D(1.0, 0.0, 0.0), ("laser", "odom"): Pose2D(-1.0, 0.0, 0.0)}
    app = ViewTestApp(["/scan", "/odom"], lookup=lambda target, source: poses.get((target, source)))
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/scan", wall_scan(1.05, frame="laser"))
        view.show_topic_message("/odom", odometry(0.0, 0.0, 0.0, frame="odom"))
        await pilot.pause(0.15)
        assert "frame laser" in view.row_text(23) and {c for c, _ in scan_cells(view)} == {vp_col(view, 1.05)}
        await pilot.press("f")
        assert "frame odom" in view.row_text(23) and {c for c, _ in scan_cells(view)} == {vp_col(view, 2.05)}
        await pilot.press("f")
        assert "frame laser" in view.row_text(23)


@sync
async def test_the_footprint_is_drawn_at_the_robot_and_o_follows_it() -> None:
    """A 0.6 m square footprint on base_link, which tf puts at (2, 1) in map: its right edge (x = 2.3) is drawn
    there; o centres the view on the robot and keeps it there as tf moves it; panning by hand stops following."""
    from textual.app import App, ComposeResult

    from rostui.models.sensors.footprint import footprint_outline

    robot = {"base_link": Pose2D(2.0, 1.0, 0.0)}

    class FootprintApp(App[None]):
        def compose(self) -> ComposeResult:
            yield TopDownView(topics=["/map"], frame="map", lookup=lambda target, source: robot.get(source),
                              footprint=footprint_outline("[[0.3, 0.3], [0.3, -0.3], [-0.3, -0.3], [-0.3, 0.3]]"),
                              show_rates=False)

    app = FootprintApp()
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.query_one(TopDownView)
        view.focus()
        await pilot.pause(0.1)
        vp = view.viewport
        assert vp is not None
        cell = vp.cell_of(2.3, 1.0)
        assert cell is not None and view.cell_topic(*cell) == "(footprint)"
        assert view.row_text(0).startswith("■ /map (no message yet)  ■ (footprint)")
        await pilot.press("o")
        await pilot.pause(0.1)
        assert (view.viewport.cx, view.viewport.cy) == (2.0, 1.0)  # type: ignore[union-attr]
        assert "following base_link" in view.row_text(23)
        robot["base_link"] = Pose2D(-1.0, 0.5, 0.0)
        view._tf_changed()
        await pilot.pause(0.15)
        assert (view.viewport.cx, view.viewport.cy) == (-1.0, 0.5)  # type: ignore[union-attr]
        await pilot.press("right")
        assert not view.follow and "centre" in view.row_text(23)
