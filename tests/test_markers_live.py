"""Markers from a real rospy node in `rostui view`: tests/peers/rospy_markers.py (Debian's rospy and
visualization_msgs) publishes a latched MarkerArray with one marker of every type in frame "map"; each is drawn
where the peer put it, in the topic's layers; a marker with a lifetime goes when it ends; DELETEALL empties the
picture. Sampled cells are checked as the other top-down tests check theirs."""

from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import SYSTEM_PYTHON, need_peer, until
from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from rostui.apps.view.app import ViewApp
from rostui.apps.view.topdown_view import TopDownView
from topdown_helpers import sync

#: A point on each marker's outline, line or dot (metres, frame "map"), by the marker's type.
MARKER_SPOTS: dict[str, tuple[float, float]] = {
    "ARROW": (-2.5, 2.0), "CUBE": (-0.5, 2.0), "SPHERE": (1.5, 2.0), "CYLINDER": (3.5, 2.0),
    "LINE_STRIP": (-3.0, 0.0), "LINE_LIST": (-1.0, 0.3), "CUBE_LIST": (1.3, 0.0), "SPHERE_LIST": (3.0, 0.3),
    "POINTS": (-3.0, -2.0), "MESH_RESOURCE": (1.4, -2.0), "TRIANGLE_LIST": (3.3, -2.0),
}
#: Where the short-lived cube's outline is.
SHORT_SPOT = (0.2, -1.0)


def _visualization_msgs() -> bool:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import visualization_msgs.msg"], capture_output=True)
    return probe.returncode == 0


def near(view: TopDownView, spot: tuple[float, float]) -> set[str | None]:
    """The topics drawn in the cell of ``spot`` and the eight around it."""
    vp = view.viewport
    cell = vp.cell_of(*spot) if vp is not None else None
    if cell is None:
        return set()
    return {view.cell_topic(cell[0] + dc, cell[1] + dr) for dc in (-1, 0, 1) for dr in (-1, 0, 1)}


@sync
async def test_every_marker_type_from_rospy_is_drawn_in_place_and_deleteall_clears(
        ros_env: dict[str, str], rostui_core: object, spawn: Spawn, rospy_available: None, tmp_path: Path) -> None:
    need_peer(_visualization_msgs(), "visualization_msgs (Debian python3-visualization-msgs)")
    trigger = tmp_path / "delete-all"
    peer = spawn([SYSTEM_PYTHON, str(PEERS / "rospy_markers.py"), str(trigger)], label="rospy markers")
    peer.wait_for("ready")
    app = ViewApp(["/markers"], period=0.3, frame="map")
    async with app.run_test(size=(100, 30)) as pilot:
        await until(lambda: len(app.query(TopDownView)) == 1, "the top-down view mounted")
        view = app.query_one(TopDownView)
        await until(lambda: all("/markers" in near(view, spot) for spot in MARKER_SPOTS.values()),
                    lambda: f"every marker type drawn in place: "
                    f"{[(kind, near(view, spot)) for kind, spot in MARKER_SPOTS.items()]} {view.row_text(0)!r}")
        assert any("hi" in view.row_text(r) for r in range(view.canvas_top, view.canvas_top + 28)), "the text marker"
        store = view.scene.markers("/markers")
        assert store is not None and store.refused == 0, store.problem if store else None
        # POINTS with a colour per point: the red point and the blue point are drawn in different colours
        vp = view.viewport
        assert vp is not None
        red_cell, blue_cell = vp.cell_of(-3.0, -2.0), vp.cell_of(-2.7, -1.7)
        assert red_cell and blue_cell
        red, blue = view.cell_color(*red_cell), view.cell_color(*blue_cell)
        assert red is not None and blue is not None and red[0] > red[2] and blue[2] > blue[0], (red, blue)
        # the short-lived cube ends after its 2 s; the others stay
        await until(lambda: store.expired == 1, lambda: f"the short-lived marker gone: {len(store)} held")
        assert ("short", 0) not in {key for key, _, _ in store.held()} and len(store) == 12
        await pilot.pause(0.2)
        assert "/markers" not in near(view, SHORT_SPOT)
        assert "12 markers" in view.row_text(0)
        trigger.touch()
        peer.wait_for("deleted all")
        await until(lambda: len(store) == 0 and all("/markers" not in near(view, spot)
                                                    for spot in MARKER_SPOTS.values()),
                    lambda: f"DELETEALL cleared the picture: {len(store)} held")
        assert "0 markers" in view.row_text(0)
        await pilot.press("q")
    assert app.return_code == 0
