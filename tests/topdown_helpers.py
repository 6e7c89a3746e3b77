"""Helpers for the top-down view tests: known messages (rostui's classes) and a tiny app around one view."""

from __future__ import annotations

import asyncio
import functools
import math
import pathlib
from typing import Any, Awaitable, Callable, Sequence

import numpy as np
from textual.app import App, ComposeResult

from rostui.apps.view.topdown_view import TopDownView
from rostui.core.msg import get_message_class
from rostui.models.sensors.scene2d import Lookup, same_frame_only

LaserScan = get_message_class("sensor_msgs/LaserScan")
Odometry = get_message_class("nav_msgs/Odometry")
Path = get_message_class("nav_msgs/Path")
PoseStamped = get_message_class("geometry_msgs/PoseStamped")
PoseArray = get_message_class("geometry_msgs/PoseArray")
Pose = get_message_class("geometry_msgs/Pose")
OccupancyGrid = get_message_class("nav_msgs/OccupancyGrid")
Marker = get_message_class("visualization_msgs/Marker")
MarkerArray = get_message_class("visualization_msgs/MarkerArray")
Point = get_message_class("geometry_msgs/Point")
ColorRGBA = get_message_class("std_msgs/ColorRGBA")

#: Where the live talker (tests/peers/topdown_talker.py) puts each topic: a point of its drawing, in "map".
TALKER_SPOTS: dict[str, tuple[float, float]] = {
    "/scan": (2.05, 0.55), "/odom": (-1.75, 1.05), "/pose": (-2.35, -1.05), "/poses": (0.55, 2.05),
    "/path": (-2.05, -2.05), "/map": (3.55, -2.3), "/cloud": (0.53, 0.05), "/scan_laser": (1.3, 1.05),
    "/move_base/local_costmap/footprint": (-2.7, 0.0),
}


def wall_scan(x: float = 2.05, frame: str = "laser", half_angle: int = 45) -> Any:
    """A scan from the origin of a wall at ``x`` m (beams every degree within ±``half_angle``), two bad beams."""
    angles = np.radians(np.arange(-half_angle, half_angle + 1))
    ranges = list(x / np.cos(angles))
    ranges[10] = float("inf")
    ranges[11] = float("nan")
    msg = LaserScan(angle_min=float(angles[0]), angle_max=float(angles[-1]), angle_increment=math.radians(1),
                    range_min=0.1, range_max=10.0, ranges=ranges)
    msg.header.frame_id = frame
    return msg


def oriented(pose: Any, yaw: float) -> Any:
    """``pose`` turned to heading ``yaw``."""
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return pose


def odometry(x: float, y: float, yaw: float, frame: str = "laser") -> Any:
    """An Odometry at (x, y) facing ``yaw`` in ``frame``."""
    msg = Odometry()
    msg.header.frame_id = frame
    msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
    oriented(msg.pose.pose, yaw)
    return msg


def path(points: Sequence[tuple[float, float]], frame: str = "laser") -> Any:
    """A Path through ``points``."""
    msg = Path()
    msg.header.frame_id = frame
    for x, y in points:
        stamped = PoseStamped()
        stamped.pose.position.x, stamped.pose.position.y = x, y
        msg.poses.append(stamped)
    return msg


def pose_array(poses: Sequence[tuple[float, float, float]], frame: str = "laser") -> Any:
    """A PoseArray of (x, y, yaw)."""
    msg = PoseArray()
    msg.header.frame_id = frame
    for x, y, yaw in poses:
        pose = oriented(Pose(), yaw)
        pose.position.x, pose.position.y = x, y
        msg.poses.append(pose)
    return msg


def room(frame: str = "laser") -> Any:
    """An 8 m x 5 m OccupancyGrid (0.1 m cells) centred on the origin: occupied walls round a free floor."""
    width, height = 80, 50
    cells = np.zeros((height, width), dtype=np.int64)
    cells[[0, -1], :] = 100
    cells[:, [0, -1]] = 100
    cells[20:30, 55] = 100
    msg = OccupancyGrid(data=cells.ravel().tolist())
    msg.header.frame_id = frame
    msg.info.resolution, msg.info.width, msg.info.height = 0.1, width, height
    msg.info.origin.position.x, msg.info.origin.position.y = -4.0, -2.5
    msg.info.origin.orientation.w = 1.0
    return msg


def occupancy() -> Any:
    """A 4 x 2 grid of 0.5 m cells with its corner at (-1, 0): values 0 100 -1 0 / 0 0 0 70."""
    grid = OccupancyGrid()
    grid.header.frame_id = "map"
    grid.info.resolution = 0.5
    grid.info.width, grid.info.height = 4, 2
    grid.info.origin.position.x, grid.info.origin.position.y = -1.0, 0.0
    grid.info.origin.orientation.w = 1.0
    grid.data = [0, 100, -1, 0,
                 0, 0, 0, 70]
    return grid


