"""rostopic's and rosservice's Python functions and genpy's fill_message_args, asked the same questions
under Debian's rospy and under `rostui python` (tests/test_rostopic_module.py compares what they print)."""

import sys

import genpy.message
import rospy
import rosservice
import rostopic
from nav_msgs.msg import Odometry
from std_srvs.srv import Trigger, TriggerResponse


def show(label, call):
    try:
        value = call()
    except Exception as exc:  # the failures are answers too
        print(label, "!!", type(exc).__name__, str(exc).replace("\n", " | "))
        return
    print(label, "->", value)


def main():
    rospy.init_node("lookups")
    pub = rospy.Publisher("/odom", Odometry, queue_size=1, latch=True)
    msg = Odometry()
    msg.pose.pose.position.x = 1.5
    msg.twist.twist.angular.z = -0.25
    pub.publish(msg)
    rospy.Service("~trigger", Trigger, lambda req: TriggerResponse(True, "ok"))
    for topic in ("/odom", "/odom/pose/pose/position", "/odom/twist/twist/angular/z", "/odom/nothing", "/none"):
        cls, real, pick = rostopic.get_topic_class(topic)
        picked = None if pick is None else pick(msg)
        print(topic, "->", None if cls is None else cls._type, real, str(picked).replace("\n", " "))
    show("_get_topic_type", lambda: rostopic._get_topic_type("/odom/pose")[:2])
    show("get_topic_type", lambda: rostopic.get_topic_type("/odom")[:2])
    show("service class", lambda: rosservice.get_service_class_by_name("/lookups/trigger")._type)
    show("service type", lambda: rosservice.get_service_type("/lookups/trigger"))
    show("missing service", lambda: rosservice.get_service_class_by_name("/nope"))
    show("service list", lambda: [s for s in rosservice.get_service_list() if s.startswith("/lookups/")])
    filled = Odometry()
    genpy.message.fill_message_args(filled, [{"header": {"frame_id": "odom", "stamp": "now"},
                                              "pose": {"pose": {"position": {"x": 2.5}}}}],
                                    keys={"now": rospy.Time(7, 8)})
    print("filled", filled.header.frame_id, filled.header.stamp.secs, filled.header.stamp.nsecs,
          filled.pose.pose.position.x)
    show("unknown field", lambda: genpy.message.fill_message_args(Odometry(), [{"posture": {}}]))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
