"""`rostui view` live with top-down topics: a real publisher of every top-down type (Debian's rospy, rostui's
client), all drawn in ONE view, each in place.

tests/peers/topdown_talker.py publishes LaserScan, Odometry, PoseStamped,
PoseArray, Path, OccupancyGrid and a big-endian float64 PointCloud2 at 10 Hz
in frame "map", plus a scan in frame "laser" placed by a latched /tf_static
map -> laser.  The app (ViewApp with ``--frame map``) mounts one TopDownView
for all of them; each topic's colour must appear where the talker put it
(topdown_helpers.TALKER_SPOTS).  When the app quits, its subscriptions leave
the master.
"""

from __future__ import annotations

import math
import sys
import xmlrpc.client

from conftest import REPO, SYSTEM_PYTHON, until
from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from rostui.apps.view.app import ViewApp, app_of
from rostui.apps.view.panel import ViewPanel
from rostui.apps.view.topdown_view import TopDownView
from rostui.models.sensors.view_file import spec_from_rviz
from topdown_helpers import TALKER_SPOTS, sync

TOPICS = list(TALKER_SPOTS)


def subscriptions(env: dict[str, str]) -> set[str]:
    """Topics the master lists some rostui view node as a subscriber of."""
    _, _, (_, subs, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/topdown_test")
    return {topic for topic, nodes in subs if any(n.startswith("/rostui_view") for n in nodes)}


def spot_owner(view: TopDownView, topic: str) -> str | None:
    """The topic drawn in the cell where the talker puts ``topic`` (topdown_helpers.TALKER_SPOTS)."""
    vp = view.viewport
    cell = vp.cell_of(*TALKER_SPOTS[topic]) if vp is not None else None
    return view.cell_topic(*cell) if cell is not None else None


async def check_drawn(env: dict[str, str]) -> None:
    app = ViewApp(TOPICS, period=0.3, frame="map")
    async with app.run_test(size=(100, 30)) as pilot:
        await until(lambda: len(app.query(TopDownView)) == 1, "the top-down view mounted")
        view = app.query_one(TopDownView)

        def owner(topic: str) -> str | None:
            return spot_owner(view, topic)

        await until(lambda: all(owner(t) == t for t in TOPICS),
                    lambda: f"every topic drawn in place: {[(t, owner(t)) for t in TOPICS]} {view.row_text(0)!r} "
                    f"size {view.size} {view.viewport} "
                    f"panels {[(p.topic, p.display, p.joined) for p in app.query(ViewPanel)]}")
        assert len(app.query(TopDownView)) == 1
        assert [p.topic for p in app.query(ViewPanel) if p.display] == ["/scan"]  # the others joined its view
        assert view.scene.fixed_frame == "map"
        assert "no transform" not in view.row_text(0) and "cannot draw" not in view.row_text(0)
        assert set(TOPICS) | {"/tf", "/tf_static"} <= subscriptions(env)
        await pilot.press("q")
    assert app.return_code == 0
    # the unregistrations left on quit; a busy master answers them when it can
    await until(lambda: subscriptions(env) == set(), lambda: f"the master forgetting {subscriptions(env)}")


@sync
async def test_rospy_publishers_on_rostui_core(ros_env: dict[str, str], rostui_core: object, spawn: Spawn,
                                               rospy_available: None) -> None:
    talker = spawn([SYSTEM_PYTHON, str(PEERS / "topdown_talker.py"), "rospy"], label="rospy topdown talker")
    talker.wait_for("ready")
    await check_drawn(ros_env)


@sync
async def test_rostui_client_publishers_on_real_roscore(ros_env: dict[str, str], real_roscore: object,
                                                        spawn: Spawn) -> None:
    talker = spawn([sys.executable, str(PEERS / "topdown_talker.py"), "rostui"], label="rostui topdown talker")
    talker.wait_for("ready")
    await check_drawn(ros_env)


@sync
async def test_turtlebot3_navigation_rviz_opens_with_its_displays(ros_env: dict[str, str], rostui_core: object,
                                                                spawn: Spawn, rospy_available: None) -> None:
    """turtlebot3_navigation.rviz (tests/rviz_corpus): its /scan, /map and footprint Polygon displays, published
    by Debian's rospy, drawn in place in its fixed frame, in one top-down view; its other displays wait."""
    talker = spawn([SYSTEM_PYTHON, str(PEERS / "topdown_talker.py"), "rospy"], label="rospy topdown talker")
    talker.wait_for("ready")
    spec, _ = spec_from_rviz(REPO / "tests" / "rviz_corpus" / "turtlebot3-turtlebot3_navigation.rviz")
    app = app_of(spec, period=0.3)
    drawn = ("/scan", "/map", "/move_base/local_costmap/footprint")
    async with app.run_test(size=(120, 40)) as pilot:
        await until(lambda: len(app.query(TopDownView)) == 1, "the top-down view mounted")
        view = app.query_one(TopDownView)

        def owner(topic: str) -> str | None:
            return spot_owner(view, topic)

        await until(lambda: all(owner(t) == t for t in drawn),
                    lambda: f"the rviz file's displays drawn: {[(t, owner(t)) for t in drawn]} {view.row_text(0)!r}")
        assert view.scene.fixed_frame == "map" and view.tool_topics.goal == "/move_base_simple/goal"
        assert math.isclose(view.span, 12.79)  # rviz's window width over its TopDownOrtho scale
        await pilot.press("q")
    assert app.return_code == 0
