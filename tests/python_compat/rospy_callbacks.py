"""Subscriber callbacks as rospy runs them: each subscriber's on a thread of its own, free to block.

A callback that sleeps, makes a Publisher and publishes from there (as ROS Robotics By Example's
turtlesim_joy.py does), one that raises, and one that hears the first one's answer. Lines starting with
"= " must be the same under rostui's rospy and Debian's.
"""

import threading

import rospy
from std_msgs.msg import String

rospy.init_node("callbacks")
echoed = threading.Event()
main_thread = threading.current_thread()


def on_chatter(msg):
    if rospy.is_shutdown():
        return  # a late delivery while the script ends (Debian's rospy under load): stdout may be closed already
    print("= chatter callback on the main thread:", threading.current_thread() is main_thread, flush=True)
    pub = rospy.Publisher("echoed", String, queue_size=1, latch=True)
    rospy.sleep(0.5)  # blocks this subscriber's callbacks only
    pub.publish(String(msg.data.upper()))


def on_echoed(msg):
    print("= echoed:", msg.data, flush=True)
    echoed.set()


def bad(msg):
    raise ValueError("boom " + msg.data)


rospy.Subscriber("echoed", String, on_echoed)
# bad first: a topic's callbacks run in the order they were added, on one thread, so its error is logged
# before on_chatter publishes the answer that lets this script end (the other way round the script could end
# before rospy logged it).
rospy.Subscriber("chatter", String, bad)
rospy.Subscriber("chatter", String, on_chatter)
talk = rospy.Publisher("chatter", String, queue_size=1, latch=True)
talk.publish(String("hello"))
print("= heard back:", echoed.wait(30), flush=True)
rospy.signal_shutdown("done")
