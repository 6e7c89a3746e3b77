"""rospy peer: print each rosgraph_msgs/Clock received on /clock, in nanoseconds.

Usage (system python): rospy_clock.py [ROS args]
Prints "subscribed" once registered, then one "clock <nsecs>" line per message, until shut down.
"""

import sys

import rospy
from rosgraph_msgs.msg import Clock


def main() -> int:
    rospy.init_node("rospy_clock", anonymous=True)
    rospy.Subscriber("/clock", Clock, lambda msg: print(f"clock {msg.clock.to_nsec()}", flush=True))
    print("subscribed", flush=True)
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
