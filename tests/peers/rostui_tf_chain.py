"""rostui client peer: the same tf chain as rospy_tf_chain.py plus its static transform, over rostui's client.

Usage: rostui_tf_chain.py HZ [ROS args]
Publishes map->odom and odom->base_link on /tf at HZ, and base_link->laser once, latched, on
/tf_static (what a static_transform_publisher does). Prints "broadcasting" after the first round.
"""

import math
import sys

from rostui import client as ros

TFMessage = ros.msg("tf2_msgs/TFMessage")
TransformStamped = ros.msg("geometry_msgs/TransformStamped")

DYNAMIC = [
    ("map", "odom", (1.0, 2.0, 0.0), (0.0, 0.0, 0.5)),
    ("odom", "base_link", (0.5, -0.25, 0.1), (0.1, -0.2, 1.2)),
]
STATIC = [("base_link", "laser", (0.2, 0.0, 0.3), (math.pi, 0.0, -0.3))]


def quaternion(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def stamped(parent, child, xyz, rpy, stamp):
    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
    t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = quaternion(*rpy)
    return t


def main() -> int:
    hz = float(ros.myargv()[1])
    ros.init_node("rostui_tf_chain")
    static_pub = ros.Publisher("/tf_static", TFMessage, queue_size=10, latch=True)
    pub = ros.Publisher("/tf", TFMessage, queue_size=100)
    static_pub.publish(TFMessage(transforms=[stamped(*s, ros.Time.now()) for s in STATIC]))
    rate = ros.Rate(hz)
    said = False
    while not ros.is_shutdown():
        now = ros.Time.now()
        pub.publish(TFMessage(transforms=[stamped(*d, now) for d in DYNAMIC]))
        if not said:
            print("broadcasting", flush=True)
            said = True
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except ros.ROSInterruptException:
        sys.exit(0)
