"""rospy peer: publish the same sensor_msgs/Image on /image and geometry_msgs/PointStamped on /point at 10 Hz.

Usage (system python): rospy_shapes_talker.py [ROS args]
The image: stamp 1700000000.000000123, frame "cam", 2x2 mono8, data bytes 0 1 2 255.
The point: stamp 5.5 s, x NaN, y +inf, z -1.5.  Prints "ready" once both are advertised.
"""

import sys

import rospy
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import Image


def main() -> int:
    rospy.init_node("shapes_talker", anonymous=True)
    image_pub = rospy.Publisher("/image", Image, queue_size=10)
    point_pub = rospy.Publisher("/point", PointStamped, queue_size=10)
    image = Image(height=2, width=2, encoding="mono8", is_bigendian=0, step=2, data=bytes([0, 1, 2, 255]))
    image.header.stamp = rospy.Time(1700000000, 123)
    image.header.frame_id = "cam"
    point = PointStamped()
    point.header.stamp = rospy.Time(5, 500000000)
    point.point.x, point.point.y, point.point.z = float("nan"), float("inf"), -1.5
    print("ready", flush=True)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        image_pub.publish(image)
        point_pub.publish(point)
        rate.sleep()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except rospy.ROSInterruptException:
        sys.exit(0)
