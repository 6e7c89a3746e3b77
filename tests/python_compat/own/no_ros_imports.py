"""What a robot script imports beyond rospy, run by `rostui python` on a machine with no ROS.

.ci/run runs it before it installs Debian's ROS and compares what it prints with no_ros_imports.expected;
tests/test_python_no_ros.py runs it on any machine and checks that every module came from rostui.
"""

import sys

import actionlib
import cv_bridge
import dynamic_reconfigure.client
import message_filters
import numpy as np
import rospy
import tf
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from dynamic_reconfigure.cfg import TestConfig
from geometry_msgs.msg import TransformStamped
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
from visualization_msgs.msg import Marker

marker = Marker(type=Marker.ARROW, ns="demo", id=3)
print("marker", marker._type, marker._md5sum, marker.ns, marker.id)
print("action", MoveBaseAction._type, type(MoveBaseAction().action_goal.goal) is MoveBaseGoal,
      actionlib.GoalStatus.to_string(GoalStatus.SUCCEEDED))
buffer = tf2_ros.Buffer(debug=False)
t = TransformStamped()
t.header.frame_id, t.child_frame_id = "map", "base_link"
t.header.stamp = rospy.Time(10)
t.transform.translation.x = 2.0
t.transform.rotation.w = 1.0
buffer.set_transform(t, "test")
print("tf2", buffer.lookup_transform("map", "base_link", rospy.Time(0)).transform.translation.x)
print("tf", [round(float(v), 6) for v in tf.transformations.quaternion_from_euler(0, 0, 1.0)])
image = cv_bridge.CvBridge().cv2_to_imgmsg(np.arange(12, dtype=np.uint8).reshape(2, 2, 3), "rgb8")
print("cv_bridge", image.encoding, image.step, [int(v) for v in cv_bridge.CvBridge().imgmsg_to_cv2(image, "bgr8")[0, 0]])
print("filters", message_filters.Cache.__name__)
print("reconfigure", dynamic_reconfigure.client.Client.__name__, TestConfig.Test_Medium, TestConfig.max["int_"])
ros_modules = ("actionlib", "cv_bridge", "dynamic_reconfigure.client", "message_filters", "rospy", "tf", "tf2_ros",
               "tf2_py", "tf.transformations")
if "--origins" in sys.argv:
    for name in ros_modules:
        print("origin", name, sys.modules[name].__file__)
    for name in ("actionlib_msgs.msg", "move_base_msgs.msg", "visualization_msgs.msg"):
        print("origin", name, sys.modules[name].__loader__.__class__.__module__)
