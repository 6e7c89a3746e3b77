"""The top-down view's tools against Debian's rospy: g sends a 2D nav goal, p a 2D pose estimate, t drives, each
exactly as rviz (and a teleop) sends them, in the fixed frame, to where the keys put the cursor; nothing is
advertised before a key asks for it.

tests/peers/topdown_talker.py (rospy) gives the view a map in frame "map"; tests/peers/rospy_typed_listener.py
(rospy) subscribes to /move_base_simple/goal, /initialpose and /cmd_vel and prints what it gets."""

from __future__ import annotations

import math
import sys
import xmlrpc.client
from typing import Any

from conftest import SYSTEM_PYTHON, until, wait_until
from interop_helpers import PEERS, Peer, Spawn, rospy_peer, spawn  # noqa: F401  (fixture)
from rostui.apps.view.app import ViewApp
from rostui.apps.view.panel import ViewPanel
from rostui.apps.view.topdown_view import TopDownView
from rostui.core.msg import get_message_class
from topdown_helpers import ViewTestApp, occupancy, sync

GOAL, POSE, TWIST = "geometry_msgs/PoseStamped", "geometry_msgs/PoseWithCovarianceStamped", "geometry_msgs/Twist"


def received(listener: Peer, topic: str, type_name: str) -> list[Any]:
    """What the rospy listener printed for ``topic``, decoded with rostui's class."""
    cls = get_message_class(type_name)
    return [cls().deserialize(bytes.fromhex(parts[3])) for parts in (line.split() for line in list(listener.lines))
            if len(parts) == 4 and parts[0] == topic]


def publishers(env: dict[str, str], topic: str) -> list[str]:
    """The nodes the master lists as publishing ``topic``."""
    _, _, (pubs, _, _) = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getSystemState("/tools_test")
    return next((nodes for name, nodes in pubs if name == topic), [])


def map_and_listener(spawn: Spawn, *topics: str) -> Peer:
    """Debian's rospy publishing a map in "map" (tests/peers/topdown_talker.py), and a rospy listener of
    ``topics`` (``/topic=pkg/Type``), both ready."""
    talker = spawn([SYSTEM_PYTHON, str(PEERS / "topdown_talker.py"), "rospy"], label="rospy topdown talker")
    listener = spawn(rospy_peer("rospy_typed_listener.py", *topics), label="listener")
    talker.wait_for("ready")
    listener.wait_for("subscribed")
    return listener


def status(view: TopDownView) -> str:
    """The view's last row: the scale bar, or the mode's line."""
    return view.row_text(view.size.height - 1)


def yaw(q: Any) -> float:
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))


