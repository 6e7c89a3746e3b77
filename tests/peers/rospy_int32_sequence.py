"""rospy peer: print ``TOPIC VALUE`` for each std_msgs/Int32 received on any of TOPICS, exit after COUNT.

Usage (system python): rospy_int32_sequence.py COUNT TOPIC... [ROS args]
Prints "subscribed" once its subscribers are registered. One lock orders the
lines as the callbacks run (rospy runs each topic's callbacks on its own thread).
"""

import sys
import threading

import rospy
from std_msgs.msg import Int32


def main() -> int:
    args = rospy.myargv()[1:]
    count, topics = int(args[0]), args[1:]
    lock = threading.Lock()
    heard = []
    done = threading.Event()

    def printer(topic):
        def callback(msg):
            with lock:
                if len(heard) < count:
                    heard.append(msg.data)
                    print(f"{topic} {msg.data}", flush=True)
                    if len(heard) >= count:
                        done.set()
        return callback

    rospy.init_node("int32_sequence", anonymous=True)
    for topic in topics:
        rospy.Subscriber(topic, Int32, printer(topic), queue_size=1000)
    print("subscribed", flush=True)
    while not done.wait(0.05):
        if rospy.is_shutdown():
            return 1
    rospy.signal_shutdown("heard enough")
    return 0


if __name__ == "__main__":
    sys.exit(main())
