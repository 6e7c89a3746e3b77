"""Top-down geometry without a terminal: messages -> points, poses, grids, braille dots in a fixed frame."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest

from rostui.core.msg import get_message_class
from rostui.models.sensors.canvas2d import BRAILLE_BASE, BrailleCanvas, Viewport, nice_step
from rostui.models.sensors.cloud2d import CloudError, cloud_points
from rostui.models.sensors.grid2d import grid_of
from rostui.models.sensors.pose2d import Pose2D, yaw_of
from rostui.models.sensors.poses2d import odometry_pose, path_points, pose_array_poses
from rostui.models.sensors.scan2d import scan_points
from rostui.models.sensors.scene2d import Scene2D
from topdown_helpers import occupancy, wall_scan

LaserScan = get_message_class("sensor_msgs/LaserScan")
PointCloud2 = get_message_class("sensor_msgs/PointCloud2")
PointField = get_message_class("sensor_msgs/PointField")
Odometry = get_message_class("nav_msgs/Odometry")
Path = get_message_class("nav_msgs/Path")
PoseStamped = get_message_class("geometry_msgs/PoseStamped")
PoseArray = get_message_class("geometry_msgs/PoseArray")
Pose = get_message_class("geometry_msgs/Pose")
OccupancyGrid = get_message_class("nav_msgs/OccupancyGrid")


def quaternion(yaw: float) -> tuple[float, float, float, float]:
    return 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)


def test_scan_points_put_the_wall_at_x_2_and_skip_missing_returns() -> None:
    pts = scan_points(wall_scan(2.0))
    assert len(pts) == 89
    assert np.allclose(pts[:, 0], 2.0)
    assert pts[0, 1] == pytest.approx(-2.0) and pts[-1, 1] == pytest.approx(2.0)


def test_odometry_pose_and_yaw() -> None:
    odom = Odometry()
    odom.pose.pose.position.x, odom.pose.pose.position.y = 1.5, -0.5
    o = odom.pose.pose.orientation
    o.x, o.y, o.z, o.w = quaternion(math.pi / 2)
    pose = odometry_pose(odom)
    assert (pose.x, pose.y) == (1.5, -0.5) and pose.yaw == pytest.approx(math.pi / 2)
    assert yaw_of(Pose().orientation) == 0.0


def test_path_and_pose_array() -> None:
    path = Path()
    for i in range(3):
        ps = PoseStamped()
        ps.pose.position.x = float(i)
        ps.pose.position.y = float(i * i)
        path.poses.append(ps)
    assert path_points(path).tolist() == [[0, 0], [1, 1], [2, 4]]
    arr = PoseArray(poses=[Pose(), Pose()])
    arr.poses[1].position.x = 3.0
    assert [p.x for p in pose_array_poses(arr)] == [0.0, 3.0]


def test_pose2d_compose_inverse_and_apply() -> None:
    a = Pose2D(1.0, 2.0, math.pi / 2)
    assert np.allclose(a.apply(np.array([[1.0, 0.0]])), [[1.0, 3.0]])
    b = a.compose(a.inverse())
    assert (b.x, b.y, b.yaw) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


def cloud(points: list[tuple[float, float, float]], *, big_endian: bool, datatype: int, pad: int,
          row_pad: int = 0, height: int = 1) -> object:
    """A PointCloud2 with x, y, z of ``datatype`` behind a 3-byte leading field and ``pad`` trailing bytes."""
    codes = {7: "f", 8: "d", 3: "h", 5: "i"}
    size = struct.calcsize(codes[datatype])
    fields = [PointField(name="intensity", offset=0, datatype=2, count=3)]
    fields += [PointField(name=n, offset=3 + i * size, datatype=datatype, count=1) for i, n in enumerate("xyz")]
    step = 3 + 3 * size + pad
    width = len(points) // height
    order = ">" if big_endian else "<"
    data = b""
    for r in range(height):
        for p in points[r * width:(r + 1) * width]:
            data += b"\x01\x02\x03" + struct.pack(order + codes[datatype] * 3, *p) + b"\0" * pad
        data += b"\xee" * row_pad
    return PointCloud2(height=height, width=width, fields=fields, is_bigendian=big_endian, point_step=step,
                       row_step=width * step + row_pad, data=data, is_dense=False)


@pytest.mark.parametrize("big_endian", [False, True])
@pytest.mark.parametrize("datatype", [7, 8])
def test_cloud_points_any_layout_skips_nans(big_endian: bool, datatype: int) -> None:
    pts = [(1.0, 2.0, 0.5), (float("nan"), 1.0, 0.0), (-3.0, 0.25, 9.0), (4.0, float("inf"), 1.0)]
    xy = cloud_points(cloud(pts, big_endian=big_endian, datatype=datatype, pad=5))
    assert xy.tolist() == [[1.0, 2.0], [-3.0, 0.25]]


def test_cloud_points_integer_fields_and_row_padding() -> None:
    pts = [(1, 2, 0), (3, 4, 0), (5, 6, 0), (7, 8, 0)]
    xy = cloud_points(cloud(pts, big_endian=True, datatype=3, pad=0, row_pad=7, height=2))  # type: ignore[arg-type]
    assert xy.tolist() == [[1, 2], [3, 4], [5, 6], [7, 8]]


def test_cloud_without_y_or_short_data_is_a_clear_error() -> None:
    msg = cloud([(1.0, 2.0, 3.0)], big_endian=False, datatype=7, pad=0)
    msg.fields = [f for f in msg.fields if f.name != "y"]
    with pytest.raises(CloudError, match="no y field"):
        cloud_points(msg)
    msg = cloud([(1.0, 2.0, 3.0)] * 4, big_endian=False, datatype=7, pad=0)
    msg.data = msg.data[:-1]
    with pytest.raises(CloudError, match="bytes of data"):
        cloud_points(msg)


def test_grid_samples_cells_by_position() -> None:
    g = grid_of(occupancy())
    probe = np.array([[-0.25, 0.25], [0.1, 0.1], [0.75, 0.75], [5.0, 5.0]])
    assert g.sample(probe).tolist() == [100, -1, 70, -1]
    assert g.occupied(probe).tolist() == [True, False, True, False]


def test_braille_dots_bits_and_cells() -> None:
    view = Viewport(cols=4, rows=2, scale=1.0)  # 8 x 8 dots, centre at dot (4, 4)
    canvas = BrailleCanvas(view, 1)
    canvas.points(0, np.array([[0.5, 0.5], [-3.5, 3.5]]))  # dot (4, 3) and dot (0, 0)
    bits, top = canvas.compose()
    assert bits[0, 2] == 0x40 and bits[0, 0] == 0x01
    assert top[0, 2] == 0 and top[1, 1] == -1
    assert chr(BRAILLE_BASE + int(bits[0, 0])) == "⠁"


def test_segments_are_clipped_to_the_canvas() -> None:
    view = Viewport(cols=4, rows=2, scale=1.0)
    canvas = BrailleCanvas(view, 1)
    canvas.segments(0, np.array([[-100.0, 0.25]]), np.array([[100.0, 0.25]]))
    bits, _ = canvas.compose()
    assert (bits[0] == 0x40 | 0x80).all() and (bits[1] == 0).all()


def test_nice_step() -> None:
    assert [nice_step(v) for v in (0.3, 1.0, 1.2, 3.0, 7.0, 0.07)] == pytest.approx([0.5, 1.0, 2.0, 5.0, 10.0, 0.1])


def test_scene_draws_in_the_first_frame_and_notes_missing_transforms() -> None:
    scene = Scene2D(["/scan", "/odom"])
    scene.offer("/scan", wall_scan(2.0, "laser"))
    odom = Odometry()
    odom.header.frame_id = "odom"
    scene.offer("/odom", odom)
    assert scene.fixed_frame == "laser"
    assert scene.note("/scan") == ""
    assert scene.note("/odom") == "no transform from odom to laser"
    view = Viewport(cols=40, rows=10, cx=0.05, scale=0.1)  # 80 x 40 dots, 8 m x 4 m; x = 2 m mid-dot
    canvas = scene.render(view)
    layer = canvas.bits[1]
    wall_col = view.cell_of(2.0, 0.0)
    assert wall_col is not None
    assert set(np.nonzero(layer)[1].tolist()) == {wall_col[0]}
    assert not canvas.bits[2].any()


def test_scene_with_a_lookup_moves_drawings_into_the_fixed_frame() -> None:
    poses = {("map", "laser"): Pose2D(1.0, 0.0, 0.0)}
    scene = Scene2D(["/scan"], fixed_frame="map", lookup=lambda t, s: poses.get((t, s)))
    scene.offer("/scan", wall_scan(2.0, "laser"))
    view = Viewport(cols=40, rows=10, cx=0.05, scale=0.1)
    bits = scene.render(view).bits[1]
    cell = view.cell_of(3.0, 0.0)
    assert cell is not None and set(np.nonzero(bits)[1].tolist()) == {cell[0]}


def test_scene_occupancy_layer_and_unreadable_message_note() -> None:
    scene = Scene2D(["/map"])
    scene.offer("/map", occupancy())
    view = Viewport(cols=8, rows=2, scale=0.125)  # 16 x 8 dots, 2 m x 1 m
    bits = scene.render(view).bits[1]
    assert bits.any()
    bad = occupancy()
    bad.data = [0]
    scene.offer("/map", bad)
    assert scene.note("/map") == "cannot draw: 1 cells of data for a 4 x 2 grid"


def test_buffer_lookup_projects_a_tf_chain_onto_the_plane() -> None:
    from rostui.models.sensors.tf_lookup import buffer_lookup
    from rostui.tools.tf.buffer import TfBuffer
    from rostui.tools.tf.buffer import stamp_ns as ns
    from rostui.tools.tf.transform import Transform

    buffer = TfBuffer()
    half = math.pi / 4
    buffer.set_transform("map", "odom", Transform.of((1.0, 0.0, 0.0), (0, 0, math.sin(half), math.cos(half))), ns(10.0),
                         static=False, broadcaster="/test", received=10.0)
    buffer.set_transform("odom", "laser", Transform.of((0.5, 0.0, 0.2), (0, 0, 0, 1)), ns(0.0), static=True,
                         broadcaster="/test", received=10.0)
    lookup = buffer_lookup(buffer)
    where = lookup("map", "laser")
    assert where is not None
    pose = where.pose(Pose2D())
    assert (pose.x, pose.y, pose.yaw) == pytest.approx((1.0, 0.5, math.pi / 2))
    assert lookup("map", "nowhere") is None
    scene = Scene2D(["/scan"], fixed_frame="map", lookup=lookup)
    scene.offer("/scan", wall_scan(2.0, "laser"))
    assert scene.note("/scan") == ""
    assert np.allclose(scene.world_points()[:, 1], 2.5)  # the wall, 2 m ahead of a laser facing +y at y 0.5


def test_an_upside_down_laser_is_drawn_mirrored() -> None:
    """roll 180 degrees: a return to the scanner's left (+y) lies to the right (-y) of the base."""
    from rostui.models.sensors.tf_lookup import buffer_lookup
    from rostui.tools.tf.buffer import TfBuffer
    from rostui.tools.tf.buffer import stamp_ns as ns
    from rostui.tools.tf.transform import Transform

    buffer = TfBuffer()
    buffer.set_transform("base_link", "laser", Transform.of((0.2, 0.0, 0.3), (1.0, 0.0, 0.0, 0.0)), ns(0.0),
                         static=True, broadcaster="/test", received=0.0)
    where = buffer_lookup(buffer)("base_link", "laser")
    assert where is not None
    assert np.allclose(where.apply(np.array([[1.0, 1.0]])), [[1.2, -1.0]])
    pose = where.pose(Pose2D(0.0, 0.0, math.pi / 2))
    assert pose.yaw == pytest.approx(-math.pi / 2)
    inverse = where.inverse()
    assert inverse is not None and np.allclose(inverse.apply(np.array([[1.2, -1.0]])), [[1.0, 1.0]])