@sync
async def test_goal_pose_estimate_and_teleop_reach_rospy_as_rviz_sends_them(
        ros_env: dict[str, str], rostui_core: object, spawn: Spawn, rospy_available: None) -> None:
    listener = map_and_listener(spawn, f"/move_base_simple/goal={GOAL}", f"/initialpose={POSE}", f"/cmd_vel={TWIST}")
    app = ViewApp(["/map"], period=0.3, frame="map")
    async with app.run_test(size=(100, 30)) as pilot:
        await until(lambda: len(app.query(TopDownView)) == 1, "the top-down view mounted")
        view = app.query_one(TopDownView)
        view.focus()
        panel = app.query_one(ViewPanel)
        await until(lambda: view.scene.received("/map") > 0 and "frame map" in status(view) and not panel.note.display
                    and view.size.height == panel.content_size.height and view.viewport is not None
                    and view.viewport.rows == view.size.height - 2,
                    "the map drawn, the panel's waiting note gone, the view at its full size")
        for topic in ("/move_base_simple/goal", "/initialpose", "/cmd_vel"):
            assert publishers(ros_env, topic) == [], f"{topic} advertised before any key"
        assert "GOAL" not in status(view)
        # the cursor starts on the centre cell and moves a cell a key
        vp = view.viewport
        assert vp is not None
        x, y = vp.cell_centre(vp.cols // 2 + 12, vp.rows // 2 - 5)
        await pilot.press("g", *["right"] * 12, *["up"] * 5, "a", "a", "a", "a", "a", "a")
        await until(lambda: f"GOAL {x:.2f},{y:.2f} 90° → /move_base_simple/goal (1 sub)  Enter send  Esc cancel"
                    in status(view),
                    lambda: f"the cursor's line with rospy connected: {status(view)!r}")
        assert view.cell_topic(vp.cols // 2 + 12, vp.rows // 2 - 5) == "(cursor)"
        await pilot.press("enter")
        await until(lambda: len(received(listener, "/move_base_simple/goal", GOAL)) == 1, "the goal at rospy")
        goal = received(listener, "/move_base_simple/goal", GOAL)[0]
        assert goal.header.frame_id == "map" and goal.header.stamp.to_sec() > 0
        assert (goal.pose.position.x, goal.pose.position.y, goal.pose.position.z) == (x, y, 0.0)
        assert math.isclose(yaw(goal.pose.orientation), math.pi / 2, abs_tol=1e-6)
        assert f"sent goal x {x:.2f} y {y:.2f} θ 90° (map) on /move_base_simple/goal (1 sub)" in status(view)
        # p: a click puts the cursor at the cell's centre, a drag gives the heading
        start = vp.cell_of(-1.0, -1.0)
        assert start is not None
        await pilot.press("p")
        await until(lambda: "→ /initialpose (1 sub)" in status(view) and status(view).startswith("POSE"),
                    "rospy connected to /initialpose")
        await pilot.mouse_down(TopDownView, offset=(start[0], start[1] + view.canvas_top))
        await pilot.mouse_up(TopDownView, offset=(start[0] - 10, start[1] + view.canvas_top))
        await pilot.press("enter")
        await until(lambda: len(received(listener, "/initialpose", POSE)) == 1, "the pose estimate at rospy")
        pose = received(listener, "/initialpose", POSE)[0]
        x, y = vp.cell_centre(*start)
        assert abs(x + 1.0) <= vp.scale and abs(y + 1.0) <= 2 * vp.scale  # within the cell
        assert math.isclose(pose.pose.pose.position.x, x) and math.isclose(pose.pose.pose.position.y, y)
        assert math.isclose(abs(yaw(pose.pose.pose.orientation)), math.pi, abs_tol=1e-6)  # dragged to the left
        assert pose.header.frame_id == "map"
        expected = [0.0] * 36
        expected[0], expected[7], expected[35] = 0.25, 0.25, (math.pi / 12) ** 2
        assert [round(v, 12) for v in pose.pose.covariance] == [round(v, 12) for v in expected]
        # t: each arrow one Twist at teleop_twist_keyboard's speeds; Esc stops the robot and leaves
        await pilot.press("t")
        await until(lambda: "TELEOP → /cmd_vel (1 sub)" in status(view), "rospy connected to /cmd_vel")
        await pilot.press("up", "left")
        await until(lambda: "TELEOP → /cmd_vel (1 sub)  sent +0.0 m/s +1.0 rad/s" in status(view), "what left")
        await pilot.press("escape")
        await until(lambda: len(received(listener, "/cmd_vel", TWIST)) == 3, "three twists at rospy")
        twists = [(t.linear.x, t.angular.z) for t in received(listener, "/cmd_vel", TWIST)]
        assert twists == [(0.5, 0.0), (0.0, 1.0), (0.0, 0.0)]
        assert view.tool is None and view.scene.cursor is None
        # quitting while driving stops the robot first, as a teleop keyboard does on exit
        await pilot.press("t")
        await until(lambda: "TELEOP → /cmd_vel (1 sub)" in status(view), "teleop again")
        await pilot.press("up")
        await until(lambda: len(received(listener, "/cmd_vel", TWIST)) == 4, "the fourth twist")
        await pilot.press("q")
    assert app.return_code == 0
    wait_until(lambda: len(received(listener, "/cmd_vel", TWIST)) == 5, "the stop sent on quitting")
    assert [(t.linear.x, t.angular.z) for t in received(listener, "/cmd_vel", TWIST)][3:] == [(0.5, 0.0), (0.0, 0.0)]


@sync
async def test_outside_rostui_view_nothing_is_sent_and_bag_view_has_no_tools() -> None:
    """A view with no panel (no node) says it sent nothing; the bag inspector's view (one recorded message at a
    time) takes no tool keys at all: g, p and t are bag view's own there."""
    app = ViewTestApp(["/map"], frame="map")
    async with app.run_test(size=(80, 24)) as pilot:
        view = app.view
        view.show_topic_message("/map", occupancy())
        await pilot.press("g", "right", "enter")
        await until(lambda: "not sent: no node here" in status(view), lambda: status(view))
        assert view.tool is None
    inspector = TopDownView.for_bag("/markers")
    assert inspector.one_message and inspector.check_action("tool", ("goal",)) is False
    assert inspector.check_action("confirm", ()) is False and inspector.check_action("zoom", (1,)) is True


@sync
async def test_under_sim_time_a_goal_is_stamped_with_the_clock(
        ros_env: dict[str, str], rostui_core: object, spawn: Spawn, rospy_available: None) -> None:
    """/use_sim_time true and a /clock at 1234.5 s (a simulator, or rosbag play --clock): the goal's stamp is the
    clock's, as rviz stamps it; a wall stamp would be in the future for move_base's transforms."""
    xmlrpc.client.ServerProxy(ros_env["ROS_MASTER_URI"]).setParam("/tools_test", "/use_sim_time", True)
    spawn([sys.executable, "-m", "rostui", "topic", "pub", "-r", "20", "/clock", "rosgraph_msgs/Clock",
                   "clock: {secs: 1234, nsecs: 500000000}"], label="clock")
    listener = map_and_listener(spawn, f"/move_base_simple/goal={GOAL}")
    app = ViewApp(["/map"], period=0.3, frame="map")
    async with app.run_test(size=(100, 30)) as pilot:
        await until(lambda: len(app.query(TopDownView)) == 1, "the top-down view mounted")
        view = app.query_one(TopDownView)
        view.focus()
        await until(lambda: "frame map" in status(view), "the map drawn")
        await pilot.press("g")
        await until(lambda: "(1 sub)" in status(view) and view.sender is not None and view.sender.now().secs == 1234,
                    lambda: f"rospy connected and the clock heard: {status(view)!r}")
        await pilot.press("enter")
        await until(lambda: len(received(listener, "/move_base_simple/goal", GOAL)) == 1, "the goal at rospy")
        stamp = received(listener, "/move_base_simple/goal", GOAL)[0].header.stamp
        assert (stamp.secs, stamp.nsecs) == (1234, 500000000)
        await pilot.press("q")
    assert app.return_code == 0
