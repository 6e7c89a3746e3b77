"""rospy peer: print the data of each std_msgs/String received, exit after COUNT.

Usage (system python): rospy_listener.py TOPIC COUNT [ROS args]
Prints "subscribed" once registered, then one "data: <text>" line per message.
"""

import sys
import threading

import rospy
from std_msgs.msg import String


def main() -> int:
    topic, count = rospy.myargv()[1:3]
    count = int(count)
    done = threading.Event()
    heard = []

    def callback(msg):
        if len(heard) < count:
            heard.append(msg.data)
            print(f"data: {msg.data}", flush=True)
            if len(heard) >= count:
                done.set()

    rospy.init_node("rospy_listener", anonymous=True)
    rospy.Subscriber(topic, String, callback)
    print("subscribed", flush=True)
    while not done.wait(0.05):
        if rospy.is_shutdown():
            return 1
    rospy.signal_shutdown("heard enough")
    return 0


if __name__ == "__main__":
    sys.exit(main())
