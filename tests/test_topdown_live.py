"""The top-down app live: a real publisher of every top-down type (Debian's rospy, rostui's client) drawn in place.

tests/peers/topdown_talker.py publishes LaserScan, Odometry, PoseStamped,
PoseArray, Path, OccupancyGrid and a big-endian float64 PointCloud2 at 10 Hz,
all in frame "map"; the app subscribes, and each topic's colour must appear
where the talker put it (topdown_helpers.TALKER_SPOTS).  When the app quits,
its subscriptions leave the master.
"""

from __future__ import annotations

import sys
import xmlrpc.client


from conftest import SYSTEM_PYTHON, until
from interop_helpers import PEERS, Spawn, spawn  # noqa: F401  (fixture)
from rostui.apps.view.topdown_app import TopDownApp
from topdown_helpers import TALKER_SPOTS, sync

TOPICS = list(TALKER_SPOTS)


def subscribed_by_view(env: dict[str, str]) -> set[str]:
    """Topics the master lists the view's node as a subscriber of."""
    _, _, (_, subs, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/topdown_test")
    return {topic for topic, nodes in subs if any(n.startswith("/rostui_monitor") for n in nodes)}


async def check_drawn(env: dict[str, str]) -> None:
    app = TopDownApp(TOPICS, period=0.3)
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view

        def owner(topic: str) -> str | None:
            vp = view.viewport
            cell = vp.cell_of(*TALKER_SPOTS[topic]) if vp is not None else None
            return view.cell_topic(*cell) if cell is not None else None

        await until(lambda: all(owner(t) == t for t in TOPICS),
                    f"every topic drawn in place: {[(t, owner(t)) for t in TOPICS]} {view.row_text(0)!r}")
        assert view.scene.fixed_frame == "map"
        assert "no transform" not in view.row_text(0) and "cannot draw" not in view.row_text(0)
        assert subscribed_by_view(env) == set(TOPICS)
        await pilot.press("q")
    assert app.return_code == 0
    assert subscribed_by_view(env) == set()


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
