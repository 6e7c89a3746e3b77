"""Lookups through tf2_ros.BufferClient, asked of Debian's tf2 buffer server (tests/test_tf2_buffer_client.py).

The server's buffer holds world -> robot (static) and a second tree sea -> island; the probe prints the
transforms and the errors the server sends back, under Debian's tf2_ros and under rostui's.

Debian's BufferClient waits with actionlib's SimpleActionClient, which drops an answer that arrives before
send_goal has stored the goal's handle (ros/actionlib issue 206, never fixed) and then times out; it logs "Got a
transition callback on a goal handle that we're not tracking" when it does. A line made while that was logged
ends with RACE_MARK, so the test knows that line shows actionlib's race and not the server's answer.
"""

import logging

import rospy
import tf2_py
import tf2_ros

RACE_MARK = "[actionlib#206]"


class RaceWatch(logging.Handler):
    """Notes actionlib's complaint that it got an answer for a goal it is not tracking."""

    def __init__(self):
        super().__init__()
        self.seen = False

    def emit(self, record):
        if "goal handle that we're not tracking" in record.getMessage():
            self.seen = True


def show(t):
    v, q = t.transform.translation, t.transform.rotation
    return " ".join([t.header.frame_id, t.child_frame_id] + ["%.6f" % x for x in (v.x, v.y, v.z, q.x, q.y, q.z, q.w)])


def line(*words):
    """Prints one line of the probe's answer, marked when actionlib's race happened while it was made."""
    print(*words, *([RACE_MARK] if watch.seen else []))
    watch.seen = False


def lookup(label, ask):
    """Prints the transform *ask* returns, or the tf2 error it raises."""
    try:
        line(label, show(ask()))
    except tf2_py.TransformException as exc:
        line(label, "error", type(exc).__name__, isinstance(exc, tf2_ros.TransformException), exc)


rospy.init_node("buffer_client_probe")
watch = RaceWatch()
logging.getLogger("rosout").addHandler(watch)
client = tf2_ros.BufferClient("tf2_buffer_server")
line("server", client.wait_for_server(rospy.Duration(30)))
lookup("lookup", lambda: client.lookup_transform("world", "robot", rospy.Time(0), rospy.Duration(10)))
lookup("back", lambda: client.lookup_transform("robot", "world", rospy.Time(0)))
lookup("full", lambda: client.lookup_transform_full("robot", rospy.Time(0), "world", rospy.Time(0), "world"))
for target, source in (("world", "nowhere"), ("world", "island"), ("", "robot")):
    lookup("ask %s %s" % (target or "''", source),
           lambda: client.lookup_transform(target, source, rospy.Time(0), rospy.Duration(0.2)))
line("can", client.can_transform("robot", "world", rospy.Time(0)), client.can_transform("world", "island", rospy.Time(0)),
     client.can_transform_full("robot", rospy.Time(0), "world", rospy.Time(0), "world"))
