"""A peer publishing one message of every top-down type at 10 Hz, all in frame "map" (ROS args accepted).

Usage: topdown_talker.py rospy    (system python: Debian's rospy and message packages)
       topdown_talker.py rostui   (project python: rostui's client)
Prints "ready" once every topic is advertised.  What is where (metres, frame "map"):
  /scan   LaserScan from the origin, beams -30..+30 degrees, a wall at x = 2.05
  /odom   Odometry at (-2.05, 1.05) facing +x
  /pose   PoseStamped at (-2.05, -1.05) facing -x
  /poses  PoseArray: (0.55, 1.8) and (1.55, 1.8), both facing +y
  /path   Path: a straight line from (-3.55, -2.05) to (-0.55, -2.05)
  /map    OccupancyGrid: 1 m x 0.5 m, every cell occupied, corner at (3.05, -2.55), 0.1 m cells
  /cloud  PointCloud2: 36 points on a circle of radius 0.53 about the origin (big-endian float64,
          x y z after a 4-byte rgb field, 4 bytes of padding), plus one NaN point
  /scan_laser  LaserScan in frame "laser", beams -30..+30 degrees, a wall 1.05 m ahead
  /tf_static   map -> laser: (1, 0, 0), yaw 90 degrees (latched), so that wall lies along y = 1.05 in "map"
  /move_base/local_costmap/footprint  PolygonStamped: a 0.6 m square centred on (-3, 0) (the name turtlebot3's
          navigation.rviz gives its Polygon display)
"""

import importlib
import math
import struct
import sys


def main(flavour: str) -> int:
    if flavour == "rostui":
        from rostui import client as ros
        message = ros.msg
    else:
        import rospy as ros

        def message(name):
            package, _, kind = name.partition("/")
            return getattr(importlib.import_module(package + ".msg"), kind)
    ros.init_node("topdown_talker", anonymous=True)
    LaserScan, Odometry, Path = message("sensor_msgs/LaserScan"), message("nav_msgs/Odometry"), message("nav_msgs/Path")
    PoseStamped, PoseArray, Pose = (message("geometry_msgs/PoseStamped"), message("geometry_msgs/PoseArray"),
                                    message("geometry_msgs/Pose"))
    OccupancyGrid, PointCloud2 = message("nav_msgs/OccupancyGrid"), message("sensor_msgs/PointCloud2")
    PointField = message("sensor_msgs/PointField")
    TFMessage, TransformStamped = message("tf2_msgs/TFMessage"), message("geometry_msgs/TransformStamped")

    def heading(pose, yaw):
        pose.orientation.z, pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        return pose

    angles = [math.radians(a) for a in range(-30, 31)]
    scan = LaserScan(angle_min=angles[0], angle_max=angles[-1], angle_increment=math.radians(1), range_min=0.1,
                     range_max=20.0, ranges=[2.05 / math.cos(a) for a in angles])
    odom = Odometry(child_frame_id="base_link")
    odom.pose.pose.position.x, odom.pose.pose.position.y = -2.05, 1.05
    heading(odom.pose.pose, 0.0)
    pose = PoseStamped()
    pose.pose.position.x, pose.pose.position.y = -2.05, -1.05
    heading(pose.pose, math.pi)
    poses = PoseArray()
    for x in (0.55, 1.55):
        p = heading(Pose(), math.pi / 2)
        p.position.x, p.position.y = x, 1.8
        poses.poses.append(p)
    path = Path()
    for i in range(7):
        stamped = PoseStamped()
        stamped.header.frame_id = "map"
        stamped.pose.position.x, stamped.pose.position.y = -3.55 + 0.5 * i, -2.05
        heading(stamped.pose, 0.0)
        path.poses.append(stamped)
    grid = OccupancyGrid(data=[100] * 50)
    grid.info.resolution, grid.info.width, grid.info.height = 0.1, 10, 5
    grid.info.origin.position.x, grid.info.origin.position.y = 3.05, -2.55
    grid.info.origin.orientation.w = 1.0
    points = [(0.53 * math.cos(math.radians(a)), 0.53 * math.sin(math.radians(a)), 0.0) for a in range(0, 360, 10)]
    points.append((float("nan"), float("nan"), 0.0))
    data = b"".join(b"\x10\x20\x30\x00" + struct.pack(">ddd", *p) + b"\0" * 4 for p in points)
    fields = [PointField(name="rgb", offset=0, datatype=6, count=1)]
    fields += [PointField(name=n, offset=4 + 8 * i, datatype=8, count=1) for i, n in enumerate("xyz")]
    cloud = PointCloud2(height=1, width=len(points), fields=fields, is_bigendian=True, point_step=32,
                        row_step=32 * len(points), data=data, is_dense=False)
    laser_scan = LaserScan(angle_min=angles[0], angle_max=angles[-1], angle_increment=math.radians(1),
                           range_min=0.1, range_max=20.0, ranges=[1.05 / math.cos(a) for a in angles])
    mount = TransformStamped(child_frame_id="laser")
    mount.header.frame_id = "map"
    mount.header.stamp = ros.Time.now()
    mount.transform.translation.x = 1.0
    mount.transform.rotation.z, mount.transform.rotation.w = math.sin(math.pi / 4), math.cos(math.pi / 4)
    static = ros.Publisher("/tf_static", TFMessage, queue_size=1, latch=True)
    static.publish(TFMessage(transforms=[mount]))
    PolygonStamped, Point32 = message("geometry_msgs/PolygonStamped"), message("geometry_msgs/Point32")
    footprint = PolygonStamped()
    footprint.polygon.points = [Point32(x, y, 0.0) for x, y in ((-2.7, 0.3), (-2.7, -0.3), (-3.3, -0.3), (-3.3, 0.3))]
    messages = {"/scan": scan, "/odom": odom, "/pose": pose, "/poses": poses, "/path": path, "/map": grid,
                "/cloud": cloud, "/move_base/local_costmap/footprint": footprint}
    publishers = {}
    for topic, msg in messages.items():
        msg.header.frame_id = "map"
        publishers[topic] = ros.Publisher(topic, type(msg), queue_size=1)
    laser_scan.header.frame_id = "laser"
    messages["/scan_laser"] = laser_scan
    publishers["/scan_laser"] = ros.Publisher("/scan_laser", LaserScan, queue_size=1)
    print("ready", flush=True)
    rate = ros.Rate(10)
    while not ros.is_shutdown():
        for topic, msg in messages.items():
            msg.header.stamp = ros.Time.now()
            publishers[topic].publish(msg)
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1]))
    except Exception as exc:  # rospy's and rostui's interrupt exceptions on Ctrl-C
        if type(exc).__name__ == "ROSInterruptException":
            sys.exit(0)
        raise