def marker(kind: int, x: float = 0.0, y: float = 0.0, *, ident: int = 0, ns: str = "n", yaw: float = 0.0,
           scale: tuple[float, float] = (1.0, 1.0), points: tuple[tuple[float, float], ...] = (),
           rgb: tuple[float, float, float] = (1.0, 0.0, 0.0), alpha: float = 1.0, frame: str = "map",
           **fields: Any) -> Any:
    """A Marker added (action ADD) of ``kind`` at (``x``, ``y``) facing ``yaw``; other fields as given."""
    m = Marker(ns=ns, id=ident, type=kind, action=Marker.ADD)
    m.header.frame_id = frame
    m.pose.position.x, m.pose.position.y = x, y
    m.pose.orientation.z, m.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    m.scale.x, m.scale.y, m.scale.z = scale[0], scale[1], 1.0
    m.color = ColorRGBA(*rgb, alpha)
    m.points = [Point(px, py, 0.0) for px, py in points]
    for name, value in fields.items():
        setattr(m, name, value)
    return m


#: Real robot meshes (tests/mesh_corpus/SOURCES.md).
MESHES = pathlib.Path(__file__).parent / "mesh_corpus"


def every_marker_type(frame: str = "map") -> Any:
    """A MarkerArray with one marker of each type, laid out as tests/peers/rospy_markers.py lays them out (the
    mesh: turtlebot3's R200 camera, 0.13 m x 0.02 m, eight times its size)."""
    red, green, blue, yellow = (1.0, 0.2, 0.2), (0.2, 1.0, 0.2), (0.3, 0.5, 1.0), (1.0, 0.9, 0.1)
    return MarkerArray(markers=[
        marker(Marker.ARROW, -3, 2, ident=0, rgb=red, frame=frame),
        marker(Marker.CUBE, -1, 2, ident=1, rgb=green, scale=(1.0, 0.6), frame=frame),
        marker(Marker.SPHERE, 1, 2, ident=2, rgb=blue, frame=frame),
        marker(Marker.CYLINDER, 3, 2, ident=3, rgb=yellow, frame=frame),
        marker(Marker.LINE_STRIP, -3, 0, ident=4, rgb=red, points=((-0.5, 0), (0.5, 0)), frame=frame),
        marker(Marker.LINE_LIST, -1, 0, ident=5, rgb=green, frame=frame,
               points=((-0.5, -0.3), (0.5, -0.3), (-0.5, 0.3), (0.5, 0.3))),
        marker(Marker.CUBE_LIST, 1, 0, ident=6, rgb=blue, points=((0, 0), (0.3, 0)), frame=frame),
        marker(Marker.SPHERE_LIST, 3, 0, ident=7, rgb=yellow, points=((0, 0), (0, 0.3)), frame=frame),
        marker(Marker.POINTS, -3, -2, ident=8, rgb=green, points=((0, 0), (0.3, 0.3)), frame=frame,
               colors=[ColorRGBA(*red, 1.0), ColorRGBA(*blue, 1.0)]),
        marker(Marker.TEXT_VIEW_FACING, -1, -2, ident=9, rgb=yellow, text="hi", frame=frame),
        marker(Marker.MESH_RESOURCE, 1, -2, ident=10, rgb=blue, scale=(8.0, 8.0), frame=frame,
               mesh_resource=f"file://{MESHES / 'turtlebot3-r200.dae'}"),
        marker(Marker.TRIANGLE_LIST, 3, -2, ident=11, rgb=red, points=((0, 0), (0.6, 0), (0, 0.6)), frame=frame),
    ])


class ViewTestApp(App[None]):
    """One :class:`TopDownView` filling the screen, nothing else."""

    def __init__(self, topics: Sequence[str], frame: str | None = None, lookup: Lookup = same_frame_only,
                 show_rates: bool = True) -> None:
        super().__init__()
        self.topics, self.frame, self.lookup, self.show_rates = list(topics), frame, lookup, show_rates

    def compose(self) -> ComposeResult:
        """The view."""
        yield TopDownView(topics=self.topics, frame=self.frame, lookup=self.lookup, show_rates=self.show_rates)

    def on_mount(self) -> None:
        """The view has the keys."""
        self.query_one(TopDownView).focus()

    @property
    def view(self) -> TopDownView:
        """The view."""
        return self.query_one(TopDownView)


def scene_app(frame: str | None = None) -> ViewTestApp:
    """A room, a wall scan, odometry, a path and a pose array, all in "laser" (messages given at mount; no rates)."""
    app = ViewTestApp(["/map", "/scan", "/path", "/odom", "/poses"], frame=frame, show_rates=False)

    def feed() -> None:
        view = app.view
        view.show_topic_message("/map", room())
        view.show_topic_message("/scan", wall_scan(2.05, half_angle=40))
        view.show_topic_message("/path", path([(-3.0, -1.5), (-1.5, -1.5), (-0.5, -0.5), (0.0, 0.0)]))
        view.show_topic_message("/odom", odometry(0.0, 0.0, math.radians(30)))
        view.show_topic_message("/poses", pose_array([(-2.0, 1.5, 0.0), (-1.0, 1.5, math.pi / 2)]))

    app.call_after_refresh(feed)
    return app


def sync(test: Callable[..., Awaitable[None]]) -> Callable[..., None]:
    """A pilot test written as a coroutine, run to its end with asyncio.run (pytest sees a plain test)."""
    @functools.wraps(test)
    def run(*args: Any, **kwargs: Any) -> None:
        asyncio.run(test(*args, **kwargs))
    return run
