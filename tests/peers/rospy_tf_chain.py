"""rospy peer: broadcast map -> odom -> base_link with tf2_ros.TransformBroadcaster.

Usage (system python): rospy_tf_chain.py HZ [ROS args]
The transforms are tests/tf_chain.py's CHAIN (map->odom and odom->base_link); base_link->laser
comes from a static publisher the test starts. Prints "broadcasting" once the first is sent.
"""

import math
import sys

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped

# parent, child, translation, roll/pitch/yaw: the same numbers as tests/tf_chain.py
DYNAMIC = [
    ("map", "odom", (1.0, 2.0, 0.0), (0.0, 0.0, 0.5)),
    ("odom", "base_link", (0.5, -0.25, 0.1), (0.1, -0.2, 1.2)),
]


def quaternion(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def main() -> int:
    hz = float(rospy.myargv()[1])
    rospy.init_node("rospy_tf_chain")
    broadcaster = tf2_ros.TransformBroadcaster()
    rate = rospy.Rate(hz)
    said = False
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        for parent, child, xyz, rpy in DYNAMIC:
            t = TransformStamped()
            t.header.stamp = now
            t.header.frame_id = parent
            t.child_frame_id = child
            t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
            q = quaternion(*rpy)
            t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = q
            broadcaster.sendTransform(t)
        if not said:
            print("broadcasting", flush=True)
            said = True
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except rospy.ROSInterruptException:
        sys.exit(0)
