"""A rospy peer publishing one visualization_msgs/Marker of every type on /markers (a latched MarkerArray, frame
"map"), as a navigation or perception node would.

Usage: rospy_markers.py TRIGGER_FILE    (system python: Debian's rospy and visualization_msgs)
Prints "ready" once the array is published.  When TRIGGER_FILE appears it publishes a DELETEALL marker and
prints "deleted all".  What is where (metres, frame "map"; see tests/test_markers_live.py MARKER_SPOTS):
  row y = 2:   ARROW at x=-3 (1 m along +x), CUBE at -1 (1 x 0.6), SPHERE at 1 (1 m), CYLINDER at 3 (1 m)
  row y = 0:   LINE_STRIP at -3, LINE_LIST at -1, CUBE_LIST at 1, SPHERE_LIST at 3
  row y = -2:  POINTS at -3 (one red, one blue), TEXT "hi" at -1, MESH_RESOURCE at 1 (0.8 m), TRIANGLE_LIST at 3
  ns "short": a CUBE at (0, -1) with a lifetime of 2 s
"""

import os
import sys
import time

import rospy
from geometry_msgs.msg import Point
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray


def marker(ident, kind, x, y, rgb, scale=(1.0, 1.0, 1.0), points=(), colors=(), text="", ns="every_type"):
    m = Marker()
    m.header.frame_id = "map"
    m.header.stamp = rospy.Time.now()
    m.ns, m.id, m.type, m.action = ns, ident, kind, Marker.ADD
    m.pose.position.x, m.pose.position.y = x, y
    m.pose.orientation.w = 1.0
    m.scale.x, m.scale.y, m.scale.z = scale
    m.color = ColorRGBA(rgb[0], rgb[1], rgb[2], 1.0)
    m.points = [Point(px, py, 0.0) for px, py in points]
    m.colors = [ColorRGBA(r, g, b, 1.0) for r, g, b in colors]
    m.text = text
    if kind == Marker.MESH_RESOURCE:
        m.mesh_resource = "package://robot/meshes/base.dae"
    return m


def main(trigger):
    rospy.init_node("markers", anonymous=True)
    pub = rospy.Publisher("/markers", MarkerArray, queue_size=10, latch=True)
    red, green, blue, yellow = (1.0, 0.2, 0.2), (0.2, 1.0, 0.2), (0.3, 0.5, 1.0), (1.0, 0.9, 0.1)
    every = [
        marker(0, Marker.ARROW, -3, 2, red),
        marker(1, Marker.CUBE, -1, 2, green, scale=(1.0, 0.6, 0.5)),
        marker(2, Marker.SPHERE, 1, 2, blue),
        marker(3, Marker.CYLINDER, 3, 2, yellow),
        marker(4, Marker.LINE_STRIP, -3, 0, red, scale=(0.05, 0, 0), points=[(-0.5, 0), (0.5, 0)]),
        marker(5, Marker.LINE_LIST, -1, 0, green, scale=(0.05, 0, 0),
               points=[(-0.5, -0.3), (0.5, -0.3), (-0.5, 0.3), (0.5, 0.3)]),
        marker(6, Marker.CUBE_LIST, 1, 0, blue, scale=(0.1, 0.1, 0.1), points=[(0, 0), (0.3, 0)]),
        marker(7, Marker.SPHERE_LIST, 3, 0, yellow, scale=(0.1, 0.1, 0.1), points=[(0, 0), (0, 0.3)]),
        marker(8, Marker.POINTS, -3, -2, green, scale=(0.05, 0.05, 0), points=[(0, 0), (0.3, 0.3)],
               colors=[red, blue]),
        marker(9, Marker.TEXT_VIEW_FACING, -1, -2, yellow, scale=(0, 0, 0.3), text="hi"),
        marker(10, Marker.MESH_RESOURCE, 1, -2, blue, scale=(0.8, 0.8, 0.8)),
        marker(11, Marker.TRIANGLE_LIST, 3, -2, red, points=[(0, 0), (0.6, 0), (0, 0.6)]),
    ]
    short = marker(0, Marker.CUBE, 0, -1, green, scale=(0.4, 0.4, 0.4), ns="short")
    short.lifetime = rospy.Duration(2.0)
    pub.publish(MarkerArray(markers=every + [short]))
    print("ready", flush=True)
    while not os.path.exists(trigger) and not rospy.is_shutdown():
        time.sleep(0.05)
    clear = Marker()
    clear.action = Marker.DELETEALL
    pub.publish(MarkerArray(markers=[clear]))
    print("deleted all", flush=True)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main(rospy.myargv(sys.argv)[1]))
