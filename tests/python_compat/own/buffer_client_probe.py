"""Lookups through tf2_ros.BufferClient, asked of Debian's tf2 buffer server (tests/test_tf2_buffer_client.py).

The server's buffer holds world -> robot (static) and a second tree sea -> island; the probe prints the
transforms and the errors the server sends back, under Debian's tf2_ros and under rostui's.
"""

import rospy
import tf2_py
import tf2_ros


def show(t):
    v, q = t.transform.translation, t.transform.rotation
    return " ".join([t.header.frame_id, t.child_frame_id] + ["%.6f" % x for x in (v.x, v.y, v.z, q.x, q.y, q.z, q.w)])


rospy.init_node("buffer_client_probe")
client = tf2_ros.BufferClient("tf2_buffer_server")
print("server", client.wait_for_server(rospy.Duration(30)))
print("lookup", show(client.lookup_transform("world", "robot", rospy.Time(0), rospy.Duration(10))))
print("back", show(client.lookup_transform("robot", "world", rospy.Time(0))))
print("full", show(client.lookup_transform_full("robot", rospy.Time(0), "world", rospy.Time(0), "world")))
for target, source in (("world", "nowhere"), ("world", "island"), ("", "robot")):
    try:
        client.lookup_transform(target, source, rospy.Time(0), rospy.Duration(0.2))
    except tf2_py.TransformException as exc:
        print("error", type(exc).__name__, isinstance(exc, tf2_ros.TransformException), exc)
print("can", client.can_transform("robot", "world", rospy.Time(0)), client.can_transform("world", "island", rospy.Time(0)),
      client.can_transform_full("robot", rospy.Time(0), "world", rospy.Time(0), "world"))
