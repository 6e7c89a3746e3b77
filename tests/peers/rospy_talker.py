"""rospy peer: publish std_msgs/String "hello N" once a subscriber connects.

Usage (system python): rospy_talker.py TOPIC COUNT HZ [ROS args]
Prints "connected" when the first subscriber appears, then "sent hello N".
"""

import sys

import rospy
from std_msgs.msg import String


def main() -> int:
    topic, count, hz = rospy.myargv()[1:4]
    count, hz = int(count), float(hz)
    rospy.init_node("rospy_talker", anonymous=True)
    pub = rospy.Publisher(topic, String, queue_size=max(10, count))
    while pub.get_num_connections() == 0:
        if rospy.is_shutdown():
            return 1
        rospy.sleep(0.05)
    print("connected", flush=True)
    rate = rospy.Rate(hz)
    for n in range(count):
        pub.publish(String(data=f"hello {n}"))
        print(f"sent hello {n}", flush=True)
        rate.sleep()
    rospy.sleep(1.0)  # let the queue drain before the connection closes
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except rospy.ROSInterruptException:
        sys.exit(1)
